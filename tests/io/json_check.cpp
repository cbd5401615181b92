// A strict JSON reader (RFC 8259) for tests, written independently of the
// program's JSON writer so that the tests judge its output instead of
// repeating it. Used by tests/io and tests/apps, which declare:
//
//   namespace spindrift_test {
//   std::string jsonError(std::string_view text);
//   std::optional<std::string> jsonQuery(std::string_view text, std::string_view path);
//   }
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace spindrift_test {

namespace {

struct Value {
    enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
    std::string text;  // number as written, decoded string, "true"/"false"
    std::vector<Value> items;
    std::vector<std::pair<std::string, Value>> members;
};

class Parser {
public:
    explicit Parser(std::string_view text) : s_(text) {}

    Value document() {
        Value v = value();
        skipSpace();
        if (i_ != s_.size()) fail("trailing characters");
        return v;
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(what + " at byte " + std::to_string(i_));
    }
    char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
    void expect(char c) {
        if (peek() != c) fail(std::string("expected '") + c + "'");
        ++i_;
    }
    void skipSpace() {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
    }

    Value value() {
        skipSpace();
        const char c = peek();
        if (c == '{') return object();
        if (c == '[') return array();
        if (c == '"') return Value{Value::Kind::String, string(), {}, {}};
        if (c == '-' || (c >= '0' && c <= '9')) return Value{Value::Kind::Number, number(), {}, {}};
        if (literal("true")) return Value{Value::Kind::Bool, "true", {}, {}};
        if (literal("false")) return Value{Value::Kind::Bool, "false", {}, {}};
        if (literal("null")) return Value{};
        fail("expected a value");
    }

    bool literal(std::string_view word) {
        if (s_.substr(i_, word.size()) != word) return false;
        i_ += word.size();
        return true;
    }

    Value object() {
        Value v{Value::Kind::Object, {}, {}, {}};
        expect('{');
        skipSpace();
        if (peek() == '}') { ++i_; return v; }
        for (;;) {
            skipSpace();
            std::string key = string();
            for (const auto& m : v.members) {
                if (m.first == key) fail("duplicate key '" + key + "'");
            }
            skipSpace();
            expect(':');
            v.members.emplace_back(std::move(key), value());
            skipSpace();
            if (peek() == ',') { ++i_; continue; }
            expect('}');
            return v;
        }
    }

    Value array() {
        Value v{Value::Kind::Array, {}, {}, {}};
        expect('[');
        skipSpace();
        if (peek() == ']') { ++i_; return v; }
        for (;;) {
            v.items.push_back(value());
            skipSpace();
            if (peek() == ',') { ++i_; continue; }
            expect(']');
            return v;
        }
    }

    std::string number() {
        const std::size_t start = i_;
        if (peek() == '-') ++i_;
        if (peek() == '0') {
            ++i_;
        } else {
            if (!digits()) fail("bad number");
        }
        if (peek() == '.') { ++i_; if (!digits()) fail("digits expected after '.'"); }
        if (peek() == 'e' || peek() == 'E') {
            ++i_;
            if (peek() == '+' || peek() == '-') ++i_;
            if (!digits()) fail("digits expected in exponent");
        }
        return std::string(s_.substr(start, i_ - start));
    }

    bool digits() {
        const std::size_t start = i_;
        while (peek() >= '0' && peek() <= '9') ++i_;
        return i_ > start;
    }

    unsigned hex4() {
        unsigned v = 0;
        for (int k = 0; k < 4; ++k) {
            const char c = peek();
            unsigned d = 0;
            if (c >= '0' && c <= '9') d = static_cast<unsigned>(c - '0');
            else if (c >= 'a' && c <= 'f') d = static_cast<unsigned>(c - 'a' + 10);
            else if (c >= 'A' && c <= 'F') d = static_cast<unsigned>(c - 'A' + 10);
            else fail("bad \\u escape");
            v = v * 16 + d;
            ++i_;
        }
        return v;
    }

    static void appendUtf8(std::string& out, std::uint32_t cp) {
        if (cp < 0x80) {
            out += static_cast<char>(cp);
        } else if (cp < 0x800) {
            out += static_cast<char>(0xc0 | (cp >> 6));
            out += static_cast<char>(0x80 | (cp & 0x3f));
        } else if (cp < 0x10000) {
            out += static_cast<char>(0xe0 | (cp >> 12));
            out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (cp & 0x3f));
        } else {
            out += static_cast<char>(0xf0 | (cp >> 18));
            out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
            out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (cp & 0x3f));
        }
    }

    std::uint32_t escapedCodePoint() {
        std::uint32_t cp = hex4();
        if (cp >= 0xdc00 && cp <= 0xdfff) fail("lone low surrogate");
        if (cp >= 0xd800 && cp <= 0xdbff) {
            if (!literal("\\u")) fail("high surrogate without low surrogate");
            const std::uint32_t low = hex4();
            if (low < 0xdc00 || low > 0xdfff) fail("bad low surrogate");
            cp = 0x10000 + ((cp - 0xd800) << 10) + (low - 0xdc00);
        }
        return cp;
    }

    void escape(std::string& out) {
        const char c = peek();
        ++i_;
        switch (c) {
            case '"': out += '"'; break;
            case '\\': out += '\\'; break;
            case '/': out += '/'; break;
            case 'b': out += '\b'; break;
            case 'f': out += '\f'; break;
            case 'n': out += '\n'; break;
            case 'r': out += '\r'; break;
            case 't': out += '\t'; break;
            case 'u': appendUtf8(out, escapedCodePoint()); break;
            default: fail("bad escape");
        }
    }

    /// Copies one raw UTF-8 sequence, checking it by decoding the code point.
    void rawUtf8(std::string& out) {
        const auto b0 = static_cast<unsigned char>(peek());
        int extra = 0;
        std::uint32_t cp = 0;
        if ((b0 & 0xe0) == 0xc0) { extra = 1; cp = b0 & 0x1f; }
        else if ((b0 & 0xf0) == 0xe0) { extra = 2; cp = b0 & 0x0f; }
        else if ((b0 & 0xf8) == 0xf0) { extra = 3; cp = b0 & 0x07; }
        else fail("invalid UTF-8 lead byte");
        const std::size_t start = i_++;
        for (int k = 0; k < extra; ++k) {
            const auto b = static_cast<unsigned char>(peek());
            if ((b & 0xc0) != 0x80) fail("invalid UTF-8 continuation byte");
            cp = (cp << 6) | (b & 0x3f);
            ++i_;
        }
        const std::uint32_t minimum[] = {0, 0x80, 0x800, 0x10000};
        if (cp < minimum[extra] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) fail("invalid UTF-8 code point");
        out.append(s_.substr(start, i_ - start));
    }

    std::string string() {
        expect('"');
        std::string out;
        for (;;) {
            if (i_ >= s_.size()) fail("unterminated string");
            const auto c = static_cast<unsigned char>(peek());
            if (c == '"') { ++i_; return out; }
            if (c < 0x20) fail("raw control character in string");
            if (c == '\\') { ++i_; escape(out); continue; }
            if (c >= 0x80) { rawUtf8(out); continue; }
            out += static_cast<char>(c);
            ++i_;
        }
    }

    std::string_view s_;
    std::size_t i_ = 0;
};

const Value* child(const Value& v, std::string_view segment) {
    if (v.kind == Value::Kind::Array) {
        std::size_t index = 0;
        for (char c : segment) {
            if (c < '0' || c > '9') return nullptr;
            index = index * 10 + static_cast<std::size_t>(c - '0');
        }
        return !segment.empty() && index < v.items.size() ? &v.items[index] : nullptr;
    }
    if (v.kind == Value::Kind::Object) {
        for (const auto& m : v.members) {
            if (m.first == segment) return &m.second;
        }
    }
    return nullptr;
}

std::string describe(const Value& v) {
    switch (v.kind) {
        case Value::Kind::Null: return "null";
        case Value::Kind::Array: return "<array>";
        case Value::Kind::Object: return "<object>";
        default: return v.text;
    }
}

}  // namespace

/// Empty if `text` is one valid JSON document, else what is wrong and where.
std::string jsonError(std::string_view text) {
    try {
        Parser(text).document();
        return {};
    } catch (const std::exception& e) {
        return e.what();
    }
}

/// The value at a '/'-separated path ("per_step/3/alive"): numbers as written,
/// strings decoded, "null", "<array>" or "<object>". A final "#" gives the size
/// of an array or object. nullopt if the text is invalid or the path missing.
std::optional<std::string> jsonQuery(std::string_view text, std::string_view path) {
    Value root;
    try {
        root = Parser(text).document();
    } catch (const std::exception&) {
        return std::nullopt;
    }
    const Value* v = &root;
    while (!path.empty()) {
        const std::size_t slash = path.find('/');
        const std::string_view segment = path.substr(0, slash);
        path = slash == std::string_view::npos ? std::string_view() : path.substr(slash + 1);
        if (segment == "#" && path.empty()) {
            if (v->kind == Value::Kind::Array) return std::to_string(v->items.size());
            if (v->kind == Value::Kind::Object) return std::to_string(v->members.size());
            return std::nullopt;
        }
        v = child(*v, segment);
        if (v == nullptr) return std::nullopt;
    }
    return describe(*v);
}

}  // namespace spindrift_test
