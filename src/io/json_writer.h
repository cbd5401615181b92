// A small streaming JSON writer: enough for run summaries, no dependency.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace spindrift::io {

/// Quotes and escapes `text` as a JSON string. Invalid UTF-8 bytes become
/// U+FFFD so the output is always valid JSON, whatever a file path holds.
std::string jsonQuote(std::string_view text);

/// Writes one JSON value, tracking commas and indentation. Containers opened
/// "inline" keep all their contents on one line, which keeps a per-step array
/// readable (one step per line). Non-finite numbers are written as null: JSON
/// has no NaN or infinity.
class JsonWriter {
public:
    explicit JsonWriter(std::ostream& out) : out_(out) {}

    void beginObject(bool inlined = false) { open('{', inlined); }
    void endObject() { close('}'); }
    void beginArray(bool inlined = false) { open('[', inlined); }
    void endArray() { close(']'); }

    /// Member name inside an object; the next call writes its value.
    void key(std::string_view name);

    void value(std::string_view text);
    void value(const char* text) { value(std::string_view(text)); }
    void value(std::uint64_t number);
    void value(std::uint32_t number) { value(static_cast<std::uint64_t>(number)); }
    /// Shortest text that parses back to the same float.
    void value(float number);
    /// Shortest text that parses back to the same double.
    void value(double number);
    void boolean(bool b);
    void null();

    /// Ends the document with a newline.
    void finish();

private:
    struct Level {
        bool inlined = false;
        bool empty = true;
    };
    void open(char bracket, bool inlined);
    void close(char bracket);
    /// Comma and line break before a value or key, unless it follows a key.
    void separate();
    void newline();

    std::ostream& out_;
    std::vector<Level> levels_;
    bool afterKey_ = false;
};

}  // namespace spindrift::io
