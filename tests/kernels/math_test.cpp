// The kernels' own elementary functions (math.glsl) against the C library's
// double-precision ones, rounded to float: the reference is independent (a
// different algorithm, 29 more bits), and the bound is what math.glsl claims,
// a few ulp: the series' truncation is under 1e-8 relative (a tenth of an
// ulp) and each function rounds about ten float operations.
#include "particles/cpu_kernels.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace spindrift::kernels {
namespace {

// Distance in units in the last place of the float nearest the reference.
double ulpError(float got, double reference) {
    const float nearest = static_cast<float>(reference);
    const float ulp = std::nextafter(std::abs(nearest), std::numeric_limits<float>::infinity()) - std::abs(nearest);
    return std::abs(static_cast<double>(got) - reference) / static_cast<double>(ulp);
}

// 200,001 arguments spread evenly over [from, to] (their mantissas are not
// round numbers: the spacing is not a power of two).
template <class Check>
void sweep(float from, float to, Check check) {
    const int n = 200000;
    for (int i = 0; i <= n; ++i) {
        const float x = from + (to - from) * (static_cast<float>(i) / static_cast<float>(n));
        check(x);
    }
}

TEST(KernelMath, ExpIsWithinTwoUlpWhereTheResultIsNormal) {
    double worst = 0.0;
    sweep(-87.0f, 88.0f, [&](float x) { worst = std::max(worst, ulpError(sdExp(x), std::exp(double{x}))); });
    sweep(-1.0f, 1.0f, [&](float x) { worst = std::max(worst, ulpError(sdExp(x), std::exp(double{x}))); });
    EXPECT_LE(worst, 2.0);
}

TEST(KernelMath, Exp2IsWithinTwoUlpWhereTheResultIsNormal) {
    double worst = 0.0;
    sweep(-125.0f, 127.0f, [&](float x) { worst = std::max(worst, ulpError(sdExp2(x), std::exp2(double{x}))); });
    EXPECT_LE(worst, 2.0);
    // Integral arguments are exact powers of two.
    for (int k = -126; k <= 127; ++k) {
        EXPECT_EQ(sdExp2(static_cast<float>(k)), std::ldexp(1.0f, k)) << k;
    }
}

TEST(KernelMath, Log2IsWithinFourUlp) {
    // s = (m - 1) / (m + 1) rounds twice, the leading coefficient 2 / ln 2 and
    // the product s x series once each: 2 x 2^-24 of the value, which is up to
    // 4 ulp where the value's mantissa is near 1 (an ulp is 2^-24 to 2^-23 of
    // it); the sum with the exponent rounds to half an ulp of the result.
    // Also near 1, where the result is small.
    double worst = 0.0;
    auto check = [&](float x) { worst = std::max(worst, ulpError(sdLog2(x), std::log2(double{x}))); };
    sweep(1e-30f, 1e30f, check);
    sweep(1e-6f, 4.0f, check);
    sweep(0.5f, 2.0f, check);
    sweep(0.999f, 1.001f, check);
    EXPECT_LE(worst, 4.0);
    // Powers of two are exact.
    for (int k = -149; k <= 127; ++k) {
        EXPECT_EQ(sdLog2(std::ldexp(1.0f, k)), static_cast<float>(k)) << k;
    }
}

TEST(KernelMath, PowIsWithinTheErrorItsLogarithmCarries) {
    // 2^(y log2 x): log2 x carries 2 x 2^-24 of itself (above) and the
    // product y log2 x rounds once more, an absolute error of 3 x 2^-24
    // |y log2 x| in the exponent; exp2 turns it into ln 2 times that of the
    // result, up to 4.2 |y log2 x| ulp, plus its own 2 ulp. The kernels raise
    // distance ratios to falloff exponents and uniform numbers to 1/3.
    for (float y : {-3.0f, -1.5f, 0.5f, 1.0f / 3.0f, 1.5f, 2.5f, 3.0f}) {
        double worst = 0.0;
        sweep(1e-3f, 100.0f, [&](float x) {
            const double allowed = 2.0 + 4.5 * std::abs(double{y} * std::log2(double{x}));
            worst = std::max(worst, ulpError(sdPow(x, y), std::pow(double{x}, double{y})) / allowed);
        });
        EXPECT_LE(worst, 1.0) << "y = " << y;
    }
}

TEST(KernelMath, SinAndCosAreWithinTwoToTheMinus23OverAWideRange) {
    // Absolute error (the results are in [-1, 1], and near a root the exact
    // result is tiny while the argument's own rounding is not): the reduced
    // argument is exact to 1e-10 for |x| <= 1000 (|k| < 640, the first two
    // parts of pi/2 times k exact), the series rounds to about 1.5 ulp of a
    // result under 1, 2^-24 each: bound 2^-23.
    double worst = 0.0;
    sweep(-1000.0f, 1000.0f, [&](float x) {
        const glm::vec2 sc = sdSinCos(x);
        worst = std::max(worst, std::abs(sc.x - std::sin(double{x})));
        worst = std::max(worst, std::abs(sc.y - std::cos(double{x})));
    });
    EXPECT_LE(worst, std::ldexp(2.0, -24));
    // sin^2 + cos^2 stays 1 to rounding.
    sweep(0.0f, 7.0f, [&](float x) {
        const glm::vec2 sc = sdSinCos(x);
        EXPECT_NEAR(sc.x * sc.x + sc.y * sc.y, 1.0f, 4e-7f) << x;
    });
}

TEST(KernelMath, SpecialValuesFollowTheCLibrary) {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(sdExp(0.0f), 1.0f);
    EXPECT_EQ(sdExp(-inf), 0.0f);
    EXPECT_EQ(sdExp(inf), inf);
    EXPECT_EQ(sdExp(89.0f), inf);     // e^89 = 4.5e38 > FLT_MAX
    EXPECT_EQ(sdExp(-104.0f), 0.0f);  // e^-104 = 6.8e-46, under half the smallest subnormal
    EXPECT_TRUE(std::isnan(sdExp(nan)));
    EXPECT_EQ(sdExp2(128.0f), inf);
    EXPECT_EQ(sdExp2(-149.0f), std::ldexp(1.0f, -149));  // the smallest subnormal
    EXPECT_EQ(sdExp2(-151.0f), 0.0f);
    EXPECT_EQ(sdLog2(0.0f), -inf);
    EXPECT_EQ(sdLog2(inf), inf);
    EXPECT_TRUE(std::isnan(sdLog2(-1.0f)));
    EXPECT_TRUE(std::isnan(sdLog2(nan)));
    EXPECT_EQ(sdPow(0.0f, 2.0f), 0.0f);
    EXPECT_EQ(sdPow(0.0f, -1.5f), inf);
    EXPECT_EQ(sdPow(0.0f, 0.0f), 1.0f);
    EXPECT_EQ(sdPow(nan, 0.0f), 1.0f);
    EXPECT_EQ(sdPow(1.0f, 7.25f), 1.0f);
    EXPECT_TRUE(std::isnan(sdPow(-2.0f, 0.5f)));
    EXPECT_EQ(sdSin(0.0f), 0.0f);
    EXPECT_EQ(sdCos(0.0f), 1.0f);
    EXPECT_TRUE(std::isnan(sdSin(inf)));
    EXPECT_TRUE(std::isnan(sdCos(-inf)));
    EXPECT_TRUE(std::isnan(sdSin(nan)));
}

}  // namespace
}  // namespace spindrift::kernels
