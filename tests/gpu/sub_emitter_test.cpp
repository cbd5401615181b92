// Sub-emitters (EmitterDef::spawnOn) on both backends: a child gets `count`
// particles at each of its parent's births, deaths or collisions, born where
// the event happened with a share of the parent particle's velocity; the
// backends make the same children (the same serials, so the same random
// numbers), and births beyond the child's free slots are counted, not made.
#include "gpu_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

namespace spindrift {
namespace {

using test::GpuTest;

class SubEmitters : public GpuTest {};

constexpr float kDt = 1.0f / 60.0f;
constexpr Backend kBackends[] = {Backend::Cpu, Backend::Vulkan};

const char* name(Backend b) { return b == Backend::Cpu ? "cpu" : "vulkan"; }

// Ten parents flying along +x at 2 m/s from the origin, each living 0.1 s.
EmitterDef parents() {
    test::OneShot o;
    o.velocity = {2.0f, 0.0f, 0.0f};
    o.count = 10;
    o.lifetime = 0.1f;
    EmitterDef def = test::oneShotEmitter(o);
    def.name = "parents";
    def.shape.kind = SpawnShapeKind::Sphere;
    def.shape.radius = 0.3f;  // spread out, so each child's place names its parent
    return def;
}

// Born at rest relative to the event, 0.1 m above it, with half the parent's
// velocity; long-lived; no births of its own.
EmitterDef children(EmitterId parent, SpawnEvent event, std::uint32_t count, std::uint32_t capacity) {
    EmitterDef def;
    def.name = "children";
    def.capacity = capacity;
    def.rate = 0.0f;
    def.shape.kind = SpawnShapeKind::Point;
    def.shape.center = {0.0f, 0.1f, 0.0f};
    def.speed = {0.0f, 0.0f};
    def.lifetime = {10.0f, 10.0f};
    def.collision.enabled = false;
    def.spawnOn = {parent, event, count, 0.5f};
    return def;
}

std::vector<std::uint32_t> sortedSerials(const ParticleSnapshot& s) {
    std::vector<std::uint32_t> serials = s.birth;
    std::sort(serials.begin(), serials.end());
    return serials;
}

// Each death gives 5 children, exactly at the dying parent's last position
// plus the child shape's 0.1 m offset (a child is born at age 0: nothing
// moves it) with exactly half its velocity (1, 0, 0) m/s; 10 deaths, 50
// children, the same serials on both backends.
TEST_F(SubEmitters, EachDeathGivesCountChildrenWhereItDiedOnBothBackends) {
    std::vector<std::uint32_t> serials[2];
    for (int b = 0; b < 2; ++b) {
        SCOPED_TRACE(name(kBackends[b]));
        test::BackendWorld w(kBackends[b]);
        const EmitterId parent = createEmitter(w.id, parents());
        const EmitterId child = createEmitter(w.id, children(parent, SpawnEvent::Death, 5, 100));
        std::map<std::uint32_t, glm::vec3> lastPosition;  // parent serial -> where it was last seen
        std::uint64_t died = 0;
        for (int step = 0; step < 12; ++step) {
            const StepStats stats = stepWorld(w.id, kDt);
            died += stats.died;
            const ParticleSnapshot p = readParticles(w.id, parent);
            for (std::size_t i = 0; i < p.count(); ++i) {
                lastPosition[p.birth[i]] = p.position[i];
            }
        }
        EXPECT_EQ(died, 10u);
        const ParticleSnapshot c = readParticles(w.id, child);
        ASSERT_EQ(c.count(), 50u);
        std::map<std::uint32_t, int> perParent;
        for (std::size_t i = 0; i < c.count(); ++i) {
            EXPECT_NE(c.birth[i] & 0x40000000u, 0u) << "a sub-emitted serial";
            // Children do not move (speed 0 plus half the parent's velocity,
            // over the steps since): find the parent by the start position.
            const glm::vec3 start = c.position[i] - c.velocity[i] * c.age[i];
            int matched = 0;
            for (const auto& [serial, at] : lastPosition) {
                const glm::vec3 expected = at + glm::vec3(0.0f, 0.1f, 0.0f);
                if (glm::length(start - expected) < 1e-4f) {
                    ++perParent[static_cast<int>(serial)];
                    ++matched;
                }
            }
            EXPECT_EQ(matched, 1) << "child " << i << " at " << start.x << ", " << start.y << ", " << start.z;
            EXPECT_EQ(c.velocity[i], glm::vec3(1.0f, 0.0f, 0.0f));
        }
        EXPECT_EQ(perParent.size(), 10u);
        for (const auto& [serial, n] : perParent) {
            EXPECT_EQ(n, 5) << "children of parent " << serial;
        }
        serials[b] = sortedSerials(c);
    }
    EXPECT_EQ(serials[0], serials[1]) << "the backends made different children";
}

// Collisions: a stream falling on a ground plane; the child gets 3 particles
// per impact, so its births equal 3 x the parent's hits, step by step.
// Births: 2 per parent birth. Both against the step's own counts.
TEST_F(SubEmitters, CollisionsAndBirthsGiveCountChildrenEachOnBothBackends) {
    for (Backend backend : kBackends) {
        SCOPED_TRACE(name(backend));
        test::BackendWorld w(backend);
        ForceDef gravity;
        gravity.kind = ForceKind::Gravity;
        gravity.vector = {0.0f, -9.81f, 0.0f};
        createForce(w.id, gravity);
        createCollider(w.id, ColliderDef{});  // the ground plane y = 0
        EmitterDef rain;
        rain.name = "rain";
        rain.capacity = 400;
        rain.rate = 120.0f;
        rain.shape.kind = SpawnShapeKind::Disk;
        rain.shape.center = {0.0f, 0.5f, 0.0f};
        rain.shape.radius = 0.5f;
        rain.shape.direction = {0.0f, -1.0f, 0.0f};
        rain.speed = {1.0f, 2.0f};
        rain.lifetime = {3.0f, 3.0f};
        rain.collision.killOnCollision = true;
        const EmitterId parent = createEmitter(w.id, rain);
        const EmitterId splashes = createEmitter(w.id, children(parent, SpawnEvent::Collision, 3, 4000));
        EmitterDef birthDef = children(parent, SpawnEvent::Birth, 2, 4000);
        birthDef.name = "births";
        const EmitterId births = createEmitter(w.id, birthDef);
        std::uint64_t hits = 0, parentBirths = 0;
        for (int step = 0; step < 40; ++step) {
            const StepStats stats = stepWorld(w.id, kDt);
            hits += stats.colliderHits[0].hits;
            parentBirths = readParticles(w.id, parent).count() + hits;  // killed on impact: alive + dead
        }
        EXPECT_GT(hits, 20u);
        EXPECT_EQ(readParticles(w.id, splashes).count(), 3 * hits);
        EXPECT_EQ(readParticles(w.id, births).count(), 2 * parentBirths);
    }
}

// A child of capacity 20 owed 10 x 5 births makes 20 and counts 30 clamped;
// a grandchild on the child's births (a chain) gets one each, 20.
TEST_F(SubEmitters, BirthsBeyondTheFreeSlotsAreClampedAndChainsWorkOnBothBackends) {
    for (Backend backend : kBackends) {
        SCOPED_TRACE(name(backend));
        test::BackendWorld w(backend);
        const EmitterId parent = createEmitter(w.id, parents());
        const EmitterId child = createEmitter(w.id, children(parent, SpawnEvent::Death, 5, 20));
        EmitterDef grandchildDef = children(child, SpawnEvent::Birth, 1, 100);
        grandchildDef.name = "grandchildren";
        const EmitterId grandchild = createEmitter(w.id, grandchildDef);
        std::uint64_t clamped = 0;
        for (int step = 0; step < 12; ++step) {
            clamped += stepWorld(w.id, kDt).clamped;
        }
        EXPECT_EQ(readParticles(w.id, child).count(), 20u);
        EXPECT_EQ(clamped, 30u);
        EXPECT_EQ(readParticles(w.id, grandchild).count(), 20u);
    }
}

}  // namespace
}  // namespace spindrift
