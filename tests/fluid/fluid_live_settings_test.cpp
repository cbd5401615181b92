// setFluidSolver (the viewer's live fluid settings): changing the solver
// before a step gives exactly the fluid that was created with those settings,
// and values FluidDef rejects change nothing.
#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <cstring>

namespace spindrift {
namespace {

FluidDef block(std::uint32_t iterations, float baumgarte) {
    FluidDef def;
    def.name = "water";
    def.spacing = 0.05f;
    def.iterations = iterations;
    def.baumgarte = baumgarte;
    def.blocks = {FluidBlockDef{{0.0f, 0.0f, 0.0f}, {0.6f, 0.8f, 0.0f}, glm::vec3(0.0f)}};
    return def;
}

FluidSnapshot run(bool changeLive) {
    WorldDef wd;
    wd.threads = 1;
    const WorldId w = createWorld(wd);
    ColliderDef floor;
    createCollider(w, floor);
    const FluidId f = createFluid(w, changeLive ? block(4, 0.05f) : block(9, 0.2f));
    if (changeLive) setFluidSolver(w, f, 9, 0.2f);
    for (int i = 0; i < 30; ++i) stepWorld(w, 1.0f / 60.0f);
    FluidSnapshot s = readFluid(w, f);
    destroyWorld(w);
    return s;
}

TEST(FluidLiveSettings, SolverChangeEqualsCreatingWithIt) {
    const FluidSnapshot live = run(true), made = run(false);
    ASSERT_EQ(live.count(), made.count());
    ASSERT_GT(live.count(), 100u);
    EXPECT_EQ(std::memcmp(live.position.data(), made.position.data(), live.count() * sizeof(glm::vec3)), 0);
    EXPECT_EQ(std::memcmp(live.velocity.data(), made.velocity.data(), live.count() * sizeof(glm::vec3)), 0);
}

TEST(FluidLiveSettings, RejectedValuesChangeNothing) {
    const WorldId w = createWorld(WorldDef{});
    const FluidId f = createFluid(w, block(4, 0.05f));
    EXPECT_THROW(setFluidSolver(w, f, 0, 0.05f), Error);
    EXPECT_THROW(setFluidSolver(w, f, 4, 1.5f), Error);
    EXPECT_THROW(setFluidSolver(w, f, 4, 0.0f), Error);  // below kFluidMinBaumgarte
    EXPECT_EQ(fluidDef(w, f).iterations, 4u);
    EXPECT_FLOAT_EQ(fluidDef(w, f).baumgarte, 0.05f);
    destroyWorld(w);
}

}  // namespace
}  // namespace spindrift
