// The rules of a definition's fields, written once (docs/design.md,
// "Validation"). The public API's validators check every field of a Def with a
// FieldCheck against a named FieldRule and throw FieldError naming the field
// as a scene file spells it; the scene loader reads values with type checks
// only, words a type error with the same rule, and turns a FieldError into an
// error at the key's line. So a range is checked in one place, for C++
// callers and scene files alike, and reads the same to both.
#pragma once

#include <spindrift/effects.h>
#include <spindrift/errors.h>

#include <glm/glm.hpp>

#include <limits>
#include <string>
#include <string_view>

namespace spindrift {

/// The accepted interval of a number. Bounds are inclusive unless open.
struct Bounds {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minOpen = false;
    bool maxOpen = false;

    static constexpr Bounds any() { return {}; }
    static constexpr Bounds atLeast(double v) { return {v, std::numeric_limits<double>::infinity()}; }
    static constexpr Bounds above(double v) { return {v, std::numeric_limits<double>::infinity(), true, false}; }
    static constexpr Bounds between(double lo, double hi) { return {lo, hi}; }
    static constexpr Bounds positive() { return above(0.0); }
    static constexpr Bounds nonNegative() { return atLeast(0.0); }
    static constexpr Bounds unit() { return between(0.0, 1.0); }

    /// False for NaN.
    constexpr bool contains(double v) const {
        const bool lowOk = minOpen ? v > min : v >= min;
        const bool highOk = maxOpen ? v < max : v <= max;
        return lowOk && highOk;
    }
    /// "a number > 0", "an integer in [1, 16]", "a number" ...
    std::string describe(bool integer) const;
};

/// One field's accepted values: an interval of numbers or of integers. Made
/// only by its factories, so a braced list reads as Bounds, never as a rule.
struct FieldRule {
    Bounds bounds;
    bool integer;

    static constexpr FieldRule number(Bounds b) { return FieldRule(b, false); }
    static constexpr FieldRule whole(Bounds b) { return FieldRule(b, true); }
    /// "an integer in [1, 16]".
    std::string describe() const { return bounds.describe(integer); }

private:
    constexpr FieldRule(Bounds b, bool isInteger) : bounds(b), integer(isInteger) {}
};

/// A channel of a linear RGB colour: >= 0, above 1 allowed (HDR). The one
/// rule of every colour a Def holds (render's background and fluid, a
/// collider's, a body's and a body shape's).
inline constexpr FieldRule kColourChannel = FieldRule::number(Bounds::nonNegative());
/// SurfaceTexture::scale: metres an image covers before it repeats.
inline constexpr FieldRule kTextureScale = FieldRule::number(Bounds::positive());

/// The span a slider offers for a field: the rule's ends where they are
/// closed and finite, otherwise `lo` and `hi` (a UI's choice for an open or
/// unbounded end), which must lie inside the rule. So a slider never offers a
/// value the API refuses; a span outside the rule fails to compile when
/// called in a constant expression, and throws otherwise.
struct SliderSpan {
    float min;
    float max;
};
constexpr SliderSpan sliderSpan(const FieldRule& rule, double lo, double hi) {
    const Bounds& b = rule.bounds;
    const double min = !b.minOpen && b.min > -std::numeric_limits<double>::infinity() ? b.min : lo;
    const double max = !b.maxOpen && b.max < std::numeric_limits<double>::infinity() ? b.max : hi;
    if (!(b.contains(min) && b.contains(max) && min < max)) throw Error("a slider's span outside its field's rule");
    return {static_cast<float>(min), static_cast<float>(max)};
}

/// How a number reads in a message: 1.5, -1, nan, inf.
std::string formatNumber(double v);

/// Checks the fields of one object ("fluid 'water'") and throws FieldError on
/// the first that breaks its rule, with "expected <rule>, got <value>".
class FieldCheck {
public:
    explicit FieldCheck(std::string object) : object_(std::move(object)) {}

    /// Finite and within the rule.
    void number(std::string_view field, double value, const FieldRule& rule) const;
    /// Each end finite and within the rule ("field[0]", "field[1]"), min <= max.
    void range(std::string_view field, FloatRange r, const FieldRule& rule) const;
    /// Every component finite ("field[1]").
    void finite(std::string_view field, glm::vec3 v) const;
    void finite(std::string_view field, glm::vec2 v) const;
    /// Each channel of a linear RGB colour finite and >= 0 ("field[1]").
    void colour(std::string_view field, glm::vec3 c) const;
    /// For rules that are not an interval: fails with "expected <expected>, got <got>".
    void expect(bool ok, std::string_view field, std::string_view expected, std::string_view got) const;
    [[noreturn]] void fail(std::string_view field, std::string message) const;

    const std::string& object() const { return object_; }

private:
    std::string object_;
};

/// "emitter 'sparks'", or "emitter" for an unnamed one.
std::string objectLabel(std::string_view kind, std::string_view name);
/// "jet[2].speed".
std::string fieldPath(std::string_view parent, std::size_t index, std::string_view key = {});

}  // namespace spindrift
