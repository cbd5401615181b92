// Birth and death: emission counts, recycle phase, capacity clamping.
#include "effects/effects_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>

namespace spindrift {
namespace {

using test::ScopedWorld;

EmitterDef spawner(float rate, std::uint32_t capacity, float lifetime) {
    EmitterDef e;
    e.lifecycle = Lifecycle::Spawn;
    e.rate = rate;
    e.capacity = capacity;
    e.lifetime = {lifetime, lifetime};
    return e;
}

// Births equal rate x time exactly (the carry keeps fractional particles
// between steps), for a rate that is not a multiple of the step rate.
TEST(Lifecycle, BirthsEqualRateTimesTime) {
    ScopedWorld w;
    createEmitter(w.id, spawner(137.0f, 100000, 100.0f));
    std::uint64_t born = 0;
    for (int i = 0; i < 600; ++i) {
        born += stepWorld(w.id, 1.0f / 60.0f).born;
    }
    // 137 / s for 10 s; the carry is a double, so at most one particle of drift.
    EXPECT_NEAR(static_cast<double>(born), 1370.0, 1.0);
}

// Steady state: with rate r and lifetime L, r L particles are alive.
TEST(Lifecycle, SpawnSteadyStateAliveIsRateTimesLifetime) {
    ScopedWorld w;
    createEmitter(w.id, spawner(200.0f, 10000, 1.5f));
    StepStats s;
    for (int i = 0; i < 300; ++i) {
        s = stepWorld(w.id, 1.0f / 60.0f);
    }
    EXPECT_NEAR(static_cast<double>(s.alive), 300.0, 2.0);
}

// Births owed beyond the capacity are counted, never stored (issue 14): a
// rate of 1e12 once stored 1.7e10 birth ages a step (bad_alloc; 1e10 took
// 650 MB for this capacity-100 emitter). Now a step holds at most the
// capacity's ages. The bound on time (1 s for 20 steps, ASan and a loaded
// machine included; microseconds in fact) fails if anything grew with the
// rate. The first step places 100, later ones none (the lifetime is long);
// every birth owed is placed or counted as clamped: 1e12 x dt a step, to
// within 1 (the carry, and the step's length taken as a difference of
// double clock readings, t1 - t0, move the floor by at most one).
TEST(Lifecycle, HugeRateIsClampedToCapacityBeforeAnythingIsStored) {
    ScopedWorld w;
    createEmitter(w.id, spawner(1e12f, 100, 100.0f));
    const float dt = 1.0f / 60.0f;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < 20; ++i) {
        const StepStats s = stepWorld(w.id, dt);
        EXPECT_EQ(s.born, i == 0 ? 100u : 0u) << "step " << i;
        EXPECT_NEAR(static_cast<double>(s.born + s.clamped), static_cast<double>(1e12f) * dt, 1.0) << "step " << i;
        EXPECT_EQ(s.alive, 100u) << "step " << i;
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

// The largest float rate over the longest step owes ~3.4e38 births, far past
// any integer: the count saturates at the largest std::uint64_t instead of
// wrapping or (as a cast of the double was) being undefined; rate 1e30 used to
// emit nothing at all.
TEST(Lifecycle, RateOfFloatMaxFillsTheCapacityAndSaturatesTheCount) {
    ScopedWorld w;
    createEmitter(w.id, spawner(std::numeric_limits<float>::max(), 100, 100.0f));
    const StepStats s = stepWorld(w.id, 1.0f);
    EXPECT_EQ(s.born, 100u);
    EXPECT_EQ(s.alive, 100u);
    EXPECT_EQ(s.clamped, std::numeric_limits<std::uint64_t>::max());
}

// A burst larger than the capacity (the API allows up to
// kEmitterMaxBurstCount) is cut to the capacity in the schedule; the rest is
// counted as before.
TEST(Lifecycle, BurstBeyondCapacityIsCutInTheSchedule) {
    ScopedWorld w;
    EmitterDef e = spawner(0.0f, 100, 10.0f);
    e.bursts = {{0.0f, kEmitterMaxBurstCount}, {0.0f, 5}};
    createEmitter(w.id, e);
    const StepStats s = stepWorld(w.id, 0.01f);
    EXPECT_EQ(s.born, 100u);
    EXPECT_EQ(s.clamped, kEmitterMaxBurstCount + 5u - 100u);
}

// Emission beyond capacity is clamped and counted, never lost silently and
// never overwriting live particles.
TEST(Lifecycle, EmissionBeyondCapacityIsClampedAndCounted) {
    ScopedWorld w;
    EmitterDef e = spawner(0.0f, 100, 10.0f);
    e.bursts = {{0.0f, 250}};
    EmitterId id = createEmitter(w.id, e);
    StepStats s = stepWorld(w.id, 0.01f);
    EXPECT_EQ(s.born, 100u);
    EXPECT_EQ(s.clamped, 150u);
    EXPECT_EQ(s.alive, 100u);
    ParticleSnapshot p = readParticles(w.id, id);
    ASSERT_EQ(p.count(), 100u);
    // Every live particle has its own serial: none overwritten.
    std::vector<bool> seen(100, false);
    for (std::uint32_t b : p.birth) {
        ASSERT_LT(b, 100u);
        EXPECT_FALSE(seen[b]);
        seen[b] = true;
    }
}

// Dead slots are reused: 10 lifetimes of a full emitter run on 1 capacity's slots.
TEST(Lifecycle, DeadSlotsAreReused) {
    ScopedWorld w;
    createEmitter(w.id, spawner(100.0f, 120, 1.0f));
    std::uint64_t born = 0, clamped = 0;
    for (int i = 0; i < 600; ++i) {
        StepStats s = stepWorld(w.id, 1.0f / 60.0f);
        born += s.born;
        clamped += s.clamped;
    }
    EXPECT_EQ(clamped, 0u);
    EXPECT_NEAR(static_cast<double>(born), 1000.0, 1.0);
}

// Recycle mode: slot i is first born at i L / N and re-born every L, keeping
// the remainder of its age, so its age at time t is (t - i L / N) mod L. After
// 20 lifetimes the float rounding of the accumulated ages is far below 1e-3 s.
TEST(Lifecycle, RecycleKeepsEvenPhase) {
    ScopedWorld w;
    EmitterDef e;
    e.lifecycle = Lifecycle::Recycle;
    e.capacity = 16;
    e.lifetime = {0.8f, 0.8f};
    EmitterId id = createEmitter(w.id, e);
    const float dt = 1.0f / 64.0f;
    const int steps = 20 * 64 + 5;  // just over 25 lifetimes
    for (int i = 0; i < steps; ++i) {
        stepWorld(w.id, dt);
    }
    ParticleSnapshot p = readParticles(w.id, id);
    ASSERT_EQ(p.count(), 16u);
    const double t = dt * steps;
    for (std::size_t k = 0; k < p.count(); ++k) {
        double phase = std::fmod(t - p.slot[k] * 0.8 / 16.0, 0.8);
        // Distance on the circle of ages, so a slot just re-born (age ~0) and the
        // expectation just below L (~0.8) still compare as equal.
        double gap = std::abs(p.age[k] - phase);
        EXPECT_LT(std::min(gap, 0.8 - gap), 1e-3) << "slot " << p.slot[k] << " age " << p.age[k];
        // Each life has its own serial: slot + capacity * lives.
        EXPECT_EQ(p.birth[k] % 16u, p.slot[k]);
    }
}

// Over-life curves: colour and size follow the piecewise-linear curves at the
// particle's normalised age.
TEST(Lifecycle, ColorAndSizeFollowOverLifeCurves) {
    ScopedWorld w;
    EmitterDef e = spawner(0.0f, 1, 2.0f);
    e.bursts = {{0.0f, 1}};
    e.color = {glm::vec4(1.0f, 0.5f, 0.25f, 1.0f), glm::vec4(1.0f, 0.5f, 0.25f, 1.0f)};
    e.size = {0.4f, 0.4f};
    e.colorOverLife.keys = {{0.0f, glm::vec4(1.0f)}, {0.5f, glm::vec4(0.0f, 1.0f, 1.0f, 0.5f)}, {1.0f, glm::vec4(0.0f)}};
    e.sizeOverLife.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(3.0f)}};
    EmitterId id = createEmitter(w.id, e);
    ParticleSnapshot p = test::run(w.id, id, 0.05f, 10);  // age 0.5 s: t = 0.25
    ASSERT_EQ(p.count(), 1u);
    // Colour curve at t = 0.25: halfway between keys 0 and 1.
    EXPECT_NEAR(p.color[0].r, 1.0f * 0.5f, 1e-5f);
    EXPECT_NEAR(p.color[0].g, 0.5f * 1.0f, 1e-5f);
    EXPECT_NEAR(p.color[0].b, 0.25f * 1.0f, 1e-5f);
    EXPECT_NEAR(p.color[0].a, 0.75f, 1e-5f);
    EXPECT_NEAR(p.size[0], 0.4f * 1.5f, 1e-5f);
}

// Duration: a spawn emitter stops emitting after its duration.
TEST(Lifecycle, DurationStopsEmission) {
    ScopedWorld w;
    EmitterDef e = spawner(100.0f, 1000, 100.0f);
    e.duration = 0.5f;
    createEmitter(w.id, e);
    std::uint64_t born = 0;
    for (int i = 0; i < 60; ++i) {
        born += stepWorld(w.id, 1.0f / 60.0f).born;
    }
    EXPECT_NEAR(static_cast<double>(born), 50.0, 1.0);
}

}  // namespace
}  // namespace spindrift
