#include "io/json_writer.h"

#include <fmt/format.h>

#include <cmath>

namespace spindrift::io {

namespace {

/// Length of the valid UTF-8 sequence starting at text[i], or 0 if invalid.
/// Rejects overlong forms, surrogates and code points above U+10FFFF, which
/// strict JSON parsers refuse.
std::size_t utf8Length(std::string_view text, std::size_t i) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char b0 = byte(i);
    std::size_t n = 0;
    unsigned char lo = 0x80, hi = 0xbf;  // allowed range of the second byte
    if (b0 >= 0xc2 && b0 <= 0xdf) n = 2;
    else if (b0 >= 0xe0 && b0 <= 0xef) { n = 3; if (b0 == 0xe0) lo = 0xa0; if (b0 == 0xed) hi = 0x9f; }
    else if (b0 >= 0xf0 && b0 <= 0xf4) { n = 4; if (b0 == 0xf0) lo = 0x90; if (b0 == 0xf4) hi = 0x8f; }
    else return 0;
    if (i + n > text.size()) return 0;
    if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
    for (std::size_t k = 2; k < n; ++k) {
        if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) return 0;
    }
    return n;
}

void appendEscapedAscii(std::string& out, char c) {
    switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        case '\b': out += "\\b"; break;
        case '\f': out += "\\f"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                out += fmt::format("\\u{:04x}", static_cast<unsigned>(c));
            } else {
                out += c;
            }
    }
}

}  // namespace

std::string jsonQuote(std::string_view text) {
    std::string out = "\"";
    for (std::size_t i = 0; i < text.size();) {
        if (static_cast<unsigned char>(text[i]) < 0x80) {
            appendEscapedAscii(out, text[i]);
            ++i;
            continue;
        }
        const std::size_t n = utf8Length(text, i);
        if (n == 0) {
            out += "\\ufffd";
            ++i;
        } else {
            out.append(text.substr(i, n));
            i += n;
        }
    }
    out += '"';
    return out;
}

void JsonWriter::newline() {
    out_ << '\n';
    for (std::size_t i = 0; i < levels_.size(); ++i) out_ << "  ";
}

void JsonWriter::separate() {
    if (afterKey_) {
        afterKey_ = false;
        return;
    }
    if (levels_.empty()) return;
    Level& level = levels_.back();
    if (!level.empty) out_ << (level.inlined ? ", " : ",");
    if (!level.inlined) newline();
    level.empty = false;
}

void JsonWriter::open(char bracket, bool inlined) {
    separate();
    out_ << bracket;
    // Inside an inline container everything stays inline.
    const bool parentInline = !levels_.empty() && levels_.back().inlined;
    levels_.push_back({inlined || parentInline, true});
}

void JsonWriter::close(char bracket) {
    const Level level = levels_.back();
    levels_.pop_back();
    if (!level.inlined && !level.empty) newline();
    out_ << bracket;
}

void JsonWriter::key(std::string_view name) {
    separate();
    out_ << jsonQuote(name) << ": ";
    afterKey_ = true;
}

void JsonWriter::value(std::string_view text) {
    separate();
    out_ << jsonQuote(text);
}

void JsonWriter::value(std::uint64_t number) {
    separate();
    out_ << number;
}

void JsonWriter::value(float number) {
    if (!std::isfinite(number)) return null();
    separate();
    // fmt writes e.g. "1e-05" and "3": both valid JSON numbers.
    out_ << fmt::format("{}", number);
}

void JsonWriter::value(double number) {
    if (!std::isfinite(number)) return null();
    separate();
    out_ << fmt::format("{}", number);
}

void JsonWriter::boolean(bool b) {
    separate();
    out_ << (b ? "true" : "false");
}

void JsonWriter::null() {
    separate();
    out_ << "null";
}

void JsonWriter::finish() { out_ << '\n'; }

}  // namespace spindrift::io
