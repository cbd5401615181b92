#include "scene/toml_read.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace spindrift::scene {

namespace {

// A float written like an integer ("1e4" prints as 10000) is shown with ".0" so
// "expected an integer, got 10000.0" makes sense.
std::string formatFloatLiteral(double v) {
    std::string s = formatNumber(v);
    if (std::isfinite(v) && s.find_first_of(".eE") == std::string::npos) {
        s += ".0";
    }
    return s;
}

// Levenshtein distance, for "did you mean" hints on misspelt keys.
std::size_t editDistance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) {
        row[j] = j;
    }
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            const std::size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
            row[j] = std::min({above + 1, row[j - 1] + 1, substitute});
            diagonal = above;
        }
    }
    return row[b.size()];
}

std::string unknownKeyMessage(std::string_view key, const std::vector<std::string_view>& allowed,
                              const std::string& what) {
    const std::string_view best = closestMatch(key, allowed);
    std::string message = fmt::format("unknown key \"{}\" in {}", key, what);
    if (!best.empty()) {
        return message + fmt::format(" (did you mean \"{}\"?)", best);
    }
    std::string list;
    for (std::string_view candidate : allowed) {
        list.append(list.empty() ? "" : ", ").append(candidate);
    }
    return message + "; expected one of: " + list;
}

bool before(const toml::source_position& a, const toml::source_position& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
}

}  // namespace

std::string_view closestMatch(std::string_view word,
                              const std::vector<std::string_view>& candidates) {
    std::string_view best;
    std::size_t bestDistance = 3;  // more than 2 edits away is not a typo
    for (std::string_view candidate : candidates) {
        const std::size_t d = editDistance(word, candidate);
        if (d < bestDistance) {
            bestDistance = d;
            best = candidate;
        }
    }
    return best;
}

void fail(const ParseContext& ctx, const toml::source_region& region, const std::string& keyPath,
          const std::string& message) {
    throw SceneError(ctx.file, static_cast<int>(region.begin.line),
                     static_cast<int>(region.begin.column), keyPath, message);
}

std::string quotedList(const std::vector<std::string_view>& names) {
    std::string list;
    for (std::string_view name : names) {
        list.append(list.empty() ? "\"" : ", \"").append(name).append("\"");
    }
    return list;
}

std::string describeValue(const toml::node& node) {
    if (auto v = node.as_integer()) {
        return fmt::format("{}", v->get());
    }
    if (auto v = node.as_floating_point()) {
        return formatFloatLiteral(v->get());
    }
    if (auto v = node.as_boolean()) {
        return v->get() ? "true" : "false";
    }
    if (auto v = node.as_string()) {
        // Control characters as TOML escapes: a NUL would end the message
        // wherever it is printed as a C string.
        std::string quoted = "\"";
        for (const char c : v->get()) {
            const auto u = static_cast<unsigned char>(c);
            if (u < 0x20u || u == 0x7Fu) {
                quoted += fmt::format("\\u{:04X}", static_cast<unsigned>(u));
            } else {
                quoted += c;
            }
        }
        return quoted + "\"";
    }
    if (node.is_array()) {
        return "an array";
    }
    if (node.is_table()) {
        return "a table";
    }
    return "a date or time";
}

std::string joinPath(const std::string& parent, std::string_view key) {
    return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string indexPath(const std::string& parent, std::size_t index) {
    return fmt::format("{}[{}]", parent, index);
}

// --- Value --------------------------------------------------------------------

void Value::fail(const std::string& message) const {
    scene::fail(*ctx_, node_->source(), path_, message);
}

void Value::failExpected(const std::string& what) const {
    fail(fmt::format("expected {}, got {}", what, describeValue(*node_)));
}

void Value::failChoice(const std::vector<std::string_view>& names) const {
    const std::string_view best = node_->is_string() ? closestMatch(node_->value_or(std::string_view()), names)
                                                     : std::string_view();
    const std::string hint = best.empty() ? std::string() : fmt::format(" (did you mean \"{}\"?)", best);
    fail(fmt::format("expected one of {}, got {}{}", quotedList(names), describeValue(*node_), hint));
}

double Value::number(Bounds bounds) const {
    if (!node_->is_number()) {
        failExpected(bounds.describe(false));
    }
    const double v = node_->value<double>().value_or(0.0);
    if (!std::isfinite(v)) {
        fail(fmt::format("expected {}, got {} (NaN and infinity are not allowed)",
                         bounds.describe(false), describeValue(*node_)));
    }
    if (!bounds.contains(v)) {
        failExpected(bounds.describe(false));
    }
    return v;
}

float Value::real(Bounds bounds) const {
    const double v = number(bounds);
    if (!std::isfinite(static_cast<float>(v))) {
        fail(fmt::format("expected a number that fits single precision (|x| < 3.4e38), got {}",
                         describeValue(*node_)));
    }
    return static_cast<float>(v);
}

std::int64_t Value::integer(Bounds bounds) const {
    return integer(bounds, FieldRule::whole(bounds));
}

std::int64_t Value::integer(Bounds bounds, const FieldRule& wording) const {
    if (!node_->is_integer()) {
        failExpected(wording.describe());
    }
    const std::int64_t v = node_->as_integer()->get();
    if (!bounds.contains(static_cast<double>(v))) {
        failExpected(wording.describe());
    }
    return v;
}

float Value::real(const FieldRule& rule) const {
    if (!node_->is_number()) {
        failExpected(rule.describe());
    }
    const double v = node_->value<double>().value_or(0.0);
    if (!std::isfinite(v)) {
        fail(fmt::format("expected {}, got {} (NaN and infinity are not allowed)", rule.describe(),
                         describeValue(*node_)));
    }
    return real();
}

bool Value::boolean() const {
    if (!node_->is_boolean()) {
        failExpected("true or false");
    }
    return node_->as_boolean()->get();
}

std::string Value::string() const {
    if (!node_->is_string()) {
        failExpected("a string");
    }
    std::string s = node_->as_string()->get();
    if (s.empty()) {
        failExpected("a non-empty string");
    }
    // A NUL ends a path or a file name where the system reads it:
    // "data/rock.cube\u0000.txt" would open data/rock.cube.
    if (s.find('\0') != std::string::npos) {
        failExpected("a string without NUL characters (\\u0000)");
    }
    return s;
}

const toml::array& Value::array() const {
    if (!node_->is_array()) {
        failExpected("an array");
    }
    return *node_->as_array();
}

Value Value::element(std::size_t index) const {
    return Value(*ctx_, *array().get(index), indexPath(path_, index));
}

std::vector<float> Value::numbers(std::size_t n, Bounds bounds) const {
    const std::string what = fmt::format("an array of {} numbers", n);
    if (!node_->is_array()) {
        failExpected(what);
    }
    const toml::array& items = *node_->as_array();
    if (items.size() != n) {
        fail(fmt::format("expected {}, got an array of {}", what, items.size()));
    }
    std::vector<float> out;
    for (std::size_t i = 0; i < n; ++i) {
        out.push_back(element(i).real(bounds));
    }
    return out;
}

glm::vec3 Value::vec3(Bounds bounds) const {
    const std::vector<float> v = numbers(3, bounds);
    return {v[0], v[1], v[2]};
}

glm::vec3 Value::direction() const {
    const glm::vec3 v = vec3();
    const float length = glm::length(v);
    // Below ~1e-6 normalising amplifies rounding into the direction.
    if (!(length > 1e-6f) || !std::isfinite(length)) {
        fail(fmt::format("expected a non-zero direction [x, y, z], got [{}, {}, {}]", v.x, v.y,
                         v.z));
    }
    return v / length;
}

glm::vec4 Value::vec4(Bounds bounds) const {
    const std::vector<float> v = numbers(4, bounds);
    return {v[0], v[1], v[2], v[3]};
}

FloatRange Value::range(Bounds bounds) const {
    if (node_->is_number()) {
        const float v = real(bounds);
        return {v, v};
    }
    const std::string what = "a number or [min, max] with each " + bounds.describe(false);
    if (!node_->is_array() || node_->as_array()->size() != 2) {
        failExpected(what);
    }
    const float lo = element(0).real(bounds);
    const float hi = element(1).real(bounds);
    if (lo > hi) {
        fail(fmt::format("expected [min, max] with min <= max, got [{}, {}]", lo, hi));
    }
    return {lo, hi};
}

FloatRange Value::range(const FieldRule& rule) const {
    if (node_->is_number()) {
        const float v = real(rule);
        return {v, v};
    }
    if (!node_->is_array() || node_->as_array()->size() != 2) {
        failExpected("a number or [min, max] with each " + rule.describe());
    }
    return {element(0).real(rule), element(1).real(rule)};
}

// --- Table --------------------------------------------------------------------

void Table::allowOnly(const std::vector<std::string_view>& allowed, const std::string& what) const {
    const toml::key* first = nullptr;
    for (auto&& [key, node] : *table_) {
        const bool known = std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end();
        if (!known && (first == nullptr || before(key.source().begin, first->source().begin))) {
            first = &key;
        }
    }
    if (first != nullptr) {
        scene::fail(*ctx_, first->source(), joinPath(path_, first->str()),
                    unknownKeyMessage(first->str(), allowed, what));
    }
}

std::optional<Value> Table::find(std::string_view key) const {
    const toml::node* node = table_->get(key);
    if (node == nullptr) {
        return std::nullopt;
    }
    return Value(*ctx_, *node, joinPath(path_, key));
}

Value Table::require(std::string_view key, const std::string& expected) const {
    if (auto value = find(key)) {
        return *value;
    }
    scene::fail(*ctx_, table_->source(), joinPath(path_, key),
                "required key is missing: expected " + expected);
}

std::optional<Table> Table::subTable(std::string_view key) const {
    std::optional<Value> value = find(key);
    if (!value) {
        return std::nullopt;
    }
    if (!value->node().is_table()) {
        value->failExpected("a table");
    }
    return Table(*ctx_, *value->node().as_table(), value->path());
}

void Table::fail(const std::string& message) const {
    scene::fail(*ctx_, table_->source(), path_, message);
}

void Table::failAtKey(std::string_view key, const std::string& message) const {
    for (auto&& [k, node] : *table_) {
        if (k.str() == key) {
            scene::fail(*ctx_, k.source(), joinPath(path_, key), message);
        }
    }
    scene::fail(*ctx_, table_->source(), joinPath(path_, key), message);
}

void Table::failAtField(std::string_view field, const std::string& message) const {
    // Walk "key", "[index]" and ".key" parts down from this table as far as
    // the file has them.
    const toml::node* node = table_;
    std::size_t found = 0;  // characters of `field` walked
    std::size_t at = 0;
    while (at < field.size()) {
        const toml::node* next = nullptr;
        std::size_t end = 0;
        if (field[at] == '[') {
            end = field.find(']', at);
            if (end == std::string_view::npos) break;
            const std::size_t index = std::stoul(std::string(field.substr(at + 1, end - at - 1)));
            if (const toml::array* a = node->as_array(); a != nullptr && index < a->size()) next = a->get(index);
            end += 1;
        } else {
            const std::size_t start = field[at] == '.' ? at + 1 : at;
            end = std::min(field.find('.', start), field.find('[', start));
            if (end == std::string_view::npos) end = field.size();
            if (const toml::table* t = node->as_table()) next = t->get(field.substr(start, end - start));
        }
        if (next == nullptr) break;
        node = next;
        found = at = end;
    }
    // The path of what was found, or the whole field if the file has none of it.
    const std::string_view where = found > 0 ? field.substr(0, found) : field;
    scene::fail(*ctx_, node->source(), where.empty() ? path_ : joinPath(path_, where), message);
}

float Table::real(std::string_view key, float fallback, const FieldRule& rule) const {
    std::optional<Value> v = find(key);
    return v ? v->real(rule) : fallback;
}

FloatRange Table::range(std::string_view key, FloatRange fallback, const FieldRule& rule) const {
    std::optional<Value> v = find(key);
    return v ? v->range(rule) : fallback;
}

float Table::real(std::string_view key, float fallback, Bounds bounds) const {
    std::optional<Value> v = find(key);
    return v ? v->real(bounds) : fallback;
}

std::int64_t Table::integer(std::string_view key, std::int64_t fallback, Bounds bounds) const {
    std::optional<Value> v = find(key);
    return v ? v->integer(bounds) : fallback;
}

bool Table::boolean(std::string_view key, bool fallback) const {
    std::optional<Value> v = find(key);
    return v ? v->boolean() : fallback;
}

glm::vec3 Table::vec3(std::string_view key, glm::vec3 fallback, Bounds bounds) const {
    std::optional<Value> v = find(key);
    return v ? v->vec3(bounds) : fallback;
}

glm::vec3 Table::direction(std::string_view key, glm::vec3 fallback) const {
    std::optional<Value> v = find(key);
    return v ? v->direction() : fallback;
}

FloatRange Table::range(std::string_view key, FloatRange fallback, Bounds bounds) const {
    std::optional<Value> v = find(key);
    return v ? v->range(bounds) : fallback;
}

std::vector<Table> tableArray(const Table& root, std::string_view key) {
    std::optional<Value> value = root.find(key);
    if (!value) {
        return {};
    }
    const std::string what = fmt::format("an array of tables, written [[{}]]", key);
    const toml::array* asArray = value->node().as_array();
    if (asArray != nullptr && asArray->empty()) {
        return {};
    }
    if (!value->node().is_array_of_tables()) {
        value->failExpected(what);
    }
    std::vector<Table> tables;
    const toml::array& items = *value->node().as_array();
    for (std::size_t i = 0; i < items.size(); ++i) {
        tables.emplace_back(root.context(), *items.get(i)->as_table(), indexPath(value->path(), i));
    }
    return tables;
}

}  // namespace spindrift::scene
