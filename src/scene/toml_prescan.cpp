#include "scene/toml_prescan.h"

#include "scene/limits.h"

#include <spindrift/scene.h>

#include <fmt/format.h>

#include <cstddef>

namespace spindrift::scene {

namespace {

class Scanner {
public:
    Scanner(std::string_view text, const std::string& file) : text_(text), file_(file) {}

    void run() {
        while (i_ < text_.size()) {
            const char c = text_[i_];
            switch (c) {
                case '#':
                    skipComment();
                    break;
                case '"':
                    skipString('"', true);
                    break;
                case '\'':
                    skipString('\'', false);
                    break;
                case '[':
                case '{':
                    if (++depth_ > kMaxTomlNesting) {
                        fail(fmt::format("arrays, inline tables and table headers nested more than {} "
                                         "deep (the limit; a scene needs a few levels, and deeper "
                                         "nesting costs the TOML parser stack)",
                                         kMaxTomlNesting));
                    }
                    endChain();
                    advance();
                    break;
                case ']':
                case '}':
                    if (depth_ > 0) {
                        --depth_;
                    }
                    endChain();
                    advance();
                    break;
                case '=':
                case ',':
                    endChain();
                    advance();
                    break;
                case '.':
                    // A dot outside strings and comments separates the parts of
                    // a key (a value has at most one, as in 1.5).
                    if (++dots_ >= kMaxKeyParts) {
                        fail(fmt::format("a dotted key or table header with more than {} parts (the "
                                         "limit; the TOML parser reads each part with one more "
                                         "level of recursion)",
                                         kMaxKeyParts));
                    }
                    advance();
                    break;
                default:
                    advance();
                    break;
            }
        }
    }

private:
    [[noreturn]] void fail(const std::string& message) const {
        throw SceneError(file_, line_, column_, "", message);
    }

    void endChain() { dots_ = 0; }

    // Moves past text_[i_], keeping line and column (columns count UTF-8
    // code points, as toml++'s do); the byte that would pass the size or the
    // line limit is an error at its own position.
    void advance() {
        const char c = text_[i_];
        if (i_ >= kMaxSceneBytes) {
            fail(fmt::format("the scene is longer than {} bytes (the limit); it was not read past here",
                             kMaxSceneBytes));
        }
        if (c == '\n') {
            ++line_;
            column_ = 1;
            lineStart_ = i_ + 1;
            endChain();
        } else {
            if (i_ - lineStart_ >= kMaxSceneLineBytes) {
                fail(fmt::format("a line longer than {} bytes (the limit)", kMaxSceneLineBytes));
            }
            if ((static_cast<unsigned char>(c) & 0xC0u) != 0x80u) {
                ++column_;
            }
        }
        ++i_;
    }

    bool startsWith(std::string_view s) const { return text_.substr(i_, s.size()) == s; }

    void skipComment() {
        while (i_ < text_.size() && text_[i_] != '\n') {
            advance();
        }
    }

    // A string starting at i_; `escapes` for basic strings ("\"" does not end one).
    // An unterminated single-line string ends at the line's end (toml++
    // reports it).
    void skipString(char quote, bool escapes) {
        const std::string triple(3, quote);
        if (startsWith(triple)) {
            for (int k = 0; k < 3; ++k) {
                advance();
            }
            while (i_ < text_.size() && !startsWith(triple)) {
                if (escapes && text_[i_] == '\\' && i_ + 1 < text_.size()) {
                    advance();
                }
                advance();
            }
            // Up to two more quotes may close the string ("""a""""" is "a""").
            for (int k = 0; k < 5 && i_ < text_.size() && text_[i_] == quote; ++k) {
                advance();
            }
            return;
        }
        advance();
        while (i_ < text_.size() && text_[i_] != quote && text_[i_] != '\n') {
            if (escapes && text_[i_] == '\\' && i_ + 1 < text_.size() && text_[i_ + 1] != '\n') {
                advance();
            }
            advance();
        }
        if (i_ < text_.size() && text_[i_] == quote) {
            advance();
        }
    }

    std::string_view text_;
    const std::string& file_;
    std::size_t i_ = 0;
    std::size_t lineStart_ = 0;
    int line_ = 1;
    int column_ = 1;
    int depth_ = 0;
    int dots_ = 0;
};

}  // namespace

void prescanToml(std::string_view text, const std::string& sourceName) {
    Scanner(text, sourceName).run();
}

}  // namespace spindrift::scene
