// The constraint setup's closing speeds (src/fluid/neighbours.cpp,
// setupConstraints): the substep rule reads a histogram in which each
// particle counts once, at the speed its fastest-closing neighbour
// approaches it, and only a step's first substep fills it (the others skip
// the neighbours' velocities: docs/fluid.md, "Substeps").
#include "core/parallel.h"
#include "fluid/fluid_state.h"
#include "fluid/fluid_world.h"

#include <gtest/gtest.h>

#include <numeric>

namespace spindrift {
namespace {

constexpr float kDt = 1.0f / 60.0f;

/// A 2D fluid of the given particles (no colliders), gridded.
fluid::FluidState fluidOf(const std::vector<glm::vec2>& x, const std::vector<glm::vec2>& v, WorkerPool& pool) {
    fluid::FluidState f;
    f.def.dimension = 2;
    f.def.spacing = 0.02f;
    fluid::initialiseFluid(f);
    for (std::size_t i = 0; i < x.size(); ++i) f.p2.push(x[i], v[i], static_cast<std::uint32_t>(i));
    fluid::buildGrid<2>(pool, f);
    f.constraints.wallDensity.assign(x.size(), 0.0f);
    f.constraints.wallGradient.assign(x.size(), glm::vec3(0.0f));
    return f;
}

std::uint64_t total(const fluid::FluidState& f) {
    return std::accumulate(f.approach.begin(), f.approach.end(), std::uint64_t{0});
}

TEST(FluidClosingSpeeds, EachParticleCountsOnceAtItsFastestNeighbourAndOnlyWhenAsked) {
    WorkerPool pool(1);
    // Two particles one spacing apart along x closing at 1 m/s each: 2 m/s
    // along their line, the fastest (only) neighbour of both. A third, far
    // from both (10 h), has no neighbour: it counts at speed 0.
    const std::vector<glm::vec2> x{{0.0f, 0.0f}, {0.02f, 0.0f}, {1.0f, 0.0f}};
    const std::vector<glm::vec2> v{{1.0f, 0.0f}, {-1.0f, 0.0f}, {0.0f, 0.0f}};
    fluid::FluidState f = fluidOf(x, v, pool);
    FluidStepStats stats;
    fluid::setupConstraints<2>(pool, f, kDt, /*countClosing=*/true, stats);
    EXPECT_EQ(total(f), 3u);
    EXPECT_EQ(f.approach[fluid::approachBin(2.0f)], 2u);
    EXPECT_EQ(f.approach[fluid::approachBin(0.0f)], 1u);
    // A later substep's setup leaves the histogram as it was.
    fluid::FluidState g = fluidOf(x, v, pool);
    fluid::setupConstraints<2>(pool, g, kDt, /*countClosing=*/false, stats);
    EXPECT_EQ(total(g), 0u);
    // The pair moving apart closes at no speed.
    fluid::FluidState h = fluidOf(x, {{-1.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 0.0f}}, pool);
    fluid::setupConstraints<2>(pool, h, kDt, /*countClosing=*/true, stats);
    EXPECT_EQ(h.approach[fluid::approachBin(0.0f)], 3u);
}

TEST(FluidClosingSpeeds, ABlockCountsEveryParticleOnce) {
    // 400 particles of a block with a shear flow: the histogram holds 400,
    // whatever their neighbours.
    WorkerPool pool(2);
    std::vector<glm::vec2> x, v;
    for (int j = 0; j < 20; ++j) {
        for (int i = 0; i < 20; ++i) {
            x.emplace_back(0.02f * static_cast<float>(i), 0.02f * static_cast<float>(j));
            v.emplace_back(0.1f * static_cast<float>(j), -0.05f * static_cast<float>(i));
        }
    }
    fluid::FluidState f = fluidOf(x, v, pool);
    FluidStepStats stats;
    fluid::setupConstraints<2>(pool, f, kDt, /*countClosing=*/true, stats);
    EXPECT_EQ(total(f), 400u);
}

}  // namespace
}  // namespace spindrift
