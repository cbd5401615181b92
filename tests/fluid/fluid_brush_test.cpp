// The viewer's brush on a fluid: removeFluid and pourFluid (fluid.h), counted
// against the lattice points a circle holds.
#include <spindrift/fluid.h>
#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <algorithm>

namespace {

using namespace spindrift;

struct BrushWorld {
    WorldId world = createWorld(WorldDef{});
    FluidId fluid;
    explicit BrushWorld(bool block) {
        FluidDef def;
        def.spacing = 0.1f;
        def.gravity = glm::vec3(0.0f);
        def.capacity = 1000;
        // A 1 m square at 0.1 m: particles at (k + 1/2) x 0.1, k = 0..9.
        if (block) def.blocks.push_back({glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 0.0f), glm::vec3(0.0f)});
        fluid = createFluid(world, def);
    }
    ~BrushWorld() { destroyWorld(world); }
};

// Around (0.5, 0.5) the lattice points lie at offsets of +-0.05 and +-0.15
// per axis; within 0.2 m are the 4 at (0.05, 0.05) (distance 0.071) and the
// 8 at (0.05, 0.15) (0.158), not those at (0.15, 0.15) (0.212).
constexpr std::uint32_t kInCircle = 12;

TEST(FluidBrush, RemoveTakesTheParticlesInTheCircleAndKeepsTheOthersIds) {
    BrushWorld w(true);
    ASSERT_EQ(readFluid(w.world, w.fluid).count(), 100u);
    EXPECT_EQ(removeFluid(w.world, w.fluid, glm::vec3(0.5f, 0.5f, 0.0f), 0.2f), kInCircle);
    const FluidSnapshot after = readFluid(w.world, w.fluid);
    ASSERT_EQ(after.count(), 100u - kInCircle);
    EXPECT_TRUE(std::is_sorted(after.id.begin(), after.id.end()));
    for (std::size_t i = 0; i < after.count(); ++i) {
        EXPECT_GT(glm::distance(glm::vec2(after.position[i]), glm::vec2(0.5f)), 0.2f);
        // A block's particle id is its lattice index, row by row.
        const std::uint32_t k = after.id[i];
        EXPECT_NEAR(after.position[i].x, 0.1f * float(k % 10) + 0.05f, 1e-5f) << k;
        EXPECT_NEAR(after.position[i].y, 0.1f * float(k / 10) + 0.05f, 1e-5f) << k;
    }
    EXPECT_NO_THROW(stepWorld(w.world, 1.0f / 60.0f));
}

TEST(FluidBrush, PourFillsOnlyTheEmptyLatticePoints) {
    BrushWorld empty(false);
    EXPECT_EQ(pourFluid(empty.world, empty.fluid, glm::vec3(0.5f, 0.5f, 0.0f), 0.2f), kInCircle);
    EXPECT_EQ(pourFluid(empty.world, empty.fluid, glm::vec3(0.5f, 0.5f, 0.0f), 0.2f), 0u) << "poured twice";

    BrushWorld full(true);
    EXPECT_EQ(pourFluid(full.world, full.fluid, glm::vec3(0.5f, 0.5f, 0.0f), 0.2f), 0u);
    removeFluid(full.world, full.fluid, glm::vec3(0.5f, 0.5f, 0.0f), 0.2f);
    EXPECT_EQ(pourFluid(full.world, full.fluid, glm::vec3(0.5f, 0.5f, 0.0f), 0.2f), kInCircle);
    EXPECT_EQ(readFluid(full.world, full.fluid).count(), 100u);
    EXPECT_THROW(pourFluid(full.world, full.fluid, glm::vec3(0.5f), 20.0f), Error);
}

}  // namespace
