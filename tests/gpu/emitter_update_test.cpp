// setEmitterRate / setEmitterSpeed: live changes act on births from the next
// step on, identically on both backends, and refuse what cannot change.
#include "gpu/gpu_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

EmitterDef steadyEmitter() {
    EmitterDef e;
    e.name = "steady";
    e.capacity = 4096;
    e.rate = 600.0f;
    e.shape.kind = SpawnShapeKind::Point;
    e.speed = {1.0f, 1.0f};
    e.lifetime = {100.0f, 100.0f};
    return e;
}

/// Speeds of the particles born after the change: birth serial >= `from`.
std::vector<float> speedsSince(WorldId world, EmitterId id, std::uint32_t from) {
    const ParticleSnapshot p = readParticles(world, id);
    std::vector<float> speeds;
    for (std::size_t i = 0; i < p.count(); ++i) {
        if (p.birth[i] >= from) speeds.push_back(glm::length(p.velocity[i]));
    }
    return speeds;
}

void checkLiveChanges(Backend backend) {
    test::BackendWorld w(backend);
    const EmitterId id = createEmitter(w.id, steadyEmitter());
    const float dt = 1.0f / 60.0f;
    for (int i = 0; i < 10; ++i) stepWorld(w.id, dt);
    const auto bornBefore = static_cast<std::uint32_t>(readParticles(w.id, id).count());
    ASSERT_GT(bornBefore, 0u);

    // No gravity, no forces: a particle keeps its launch speed.
    setEmitterSpeed(w.id, id, {3.0f, 4.0f});
    EXPECT_FLOAT_EQ(emitterDef(w.id, id).speed.min, 3.0f);
    for (int i = 0; i < 10; ++i) stepWorld(w.id, dt);
    const std::vector<float> speeds = speedsSince(w.id, id, bornBefore);
    ASSERT_FALSE(speeds.empty());
    for (float s : speeds) {
        EXPECT_GE(s, 3.0f - 1e-4f);
        EXPECT_LE(s, 4.0f + 1e-4f);
    }
    // Those born before keep theirs.
    const ParticleSnapshot all = readParticles(w.id, id);
    for (std::size_t i = 0; i < all.count(); ++i) {
        if (all.birth[i] < bornBefore) {
            EXPECT_NEAR(glm::length(all.velocity[i]), 1.0f, 1e-4f);
        }
    }

    setEmitterRate(w.id, id, 0.0f);
    const std::size_t alive = readParticles(w.id, id).count();
    StepStats stats;
    for (int i = 0; i < 10; ++i) stats = stepWorld(w.id, dt);
    EXPECT_EQ(stats.born, 0u);
    EXPECT_EQ(readParticles(w.id, id).count(), alive);

    // Rejected values change nothing.
    EXPECT_THROW(setEmitterSpeed(w.id, id, {5.0f, 2.0f}), Error);
    EXPECT_THROW(setEmitterRate(w.id, id, -1.0f), Error);
    EXPECT_FLOAT_EQ(emitterDef(w.id, id).speed.max, 4.0f);
    EXPECT_FLOAT_EQ(emitterDef(w.id, id).rate, 0.0f);
}

TEST(EmitterUpdate, CpuRateAndSpeedActOnNewBirths) { checkLiveChanges(Backend::Cpu); }

class EmitterUpdateGpu : public test::GpuTest {};

TEST_F(EmitterUpdateGpu, VulkanRateAndSpeedActOnNewBirths) { checkLiveChanges(Backend::Vulkan); }

TEST(EmitterUpdate, StatelessEmitterRefuses) {
    test::ScopedWorld w;
    EmitterDef e = steadyEmitter();
    e.stateless = true;
    const EmitterId id = createEmitter(w.id, e);
    EXPECT_THROW(setEmitterRate(w.id, id, 10.0f), Error);
    EXPECT_THROW(setEmitterSpeed(w.id, id, {2.0f, 2.0f}), Error);
}

}  // namespace
}  // namespace spindrift
