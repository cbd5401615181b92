// Piecewise-linear curves: values at keys, linear between, constant outside.
#include "particles/params.h"
#include "kernels/curves.glsl"
#include "kernels/derived.glsl"

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

// Colour and size by speed (derived.glsl, restoreLook): |v| mapped from
// over_speed_range onto the curves' t, clamped; the factors multiply the start
// colour and size (2, 2, 2, 1) and 0.1 (no over-life curves: factor 1). Here
// the range is [2, 12] m/s; at 10 m/s t = 0.8, so the colour factor is
// mix(1, (0, 0.5, 1, 0), 0.8) = (0.2, 0.6, 1, 0.2) and the size factor
// 1 + 2 * 0.8 = 2.6. Float rounding of a few operations: 1e-6.
TEST(Curves, OverSpeedCurvesReadTheSpeed) {
    EmitterDef def;
    def.color = {vec4(2.0f, 2.0f, 2.0f, 1.0f), vec4(2.0f, 2.0f, 2.0f, 1.0f)};
    def.size = {0.1f, 0.1f};
    def.overSpeedRange = {2.0f, 12.0f};
    def.colorOverSpeed.keys = {{0.0f, vec4(1.0f)}, {1.0f, vec4(0.0f, 0.5f, 1.0f, 0.0f)}};
    def.sizeOverSpeed.keys = {{0.0f, vec4(1.0f)}, {1.0f, vec4(3.0f)}};
    const EmitterParams e = makeEmitterParams(def, 1u, 0u, 0u, 0u);
    Particle p{};
    p.lifetime = 1.0f;
    p.velocity = vec3(0.0f, 6.0f, 8.0f);
    Particle q = restoreLook(e, p);
    EXPECT_NEAR(q.color.x, 0.4f, 1e-6f);
    EXPECT_NEAR(q.color.y, 1.2f, 1e-6f);
    EXPECT_NEAR(q.color.z, 2.0f, 1e-6f);
    EXPECT_NEAR(q.color.w, 0.2f, 1e-6f);
    EXPECT_NEAR(q.size, 0.26f, 1e-6f);
    // Below the range t = 0 (the first key), above it t = 1 (the last).
    p.velocity = vec3(1.0f, 0.0f, 0.0f);
    q = restoreLook(e, p);
    EXPECT_EQ(q.color, vec4(2.0f, 2.0f, 2.0f, 1.0f));
    EXPECT_EQ(q.size, 0.1f);
    p.velocity = vec3(0.0f, 0.0f, -50.0f);
    q = restoreLook(e, p);
    EXPECT_EQ(q.color, vec4(0.0f, 1.0f, 2.0f, 0.0f));
    EXPECT_NEAR(q.size, 0.3f, 1e-7f);
}

// A range of one speed is a step: below it the first key, at and above it
// the last. Without over-speed curves the start values stay, whatever the
// speed.
TEST(Curves, OverSpeedRangeOfOneSpeedIsAStep) {
    EmitterDef def;
    def.size = {1.0f, 1.0f};
    def.overSpeedRange = {3.0f, 3.0f};
    def.sizeOverSpeed.keys = {{0.0f, vec4(1.0f)}, {1.0f, vec4(4.0f)}};
    const EmitterParams e = makeEmitterParams(def, 1u, 0u, 0u, 0u);
    Particle p{};
    p.lifetime = 1.0f;
    p.velocity = vec3(2.9f, 0.0f, 0.0f);
    EXPECT_EQ(restoreLook(e, p).size, 1.0f);
    p.velocity = vec3(3.0f, 0.0f, 0.0f);
    EXPECT_EQ(restoreLook(e, p).size, 4.0f);
    EmitterDef plainDef;
    plainDef.size = {1.0f, 1.0f};
    const EmitterParams plain = makeEmitterParams(plainDef, 1u, 0u, 0u, 0u);
    EXPECT_EQ(restoreLook(plain, p).size, 1.0f);
    EXPECT_EQ(restoreLook(plain, p).color, vec4(1.0f));  // ColorRange's default ends
}

}  // namespace
}  // namespace spindrift::kernels
