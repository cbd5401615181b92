// The warm start's cap (src/kernels/fluid.glsl, fluidWarmCap): the pressure
// an impact left on one particle is not re-applied in full in the next
// substep, where it flung that particle's neighbours (docs/fluid.md, "The
// warm start's cap").
#include "core/parallel.h"
#include "fluid/fluid_state.h"
#include "fluid/fluid_world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

namespace spindrift {
namespace {

constexpr float kSpacing = 0.02f;
constexpr int kSide = 21;                  // particles per row and column
constexpr float kSubstep = 1.0f / 300.0f;  // s: 5 substeps of 1/60 s

/// A 2D block of kSide x kSide particles on the lattice, at rest, without
/// colliders, whose centre particle carries `pressure` (m/s) from the last
/// substep (as an impact leaves it), under gravity g (m/s^2) and a pressed
/// depth of the block's height; set up and solved for one substep.
struct StruckBlock {
    WorkerPool pool{1};
    fluid::FluidState f;

    StruckBlock(float pressure, float g) {
        f.def.dimension = 2;
        f.def.spacing = kSpacing;
        f.def.gravity = glm::vec3(0.0f, -g, 0.0f);
        fluid::initialiseFluid(f);
        const int centre = (kSide / 2) * kSide + kSide / 2;
        for (int j = 0; j < kSide; ++j) {
            for (int i = 0; i < kSide; ++i) {
                const glm::vec2 x(kSpacing * static_cast<float>(i), kSpacing * static_cast<float>(j));
                f.p2.push(x, glm::vec2(0.0f), static_cast<std::uint32_t>(j * kSide + i));
                f.p2.pressure.back() = j * kSide + i == centre ? pressure : 0.0f;
            }
        }
        f.pressedDepth = kSpacing * static_cast<float>(kSide - 1);
        f.lastSubstep = kSubstep;  // the warm start's share is then FluidDef::warmStart, 1
        fluid::buildGrid<2>(pool, f);
        f.constraints.wallDensity.assign(f.p2.size(), 0.0f);
        f.constraints.wallGradient.assign(f.p2.size(), glm::vec3(0.0f));
        FluidStepStats stats;
        fluid::setupConstraints<2>(pool, f, kSubstep, /*countClosing=*/true, stats);
        fluid::solveConstraints<2>(pool, f, kSubstep);
    }

    float fastest() const {
        float m = 0.0f;
        for (const glm::vec2& v : f.p2.velocity) m = std::max(m, glm::length(v));
        return m;
    }
};

TEST(FluidWarmStart, AnImpactsPressureIsNotReappliedInFull) {
    // The cap, from its closed form: 5 hydrostatic pressures at the bottom of
    // the block, 5 g dt depth / S with S = sum_n w_n dy_n^2 / r_n over the
    // lattice (6.7087 spacings at h = 3.5 spacings, summed independently of
    // latticeHydrostaticSum). 20 m/s is an impact's pressure: the 30k dam
    // break's crushed particle carried 20 times its fluid's 99.9th
    // percentile (docs/fluid.md).
    const float g = 10.0f;
    const float depth = kSpacing * static_cast<float>(kSide - 1);
    const float cap = 5.0f * g * kSubstep * depth / (6.7087f * kSpacing);
    StruckBlock struck(20.0f, g);
    EXPECT_NEAR(struck.f.hydrostaticSum, 6.7087f * kSpacing, 1e-4f * kSpacing);
    // The warm start moves each neighbour by at most its w (<= 1) times the
    // pressure it re-applies, and the sweeps after it only solve the
    // constraints (at rest density, no bias) with pressures that stay >= 0:
    // no particle ends faster than the cap.
    const float fastest = struck.fastest();
    std::printf("an impact's pressure of 20 m/s: the fastest particle %.3f m/s after the substep, cap %.3f m/s\n",
                fastest, cap);
    EXPECT_GT(fastest, 0.0f) << "the capped pressure is still applied";
    EXPECT_LE(fastest, cap);
}

TEST(FluidWarmStart, WithoutGravityNothingIsCapped) {
    // Without gravity there is no hydrostatic scale: the pressure is
    // re-applied as it was, so the same strike moves the block faster than
    // any cap of the test above.
    StruckBlock free(20.0f, 0.0f);
    StruckBlock held(20.0f, 10.0f);
    std::printf("the same strike, the fastest particle: %.3f m/s without gravity, %.3f m/s with\n", free.fastest(),
                held.fastest());
    EXPECT_GT(free.fastest(), 2.0f * held.fastest());
}

}  // namespace
}  // namespace spindrift
