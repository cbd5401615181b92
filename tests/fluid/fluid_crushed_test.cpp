// A fluid squeezed into a point (issue 14): a jet of 16,777,217 particles/s
// leaves its whole capacity at the nozzle in one step, so every particle is
// within h of every other. Without a bound each particle then reads every
// other as a neighbour and the steps cost seconds (docs/fuzzing.md); the
// setup reads a sub-cell only up to kCrushedSubCell (8) times its count at
// rest (src/fluid/fluid_state.h), so the kept neighbours stay under 3^2
// sub-cells x 8 x (h / spacing)^2 per particle, the rest are counted as
// overflows, and the fluid stays finite.
#include "fluid/fluid_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

TEST(FluidCrushed, APileAtTheNozzleReadsABoundedNumberOfNeighbours) {
    test::FluidWorld w;
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(1.5f, 1.5f, 0.0f), 2);
    FluidDef def;
    def.name = "pile";
    def.spacing = 0.02f;
    def.capacity = 1500;
    FluidJetDef jet;
    jet.position = glm::vec3(0.1f, 0.9f, 0.0f);
    jet.speed = 3.0f;
    jet.rate = 16777217.0f;
    def.jets.push_back(jet);
    const FluidId fluid = createFluid(w.id, def);
    // Default h = 3.5 spacings: 12.25 particles per h-wide sub-cell at rest,
    // read up to ceil(8 x 12.25) = 98, 9 sub-cells around a particle.
    constexpr double kBound = 98.0 * 9.0;
    std::uint64_t overflows = 0;
    double mostNeighbours = 0.0;
    for (int step = 0; step < 5; ++step) {
        const FluidStepStats s = stepWorld(w.id, 1.0f / 60.0f).fluids.at(0);
        overflows += s.neighbourOverflows;
        mostNeighbours = std::max(mostNeighbours, s.meanNeighbours);
    }
    const FluidSnapshot snap = readFluid(w.id, fluid);
    ASSERT_EQ(snap.count(), 1500u);  // the capacity, all born in the first step
    // Unbounded, the pile's particles would keep about 1,499 neighbours each
    // in the first step (all within a few centimetres).
    EXPECT_LE(mostNeighbours, kBound);
    EXPECT_GT(overflows, 0u);
    for (std::size_t i = 0; i < snap.count(); ++i) {
        ASSERT_TRUE(std::isfinite(snap.position[i].x) && std::isfinite(snap.position[i].y)) << i;
        ASSERT_TRUE(std::isfinite(snap.velocity[i].x) && std::isfinite(snap.velocity[i].y)) << i;
    }
}

}  // namespace
}  // namespace spindrift
