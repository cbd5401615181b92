// Counter-based random numbers: uniform, independent streams, exact floats.
#include "kernels/random.glsl"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace spindrift::kernels {
namespace {

// Chi-square goodness of fit over 64 bins of 64k draws: 63 degrees of freedom,
// the 99.9th percentile is 103.4; a uniform generator fails 1 run in 1000 and
// this one is deterministic, so the test either always passes or always fails.
TEST(Random, UnitIsUniform) {
    std::array<int, 64> bins{};
    const int n = 1 << 16;
    for (int i = 0; i < n; ++i) {
        float u = randomUnit(particleKey(emitterKeyBase(1u, 0u), static_cast<uint>(i)), 3u);
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        bins[static_cast<int>(u * 64.0f)] += 1;
    }
    double chi2 = 0.0;
    const double expected = n / 64.0;
    for (int b : bins) {
        chi2 += (b - expected) * (b - expected) / expected;
    }
    EXPECT_LT(chi2, 103.4);
}

// Different streams of one key, and neighbouring keys, are uncorrelated:
// the sample correlation of 64k pairs has standard error 1/256 = 0.0039;
// bound 0.02 (5 sigma).
TEST(Random, StreamsAndNeighboursAreUncorrelated) {
    const int n = 1 << 16;
    auto correlation = [&](auto draw) {
        double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
        for (int i = 0; i < n; ++i) {
            auto [x, y] = draw(static_cast<uint>(i));
            sx += x; sy += y; sxx += x * x; syy += y * y; sxy += x * y;
        }
        double cov = sxy / n - (sx / n) * (sy / n);
        return cov / std::sqrt((sxx / n - (sx / n) * (sx / n)) * (syy / n - (sy / n) * (sy / n)));
    };
    uint base = emitterKeyBase(9u, 2u);
    EXPECT_LT(std::abs(correlation([&](uint i) {
        uint k = particleKey(base, i);
        return std::pair<double, double>(randomUnit(k, 0u), randomUnit(k, 1u));
    })), 0.02);
    EXPECT_LT(std::abs(correlation([&](uint i) {
        return std::pair<double, double>(randomUnit(particleKey(base, i), 0u), randomUnit(particleKey(base, i + 1u), 0u));
    })), 0.02);
    EXPECT_LT(std::abs(correlation([&](uint i) {
        return std::pair<double, double>(randomUnit(particleKey(emitterKeyBase(9u, 2u), i), 0u),
                                         randomUnit(particleKey(emitterKeyBase(9u, 3u), i), 0u));
    })), 0.02);
}

// 24 random bits: every value is a multiple of 2^-24, exactly representable,
// so GLSL and C++ produce the same float from the same integer.
TEST(Random, UnitIsAMultipleOfTwoToMinus24) {
    for (uint i = 0; i < 1000u; ++i) {
        float u = randomUnit(particleKey(7u, i), 0u);
        float scaled = u * 16777216.0f;
        EXPECT_EQ(scaled, std::floor(scaled));
    }
}

}  // namespace
}  // namespace spindrift::kernels
