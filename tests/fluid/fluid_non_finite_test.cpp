// Non-finite fluid particles (issue 14): a fluid whose gravity is 3e38 m/s^2
// (finite, so accepted) reaches about 5e36 m/s in its first substep, whose
// square (every contact, speed and substep count takes a length) overflows
// single precision; left alone the speed itself passes 3.4e38 m/s within 70
// steps. Each such particle is removed in the substep where it arises and
// counted; a calm fluid in the same world keeps every particle; no snapshot
// holds NaN or infinity.
#include "fluid/fluid_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

FluidDef smallFluid(const char* name, glm::vec3 gravity, float x0) {
    FluidDef def;
    def.name = name;
    def.dimension = 2;
    def.spacing = 0.1f;
    def.gravity = gravity;
    FluidBlockDef block;
    block.min = glm::vec3(x0, 0.0f, 0.0f);
    block.max = glm::vec3(x0 + 0.6f, 0.6f, 0.0f);  // 6 x 6 = 36 particles
    def.blocks.push_back(block);
    return def;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TEST(FluidNonFinite, ABlownUpFluidLosesItsParticlesAndTheCalmOneNone) {
    test::FluidWorld w;
    const FluidId wild = createFluid(w.id, smallFluid("wild", glm::vec3(3.0e38f, 3.0e38f, 0.0f), 0.0f));
    const FluidId calm = createFluid(w.id, smallFluid("calm", glm::vec3(0.0f, -9.81f, 0.0f), 10.0f));
    const std::size_t start = readFluid(w.id, wild).position.size();
    ASSERT_EQ(start, 36u);
    std::uint64_t removedWild = 0, removedCalm = 0;
    for (int i = 0; i < 40; ++i) {
        const StepStats s = stepWorld(w.id, 1.0f / 60.0f);
        ASSERT_EQ(s.fluids.size(), 2u);
        removedWild += s.fluids[0].nonFinite;
        removedCalm += s.fluids[1].nonFinite;
        EXPECT_EQ(s.fluids[0].particles + removedWild, start);  // removed ones are gone, and counted
    }
    EXPECT_GT(removedWild, 0u);
    EXPECT_EQ(removedCalm, 0u);
    for (const FluidId id : {wild, calm}) {
        const FluidSnapshot s = readFluid(w.id, id);
        for (std::size_t i = 0; i < s.position.size(); ++i) {
            EXPECT_TRUE(finite(s.position[i]) && finite(s.velocity[i])) << "particle " << i;
        }
    }
    // The calm block fell freely for 40 steps (no floor): every particle is
    // still there and below where it started.
    const FluidSnapshot c = readFluid(w.id, calm);
    ASSERT_EQ(c.position.size(), start);
    for (const glm::vec3& x : c.position) EXPECT_LT(x.y, 0.0f);
}

}  // namespace
}  // namespace spindrift
