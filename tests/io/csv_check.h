// An RFC 4180 CSV reader for tests, independent of src/io: fields split at
// commas outside double quotes, "" inside quotes is one quote, and records
// end at a line break outside quotes; every record must end with one.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace spindrift_test {

/// Every record of `text` as its fields; throws std::runtime_error on a
/// stray quote, an unterminated quote or a last record without a line end.
inline std::vector<std::vector<std::string>> readCsv(const std::string& text) {
    std::vector<std::vector<std::string>> rows(1);
    std::string field;
    bool quoted = false, wasQuoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                field += c;
            }
        } else if (c == '"') {
            if (!field.empty() || wasQuoted) throw std::runtime_error("quote inside an unquoted field");
            quoted = wasQuoted = true;
        } else if (c == ',' || c == '\n') {
            rows.back().push_back(field);
            field.clear();
            wasQuoted = false;
            if (c == '\n') rows.emplace_back();
        } else {
            if (wasQuoted) throw std::runtime_error("text after a closing quote");
            field += c;
        }
    }
    if (quoted) throw std::runtime_error("unterminated quote");
    if (!field.empty() || !rows.back().empty()) throw std::runtime_error("last record has no line end");
    rows.pop_back();
    return rows;
}

}  // namespace spindrift_test
