// Reading values out of a parsed TOML document.
//
// Every reader checks type and finiteness and, on the first problem, throws a
// SceneError that points at the offending node (file, line, column, key path)
// and says what was expected. A reader given a FieldRule (the API's rule of
// the field, src/core/field_rules.h) checks the type only and words a type
// error with the rule: the range is the API validator's to check, once, and
// validateAt turns its FieldError into an error at the key. A reader given
// Bounds checks the range itself: for values only a scene file has (run,
// camera ...). Nothing here builds anything.
#pragma once

#include "core/field_rules.h"

#include <spindrift/scene.h>

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace spindrift::scene {

/// Where errors point and where relative data paths start.
struct ParseContext {
    std::string file;               ///< scene name used in messages
    std::filesystem::path baseDir;  ///< relative data paths resolve against this
};

/// Throws the SceneError for `region` (line and column 1-based; 0 = unknown).
[[noreturn]] void fail(const ParseContext& ctx, const toml::source_region& region,
                       const std::string& keyPath, const std::string& message);

/// "\"a\", \"b\", \"c\"" for messages.
std::string quotedList(const std::vector<std::string_view>& names);

/// The candidate at most 2 edits from `word` (a likely typo), or "".
std::string_view closestMatch(std::string_view word,
                              const std::vector<std::string_view>& candidates);

/// How a value looks in a message: 1.5, -1, "text", nan, an array ...
std::string describeValue(const toml::node& node);

/// The path of a child: "emitter[2]" + "shape" -> "emitter[2].shape".
std::string joinPath(const std::string& parent, std::string_view key);
std::string indexPath(const std::string& parent, std::size_t index);

/// One value of the document together with its key path.
class Value {
public:
    Value(const ParseContext& ctx, const toml::node& node, std::string path)
        : ctx_(&ctx), node_(&node), path_(std::move(path)) {}

    const toml::node& node() const { return *node_; }
    const std::string& path() const { return path_; }
    const ParseContext& context() const { return *ctx_; }
    [[noreturn]] void fail(const std::string& message) const;
    /// "expected <what>, got <value>".
    [[noreturn]] void failExpected(const std::string& what) const;

    double number(Bounds bounds = Bounds::any()) const;
    float real(Bounds bounds = Bounds::any()) const;  ///< number() that also fits a float
    std::int64_t integer(Bounds bounds) const;
    /// A finite number that fits a float; the rule words a type error only.
    float real(const FieldRule& rule) const;
    /// An integer that fits T (a type check: the field's C++ type); the rule
    /// words the error only.
    template <class T>
    T whole(const FieldRule& rule) const {
        const std::int64_t v = integer(Bounds::any(), rule);
        if (v < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
            static_cast<std::uint64_t>(v) > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) {
            failExpected(rule.describe());
        }
        return static_cast<T>(v);
    }
    bool boolean() const;
    std::string string() const;  ///< non-empty
    /// An array of exactly `n` numbers (n = 2, 3, 4 ...), each within bounds.
    std::vector<float> numbers(std::size_t n, Bounds bounds = Bounds::any()) const;
    glm::vec3 vec3(Bounds bounds = Bounds::any()) const;
    glm::vec3 direction() const;  ///< a non-zero vec3, normalised
    glm::vec4 vec4(Bounds bounds = Bounds::any()) const;
    /// `x` or `[min, max]` with min <= max, each within bounds.
    FloatRange range(Bounds bounds = Bounds::any()) const;
    /// `x` or `[min, max]`, type only; the rule (of each end) words a type error.
    FloatRange range(const FieldRule& rule) const;
    const toml::array& array() const;
    Value element(std::size_t index) const;

    /// One of a fixed set of names, e.g. {{"cpu", Backend::Cpu}, ...}.
    template <class E>
    E choice(std::initializer_list<std::pair<std::string_view, E>> options) const {
        const std::string name = string();
        for (const auto& [key, value] : options) {
            if (key == name) {
                return value;
            }
        }
        std::vector<std::string_view> names;
        for (const auto& option : options) {
            names.push_back(option.first);
        }
        failChoice(names);
    }
    /// "expected one of <names>, got <value>", with a "did you mean" hint
    /// when the value is a likely typo of one of them.
    [[noreturn]] void failChoice(const std::vector<std::string_view>& names) const;

private:
    std::int64_t integer(Bounds bounds, const FieldRule& wording) const;

    const ParseContext* ctx_;
    const toml::node* node_;
    std::string path_;
};

/// A TOML table with its key path: key checks and defaulted reads.
class Table {
public:
    Table(const ParseContext& ctx, const toml::table& table, std::string path)
        : ctx_(&ctx), table_(&table), path_(std::move(path)) {}

    /// Rejects the first key (in file order) not in `allowed`; `what` names
    /// the table in the message, e.g. "a force of kind \"gravity\"".
    void allowOnly(const std::vector<std::string_view>& allowed, const std::string& what) const;

    bool has(std::string_view key) const { return table_->contains(key); }
    std::optional<Value> find(std::string_view key) const;
    /// The value of a required key; if missing, an error at this table's
    /// position that says what was expected.
    Value require(std::string_view key, const std::string& expected) const;
    /// The sub-table at `key` (wrong type is an error); nullopt if absent.
    std::optional<Table> subTable(std::string_view key) const;
    [[noreturn]] void fail(const std::string& message) const;
    /// Error at the key itself (not its value), for "not allowed here".
    [[noreturn]] void failAtKey(std::string_view key, const std::string& message) const;
    /// Error at the value of `field`, a key path inside this table as a
    /// FieldError names it ("jet[0].speed"); a part the file left out (a
    /// default broke a rule with another key) is reported at the deepest part
    /// present.
    [[noreturn]] void failAtField(std::string_view field, const std::string& message) const;

    float real(std::string_view key, float fallback, Bounds bounds = Bounds::any()) const;
    std::int64_t integer(std::string_view key, std::int64_t fallback, Bounds bounds) const;
    bool boolean(std::string_view key, bool fallback) const;
    glm::vec3 vec3(std::string_view key, glm::vec3 fallback, Bounds bounds = Bounds::any()) const;
    glm::vec3 direction(std::string_view key, glm::vec3 fallback) const;
    FloatRange range(std::string_view key, FloatRange fallback, Bounds bounds) const;
    /// Type-only readers: `rule` words a type error (see the top of this file).
    float real(std::string_view key, float fallback, const FieldRule& rule) const;
    template <class T>
    T whole(std::string_view key, T fallback, const FieldRule& rule) const {
        std::optional<Value> v = find(key);
        return v ? v->whole<T>(rule) : fallback;
    }
    FloatRange range(std::string_view key, FloatRange fallback, const FieldRule& rule) const;

    const toml::table& raw() const { return *table_; }
    const std::string& path() const { return path_; }
    const ParseContext& context() const { return *ctx_; }

private:
    const ParseContext* ctx_;
    const toml::table* table_;
    std::string path_;
};

/// Runs the API's validator of what `table` defined: a FieldError becomes an
/// error at the field's value (Table::failAtField), any other Error one at the
/// table. The one path from a rule to a located scene error.
template <class Validate>
void validateAt(const Table& table, Validate&& validate) {
    try {
        validate();
    } catch (const FieldError& e) {
        table.failAtField(e.field(), e.message());
    } catch (const Error& e) {
        table.fail(e.what());
    }
}

/// The tables of an array of tables ([[emitter]]); empty if the key is absent.
std::vector<Table> tableArray(const Table& root, std::string_view key);

}  // namespace spindrift::scene
