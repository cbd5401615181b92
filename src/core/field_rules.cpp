#include "core/field_rules.h"

#include <fmt/format.h>

#include <cmath>

namespace spindrift {

FieldError::FieldError(std::string object, std::string field, std::string message)
    : Error(fmt::format("{}: {}: {}", object, field, message)),
      object_(std::move(object)),
      field_(std::move(field)),
      message_(std::move(message)) {}

std::string formatNumber(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    // Most values are floats: a float widened to double prints as the float
    // it was (0.005, not 0.004999999888241291).
    const auto f = static_cast<float>(v);
    if (static_cast<double>(f) == v) return fmt::format("{}", f);
    return fmt::format("{}", v);
}

std::string Bounds::describe(bool integer) const {
    const std::string noun = integer ? "an integer" : "a number";
    const bool hasMin = std::isfinite(min);
    const bool hasMax = std::isfinite(max);
    if (hasMin && hasMax) {
        return fmt::format("{} in {}{}, {}{}", noun, minOpen ? "(" : "[", formatNumber(min), formatNumber(max),
                           maxOpen ? ")" : "]");
    }
    if (hasMin) return fmt::format("{} {} {}", noun, minOpen ? ">" : ">=", formatNumber(min));
    if (hasMax) return fmt::format("{} {} {}", noun, maxOpen ? "<" : "<=", formatNumber(max));
    return noun;
}

void FieldCheck::fail(std::string_view field, std::string message) const {
    throw FieldError(object_, std::string(field), std::move(message));
}

void FieldCheck::expect(bool ok, std::string_view field, std::string_view expected, std::string_view got) const {
    if (!ok) fail(field, fmt::format("expected {}, got {}", expected, got));
}

void FieldCheck::number(std::string_view field, double value, const FieldRule& rule) const {
    // NaN fails contains(); infinity is never a value a rule means.
    expect(std::isfinite(value) && rule.bounds.contains(value), field, rule.describe(), formatNumber(value));
}

void FieldCheck::range(std::string_view field, FloatRange r, const FieldRule& rule) const {
    number(fmt::format("{}[0]", field), r.min, rule);
    number(fmt::format("{}[1]", field), r.max, rule);
    expect(r.min <= r.max, field, "[min, max] with min <= max", fmt::format("[{}, {}]", r.min, r.max));
}

void FieldCheck::finite(std::string_view field, glm::vec3 v) const {
    for (int i = 0; i < 3; ++i) number(fmt::format("{}[{}]", field, i), v[i], FieldRule::number(Bounds::any()));
}

void FieldCheck::finite(std::string_view field, glm::vec2 v) const {
    for (int i = 0; i < 2; ++i) number(fmt::format("{}[{}]", field, i), v[i], FieldRule::number(Bounds::any()));
}

void FieldCheck::colour(std::string_view field, glm::vec3 c) const {
    for (int i = 0; i < 3; ++i) number(fmt::format("{}[{}]", field, i), c[i], kColourChannel);
}

std::string objectLabel(std::string_view kind, std::string_view name) {
    return name.empty() ? std::string(kind) : fmt::format("{} '{}'", kind, name);
}

std::string fieldPath(std::string_view parent, std::size_t index, std::string_view key) {
    return key.empty() ? fmt::format("{}[{}]", parent, index) : fmt::format("{}[{}].{}", parent, index, key);
}

}  // namespace spindrift
