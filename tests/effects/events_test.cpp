// Collision and death events on the CPU backend, against closed forms: a
// particle dropped from a known height hits the ground when and as fast as
// free fall says, and dies when its lifetime says. (The Vulkan backend is
// checked against these events in tests/gpu/gpu_world_test.cpp.)
#include "effects_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

using test::OneShot;
using test::ScopedWorld;

constexpr float kG = 9.81f;   // m/s^2
constexpr float kDt = 0.01f;  // s

// A particle at rest at height h falls for t* = sqrt(2 h / g) s and meets the
// ground at v* = sqrt(2 g h) m/s. Semi-implicit Euler (the default) falls
// g dt t / 2 ahead of the closed form, so it reaches the ground up to half a
// step early; the hit is reported in the step that crosses the plane, which
// starts within [t* - 1.5 dt, t*], with the speed at the start of that step,
// g times that time: within [v* - 1.5 g dt, v*]. Bounds with 2 dt for float
// rounding of the step boundary. Position: the end of the step, on or above
// the plane and below what half a step of the bounce (e = 0.5) can reach.
TEST(Events, FallingParticleHitsTheGroundWhenAndAsFastAsFreeFallSays) {
    ScopedWorld w;
    createForce(w.id, test::gravity({0.0f, -kG, 0.0f}));
    createCollider(w.id, test::groundPlane(0.5f));
    const float h = 1.25f;
    OneShot shot;
    shot.start = {0.0f, h, 0.0f};
    createEmitter(w.id, test::oneShotEmitter(shot));
    for (int s = 0; s < 60; ++s) {
        stepWorld(w.id, kDt);
    }
    EventBatch batch = takeEvents(w.id);
    ASSERT_FALSE(batch.events.empty());
    const ParticleEvent& hit = batch.events.front();
    EXPECT_EQ(hit.kind, ParticleEventKind::Collision);
    EXPECT_EQ(hit.collider.index, 1u);
    EXPECT_EQ(hit.emitter.index, 1u);
    EXPECT_EQ(hit.birth, 0u);
    const float impactTime = std::sqrt(2.0f * h / kG);  // 0.505 s
    const float impactSpeed = std::sqrt(2.0f * kG * h); // 4.95 m/s
    EXPECT_LE(static_cast<float>(hit.step), impactTime / kDt);
    EXPECT_GE(static_cast<float>(hit.step), impactTime / kDt - 2.0f);
    EXPECT_LE(hit.speed, impactSpeed + 1e-4f);
    EXPECT_GE(hit.speed, impactSpeed - 2.0f * kG * kDt);
    EXPECT_GE(hit.position.y, 0.0f);
    EXPECT_LE(hit.position.y, 0.5f * impactSpeed * kDt + 1e-4f);
    EXPECT_EQ(batch.dropped, 0u);
    EXPECT_TRUE(takeEvents(w.id).events.empty());  // handed out once
}

// Lifetime L: the particle dies in the step whose end reaches age L, step
// L / dt - 1 (0-based; within one for the rounding of the ages), with one
// death event that names no collider (it never touched one).
TEST(Events, ParticleDiesWhenItsLifetimeEnds) {
    ScopedWorld w;
    OneShot shot;
    shot.lifetime = 0.5f;
    shot.velocity = {1.0f, 0.0f, 0.0f};
    createEmitter(w.id, test::oneShotEmitter(shot));
    for (int s = 0; s < 80; ++s) {
        stepWorld(w.id, kDt);
    }
    EventBatch batch = takeEvents(w.id);
    ASSERT_EQ(batch.events.size(), 1u);
    const ParticleEvent& death = batch.events[0];
    EXPECT_EQ(death.kind, ParticleEventKind::Death);
    EXPECT_EQ(death.collider.index, 0u);
    EXPECT_NEAR(static_cast<float>(death.step), shot.lifetime / kDt - 1.0f, 1.0f);
    EXPECT_NEAR(death.speed, 1.0f, 1e-6f);  // no force acts: the speed it was born with
    EXPECT_NEAR(death.position.x, shot.lifetime, 2.0f * kDt);
}

// Kill on collision: one collision and one death in the same step, the death
// naming the collider that killed it; with events off nothing is recorded.
TEST(Events, KillOnCollisionReportsTheHitAndTheKiller) {
    for (std::uint32_t capacity : {4096u, 0u}) {
        WorldDef def;
        def.threads = 1;
        def.eventCapacity = capacity;
        WorldId w = createWorld(def);
        createForce(w, test::gravity({0.0f, -kG, 0.0f}));
        createCollider(w, test::groundPlane(0.5f));
        OneShot shot;
        shot.start = {0.0f, 0.5f, 0.0f};
        EmitterDef e = test::oneShotEmitter(shot);
        e.collision.killOnCollision = true;
        createEmitter(w, e);
        for (int s = 0; s < 60; ++s) {
            stepWorld(w, kDt);
        }
        EventBatch batch = takeEvents(w);
        destroyWorld(w);
        if (capacity == 0) {
            EXPECT_TRUE(batch.events.empty());
            EXPECT_EQ(batch.dropped, 0u);
            continue;
        }
        ASSERT_EQ(batch.events.size(), 2u);
        EXPECT_EQ(batch.events[0].kind, ParticleEventKind::Collision);
        EXPECT_EQ(batch.events[1].kind, ParticleEventKind::Death);
        EXPECT_EQ(batch.events[1].collider.index, 1u);
        EXPECT_EQ(batch.events[0].step, batch.events[1].step);
    }
}

// A world whose events are never taken (the command-line renderer's) must
// not grow: past 32 steps' worth the oldest waiting events are dropped and
// counted, down to 16 steps' worth (WorldDef::eventCapacity). Independent
// references: conservation (every hit and death is an event, kept or counted
// dropped) and the step counts, which say how many events the last steps
// had room for.
TEST(Events, UntakenEventsStayBoundedAndTheNewestAreKept) {
    constexpr std::uint32_t kCapacity = 10;  // per step; the rain below makes more
    ScopedWorld w(1, 7, Backend::Cpu, 1, kCapacity);
    createForce(w.id, test::gravity({0.0f, -kG, 0.0f}));
    createCollider(w.id, test::groundPlane(0.5f));
    EmitterDef rain;  // recycle: a steady 2000 particles, many striking the ground each step
    rain.lifecycle = Lifecycle::Recycle;
    rain.capacity = 2000;
    rain.lifetime = {0.2f, 0.4f};
    rain.speed = {1.0f, 3.0f};
    rain.shape.kind = SpawnShapeKind::Sphere;
    rain.shape.center = {0.0f, 0.1f, 0.0f};
    rain.shape.radius = 0.1f;
    rain.shape.direction = {0.0f, -1.0f, 0.0f};
    rain.shape.spreadAngle = 0.5f;
    createEmitter(w.id, rain);
    constexpr int kSteps = 200;
    std::uint64_t offered = 0;
    std::vector<std::uint64_t> offeredPerStep;
    for (int s = 0; s < kSteps; ++s) {
        const StepStats st = stepWorld(w.id, kDt);
        offered += st.collisions + st.died;
        offeredPerStep.push_back(st.collisions + st.died);
    }
    const EventBatch batch = takeEvents(w.id);
    ASSERT_GT(offered, 4u * kSteps * kCapacity);  // not vacuous: far more than is kept
    EXPECT_GE(batch.events.size(), 16u * kCapacity);
    EXPECT_LE(batch.events.size(), 32u * kCapacity);
    EXPECT_EQ(batch.events.size() + batch.dropped, offered);
    // The newest are kept: the last step's events are the batch's last ones,
    // as many as that step had room for.
    std::size_t lastStep = 0;
    for (const ParticleEvent& e : batch.events) lastStep += e.step == kSteps - 1 ? 1 : 0;
    EXPECT_EQ(lastStep, std::min<std::uint64_t>(kCapacity, offeredPerStep.back()));
    EXPECT_EQ(batch.events.back().step, static_cast<std::uint64_t>(kSteps - 1));
}

}  // namespace
}  // namespace spindrift
