// The weights of exact linear drag (dragWeights, integrate.glsl) against the
// phi functions phi_k(z) = sum_i z^i / (i + k)! at z = -x computed here in
// double, independently: the series summed to convergence below x = 5 (its
// terms peak near 0.5 and the sums are >= 0.03, so double keeps ~14 digits),
// the closed forms with exp and expm1 above (no cancellation worse than a
// factor 1 / x^3 there).
#include "particles/cpu_kernels.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace spindrift::kernels {
namespace {

double referencePhi(int k, double x) {
    if (x < 5.0) {
        double term = 1.0;  // (-x)^i / (i + k)! for i = 0: 1 / k!
        for (int j = 2; j <= k; ++j) {
            term /= j;
        }
        double sum = 0.0;
        for (int i = 0; i < 80; ++i) {
            sum += term;
            term *= -x / static_cast<double>(i + k + 1);
        }
        return sum;
    }
    const double e = std::exp(-x);
    const double one = -std::expm1(-x);  // 1 - e^-x
    switch (k) {
        case 0: return e;
        case 1: return one / x;
        case 2: return (x - one) / (x * x);
        case 3: return (x * x / 2.0 - x + one) / (x * x * x);
        default: return (x * x * x / 6.0 - x * x / 2.0 + x - one) / (x * x * x * x);
    }
}

// Float weights carry at most ~10 roundings of 6e-8 without cancellation in
// the series branch (x < 1); in the exp branch each step of the downward
// recurrence subtracts from 1/k! a value up to 0.8 of it at x = 1, losing ~1e-7
// of absolute precision per step: ~1e-6 relative in phi_3 (0.13) and ~4e-6
// in phi_4 (0.035) there. 2e-6 and 8e-6 relative cover them with a margin of
// ~2; a wrong coefficient or a swapped branch is off by far more (the
// series' first dropped term is 5e-9 of phi_4, a wrong factorial 1e-2).
constexpr double kRelative = 2e-6;
constexpr double kRelativePhi4 = 8e-6;

TEST(DragWeights, MatchThePhiFunctionsOnBothSidesOfTheBranch) {
    const float dt = 0.5f;
    for (float x : {0.0f, 1e-8f, 1e-4f, 0.01f, 0.3f, 0.7f, 0.999f, 1.0f, 1.001f, 2.0f, 5.0f, 30.0f, 1e3f, 1e6f}) {
        SCOPED_TRACE(x);
        DragWeights w = dragWeights(x / dt, dt);
        const double xs = static_cast<double>(w.x);  // the x the kernel used (x / dt * dt rounded)
        EXPECT_NEAR(w.x, x, 1e-6f * x);
        EXPECT_NEAR(w.decay, referencePhi(0, xs), kRelative * referencePhi(0, xs) + 1e-30);
        EXPECT_NEAR(w.phi1, referencePhi(1, xs), kRelative * referencePhi(1, xs));
        EXPECT_NEAR(w.phi2, referencePhi(2, xs), kRelative * referencePhi(2, xs));
        EXPECT_NEAR(w.phi3, referencePhi(3, xs), kRelative * referencePhi(3, xs));
        EXPECT_NEAR(w.phi4, referencePhi(4, xs), kRelativePhi4 * referencePhi(4, xs));
    }
}

// Without drag the weights are exactly Euler's and Taylor's: 1, 1, 1/2, 1/6, 1/24
// (float), so an emitter without wind or flow field integrates as before.
TEST(DragWeights, AreExactlyTheTaylorCoefficientsWithoutDrag) {
    DragWeights w = dragWeights(0.0f, 1.0f / 60.0f);
    EXPECT_EQ(w.x, 0.0f);
    EXPECT_EQ(w.decay, 1.0f);
    EXPECT_EQ(w.phi1, 1.0f);
    EXPECT_EQ(w.phi2, 0.5f);
    EXPECT_EQ(w.phi3, 1.0f / 6.0f);
    EXPECT_EQ(w.phi4, 1.0f / 24.0f);
}

// Stability: the decay stays in [0, 1] and the weight of the other forces, h
// phi_1, never exceeds h, for every rate including an overflowed one (k / m
// beyond float range); x phi_1, the medium's weight, is 1 - decay, so the
// velocity is a convex mix of the old one and the medium's (plus a h phi_1).
TEST(DragWeights, StayBoundedForEveryRate) {
    const float h = 1.0f / 60.0f;
    for (float rate : {0.0f, 1e-3f, 1.0f, 60.0f, 300.0f, 1e5f, 1e20f, 3e38f, std::numeric_limits<float>::infinity()}) {
        SCOPED_TRACE(rate);
        DragWeights w = dragWeights(rate, h);
        EXPECT_GE(w.decay, 0.0f);
        EXPECT_LE(w.decay, 1.0f);
        EXPECT_GE(w.phi1, 0.0f);
        EXPECT_LE(w.phi1, 1.0f);
        EXPECT_TRUE(std::isfinite(w.x * w.phi1) && std::isfinite(w.x * w.phi2) && std::isfinite(w.x * w.phi3) &&
                    std::isfinite(w.x * w.phi4));
        EXPECT_NEAR(w.x * w.phi1, 1.0f - w.decay, 1e-6f);
    }
}

// One exponential-Euler step from v0 under constant a and u is the closed
// form u + a / K + (v0 - u - a / K) e^(-K h), for a rate far past explicit
// Euler's limit of 2 / h (the spark of issue 18: K = 300 1/s, h = 1/60 s).
TEST(DragWeights, EulerStepIsTheClosedForm) {
    const float h = 1.0f / 60.0f, rate = 300.0f;
    const vec3 v0(1.0f, 5.0f, -2.0f), a(0.0f, -9.81f, 0.0f), u(3.0f, 0.0f, 0.0f);
    Motion m = eulerMotion(SD_INTEGRATE_SEMI_IMPLICIT_EULER, vec3(0.0f), v0, a, u, dragWeights(rate, h), h);
    for (int c = 0; c < 3; ++c) {
        const double terminal = double(u[c]) + double(a[c]) / rate;
        const double exact = terminal + (double(v0[c]) - terminal) * std::exp(-double(rate) * h);
        // A few roundings of values up to 5 m/s: 1e-6 m/s.
        EXPECT_NEAR(m.velocity[c], exact, 1e-6) << c;
    }
}

}  // namespace
}  // namespace spindrift::kernels
