// Non-finite numbers arising in flight (issue 14): an attractor 1e-7 m from
// the spawn point with strength 1e30 pulls a 1 kg particle with 1e30 x
// (1 m / 0.01 m)^2 = 1e34 N (the force is softened within 1 % of its radius),
// so in its first 1/60 s step it reaches 1.7e32 m/s, whose square overflows
// single precision (3.4e38), and goes on to infinity and NaN (the issue saw
// "-nan" in the caches). Each such particle must be removed where it arises
// and counted, on both backends alike, while an emitter out of the
// attractor's range goes on as if nothing happened; no snapshot or event may
// then hold NaN or infinity.
#include "gpu/gpu_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

EmitterDef pointEmitter(const char* name, glm::vec3 at, Lifecycle lifecycle) {
    EmitterDef e;
    e.name = name;
    e.capacity = 256;
    e.rate = 600.0f;
    e.lifecycle = lifecycle;
    e.shape.kind = SpawnShapeKind::Point;
    e.shape.center = at;
    e.speed = {0.0f, 0.0f};
    e.lifetime = {100.0f, 100.0f};
    return e;
}

struct Outcome {
    std::uint64_t nonFinite = 0, born = 0, died = 0, alive = 0, events = 0;
    std::size_t nearLive = 0, farLive = 0;
};

void expectFinite(const ParticleSnapshot& p) {
    for (std::size_t i = 0; i < p.count(); ++i) {
        EXPECT_TRUE(finite(p.position[i]) && finite(p.velocity[i])) << "particle " << i;
        EXPECT_TRUE(std::isfinite(p.size[i]) && std::isfinite(p.rotation[i]) && std::isfinite(p.age[i]));
        EXPECT_TRUE(finite(glm::vec3(p.color[i])) && std::isfinite(p.color[i].a));
    }
}

Outcome runAttractorAtSpawn(Backend backend) {
    test::BackendWorld w(backend);
    const glm::vec3 near(0.0f), far(1000.0f, 0.0f, 0.0f);
    ForceDef attractor;
    attractor.kind = ForceKind::Attractor;
    attractor.position = glm::vec3(1.0e-7f, 0.0f, 0.0f);
    attractor.strength = 1.0e30f;
    attractor.radius = 1.0f;
    attractor.falloff = 2.0f;
    attractor.range = 10.0f;  // the far emitter, 1 km away, feels nothing
    createForce(w.id, attractor);  // before the emitters, which take the world's forces
    const EmitterId spawned = createEmitter(w.id, pointEmitter("spawn", near, Lifecycle::Spawn));
    const EmitterId recycled = createEmitter(w.id, pointEmitter("recycle", near, Lifecycle::Recycle));
    const EmitterId outside = createEmitter(w.id, pointEmitter("far", far, Lifecycle::Spawn));
    Outcome o;
    const float dt = 1.0f / 60.0f;
    for (int i = 0; i < 20; ++i) {
        const StepStats s = stepWorld(w.id, dt);
        o.nonFinite += s.nonFinite;
        o.born += s.born;
        o.died += s.died;
        o.alive = s.alive;
    }
    const EventBatch events = takeEvents(w.id);
    o.events = events.events.size();
    for (const ParticleEvent& e : events.events) {
        EXPECT_TRUE(finite(e.position) && std::isfinite(e.speed));
    }
    const ParticleSnapshot a = readParticles(w.id, spawned), b = readParticles(w.id, recycled),
                           c = readParticles(w.id, outside);
    expectFinite(a);
    expectFinite(b);
    expectFinite(c);
    o.nearLive = a.count() + b.count();
    o.farLive = c.count();
    return o;
}

// What both backends must show: 600/s for 20 steps of 1/60 s is 200 births
// per emitter (the far one keeps all of them, being out of range and living
// 100 s); every particle born at the attractor is removed, none dies.
void expectRemovedAndCounted(const Outcome& o) {
    EXPECT_GT(o.nonFinite, 0u);
    EXPECT_EQ(o.nearLive, 0u);
    EXPECT_EQ(o.farLive, 200u);
    EXPECT_EQ(o.alive, o.farLive);
    EXPECT_EQ(o.died, 0u);
    EXPECT_EQ(o.born, o.farLive + o.nonFinite);  // every birth at the attractor was removed
    EXPECT_EQ(o.events, 0u);                     // a removal is not a death event
}

TEST(NonFinite, CpuParticlesAtAnAttractorAreRemovedAndCounted) {
    expectRemovedAndCounted(runAttractorAtSpawn(Backend::Cpu));
}

class NonFiniteGpu : public test::GpuTest {};

TEST_F(NonFiniteGpu, VulkanRemovesAndCountsTheSameParticlesAsTheCpu) {
    const Outcome gpu = runAttractorAtSpawn(Backend::Vulkan);
    expectRemovedAndCounted(gpu);
    const Outcome cpu = runAttractorAtSpawn(Backend::Cpu);
    EXPECT_EQ(gpu.nonFinite, cpu.nonFinite);
    EXPECT_EQ(gpu.born, cpu.born);
    EXPECT_EQ(gpu.alive, cpu.alive);
}

}  // namespace
}  // namespace spindrift
