// Piecewise-linear curves: values at keys, linear between, constant outside.
#include "particles/params.h"
#include "kernels/curves.glsl"

#include <gtest/gtest.h>

namespace spindrift::kernels {
namespace {

// The field validateEmitterDef names for an emitter with this colour curve,
// or "" if it accepts it.
std::string curveError(const Curve& curve) {
    EmitterDef def;
    def.colorOverLife = curve;
    try {
        validateEmitterDef(def);
    } catch (const FieldError& e) {
        return e.field();
    }
    return "";
}

TEST(Curves, EmptyIsOne) {
    CurveParams c = makeCurveParams(Curve{});
    EXPECT_EQ(evaluateCurve(c, 0.3f), vec4(1.0f));
}

TEST(Curves, LinearBetweenKeysAndClampedOutside) {
    Curve curve;
    curve.keys = {{0.2f, vec4(2.0f)}, {0.4f, vec4(4.0f, 0.0f, 1.0f, 1.0f)}, {0.9f, vec4(-1.0f)}};
    CurveParams c = makeCurveParams(curve);
    EXPECT_EQ(evaluateCurve(c, 0.0f), vec4(2.0f));  // before the first key
    EXPECT_EQ(evaluateCurve(c, 0.2f), vec4(2.0f));
    EXPECT_NEAR(evaluateCurve(c, 0.3f).x, 3.0f, 1e-6f);
    EXPECT_NEAR(evaluateCurve(c, 0.3f).y, 1.0f, 1e-6f);
    EXPECT_NEAR(evaluateCurve(c, 0.65f).x, 1.5f, 1e-6f);  // halfway from 4 to -1
    EXPECT_EQ(evaluateCurve(c, 0.95f), vec4(-1.0f));      // after the last key
}

TEST(Curves, UseAllEightKeys) {
    Curve curve;
    for (int i = 0; i < 8; ++i) {
        curve.keys.push_back({static_cast<float>(i) / 7.0f, vec4(static_cast<float>(i * i))});
    }
    CurveParams c = makeCurveParams(curve);
    // Between keys 6 and 7 (36 and 49): at t = 13/14, halfway.
    EXPECT_NEAR(evaluateCurve(c, 13.0f / 14.0f).x, 42.5f, 1e-4f);
    // A ninth key does not fit the kernel's array: the emitter's validation
    // names the curve.
    curve.keys.push_back({1.0f, vec4(0.0f)});
    EXPECT_EQ(curveError(curve), "color_over_life");
}

TEST(Curves, RejectNonIncreasingTimes) {
    Curve curve;
    curve.keys = {{0.5f, vec4(1.0f)}, {0.5f, vec4(2.0f)}};
    EXPECT_EQ(curveError(curve), "color_over_life[1].t");
    curve.keys = {{0.5f, vec4(1.0f)}, {0.25f, vec4(2.0f)}};
    EXPECT_EQ(curveError(curve), "color_over_life[1].t");
}

TEST(Curves, RejectNegativeFactorsAndTimesOutsideTheLife) {
    Curve curve;
    curve.keys = {{0.0f, vec4(1.0f, 1.0f, -0.5f, 1.0f)}};
    EXPECT_EQ(curveError(curve), "color_over_life[0].value");
    curve.keys = {{1.5f, vec4(1.0f)}};
    EXPECT_EQ(curveError(curve), "color_over_life[0].t");
}

}  // namespace
}  // namespace spindrift::kernels
