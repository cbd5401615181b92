// Piecewise-linear curves: values at keys, linear between, constant outside.
#include "particles/params.h"
#include "kernels/curves.glsl"

#include <gtest/gtest.h>

namespace spindrift::kernels {
namespace {

TEST(Curves, EmptyIsOne) {
    CurveParams c = makeCurveParams(Curve{}, "test");
    EXPECT_EQ(evaluateCurve(c, 0.3f), vec4(1.0f));
}

TEST(Curves, LinearBetweenKeysAndClampedOutside) {
    Curve curve;
    curve.keys = {{0.2f, vec4(2.0f)}, {0.4f, vec4(4.0f, 0.0f, 1.0f, 1.0f)}, {0.9f, vec4(-1.0f)}};
    CurveParams c = makeCurveParams(curve, "test");
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
    CurveParams c = makeCurveParams(curve, "test");
    // Between keys 6 and 7 (36 and 49): at t = 13/14, halfway.
    EXPECT_NEAR(evaluateCurve(c, 13.0f / 14.0f).x, 42.5f, 1e-4f);
    curve.keys.push_back({1.0f, vec4(0.0f)});
    EXPECT_THROW(makeCurveParams(curve, "test"), Error);
}

TEST(Curves, RejectNonIncreasingTimes) {
    Curve curve;
    curve.keys = {{0.5f, vec4(1.0f)}, {0.5f, vec4(2.0f)}};
    EXPECT_THROW(makeCurveParams(curve, "test"), Error);
}

}  // namespace
}  // namespace spindrift::kernels
