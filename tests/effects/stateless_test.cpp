// Stateless emitters: the closed form, nothing stored.
#include "effects/effects_test_util.h"
#include "effects/stateless.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace spindrift {
namespace {

EmitterDef sparks() {
    EmitterDef e;
    e.stateless = true;
    e.rate = 50.0f;
    e.capacity = 10000;
    e.lifetime = {0.5f, 1.0f};
    e.speed = {2.0f, 6.0f};
    e.shape.kind = SpawnShapeKind::Sphere;
    e.shape.radius = 0.2f;
    e.shape.spreadAngle = 1.0f;
    e.statelessGravity = {0.0f, -9.81f, 0.0f};
    e.bursts = {{0.25f, 40}};
    return e;
}

// Each particle moves on p0 + v0 a + g a^2 / 2 with a its age: the birth state
// is the same key's state at age 0, from the same function.
TEST(Stateless, ParticlesFollowTheClosedForm) {
    EmitterDef e = sparks();
    ParticleSnapshot born = evaluateStateless(e, 3, 0, 0.3f);
    ParticleSnapshot later = evaluateStateless(e, 3, 0, 0.6f);
    ASSERT_GT(born.count(), 0u);
    int matched = 0;
    for (std::size_t i = 0; i < later.count(); ++i) {
        for (std::size_t j = 0; j < born.count(); ++j) {
            if (later.birth[i] != born.birth[j]) {
                continue;
            }
            float a0 = born.age[j], a1 = later.age[i];
            EXPECT_NEAR(a1 - a0, 0.3f, 1e-6f);
            // From p = p0 + v0 a + g a^2 / 2 and v = v0 + g a: p0 = p - v a + g a^2 / 2.
            glm::vec3 p0 = born.position[j] - born.velocity[j] * a0 + glm::vec3(0.0f, -9.81f, 0.0f) * (0.5f * a0 * a0);
            glm::vec3 v0 = born.velocity[j] + glm::vec3(0.0f, 9.81f, 0.0f) * a0;
            glm::vec3 expected = p0 + v0 * a1 + glm::vec3(0.0f, -9.81f, 0.0f) * (0.5f * a1 * a1);
            EXPECT_NEAR(glm::length(later.position[i] - expected), 0.0f, 1e-5f);
            ++matched;
        }
    }
    EXPECT_GT(matched, 0);
}

// Colour and size by speed on a stateless emitter: its speed changes along
// the arc (|v0 + g a|), and each particle's colour and size are the start
// values times the curve at its own speed. One colour and one size for every
// particle, no over-life curves: colour = (2, 2, 2, 1) * mix(1, 0, t) and size
// 0.1 * (1 + t) with t = clamp((|v| - 1) / 5, 0, 1) from the snapshot's own
// velocity. Float rounding of a few operations: 1e-5.
TEST(Stateless, ColourAndSizeFollowTheSpeed) {
    EmitterDef e = sparks();
    e.color = {glm::vec4(2.0f, 2.0f, 2.0f, 1.0f), glm::vec4(2.0f, 2.0f, 2.0f, 1.0f)};
    e.size = {0.1f, 0.1f};
    e.overSpeedRange = {1.0f, 6.0f};
    e.colorOverSpeed.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(0.0f)}};
    e.sizeOverSpeed.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(2.0f)}};
    ParticleSnapshot s = evaluateStateless(e, 3, 0, 0.6f);
    ASSERT_GT(s.count(), 10u);
    float slowest = 1e9f, fastest = 0.0f;
    for (std::size_t i = 0; i < s.count(); ++i) {
        const float speed = glm::length(s.velocity[i]);
        slowest = std::min(slowest, speed);
        fastest = std::max(fastest, speed);
        const float t = std::clamp((speed - 1.0f) / 5.0f, 0.0f, 1.0f);
        EXPECT_NEAR(s.color[i].x, 2.0f * (1.0f - t), 1e-5f) << i;
        EXPECT_NEAR(s.color[i].w, 1.0f - t, 1e-5f) << i;
        EXPECT_NEAR(s.size[i], 0.1f * (1.0f + t), 1e-5f) << i;
    }
    // Not vacuous: the speeds span the range (launch 2 to 6 m/s, slowed and
    // sped up by gravity over up to 0.6 s).
    EXPECT_LT(slowest, 3.0f);
    EXPECT_GT(fastest, 4.0f);
}

// How many are alive: the rate's particles born within their lifetime before
// t, plus the burst's. With lifetimes uniform in [0.5, 1] and t = 2 s, a rate
// particle born a seconds ago lives with probability P(L > a); integrating,
// the expected count is 50 * (0.5 + 0.25) = 37.5; the burst at 0.25 s is dead.
// Binomial spread ~ 2.5: bound 12 (about 4 sigma).
TEST(Stateless, LiveCountMatchesRateAndLifetimes) {
    EmitterDef e = sparks();
    ParticleSnapshot s = evaluateStateless(e, 3, 0, 2.0f);
    EXPECT_NEAR(static_cast<double>(s.count()), 37.5, 12.0);
    for (std::size_t i = 0; i < s.count(); ++i) {
        EXPECT_GE(s.age[i], 0.0f);
        EXPECT_LT(s.age[i], s.lifetime[i]);
    }
    // At 0.3 s the whole burst of 40 (born 0.05 s ago, lifetime >= 0.5 s) is alive.
    ParticleSnapshot early = evaluateStateless(e, 3, 0, 0.3f);
    int burst = 0;
    for (std::uint32_t b : early.birth) {
        burst += b >= 0x80000000u ? 1 : 0;
    }
    EXPECT_EQ(burst, 40);
}

// A rate far beyond the capacity: the emitter shows its capacity of particles,
// the newest ones (serials just below rate x t), and the candidates handed to
// the walk and the sprite draw are that many too, not the 2^30 the rate's
// window holds (a mutant scene with rate = 3e38 took 5 s to evaluate). With
// a fixed lifetime of 1 s every candidate born within the last second is
// alive.
TEST(Stateless, RateBeyondTheCapacityShowsTheNewestCapacity) {
    EmitterDef e = sparks();
    e.bursts.clear();
    e.rate = 1.0e6f;
    e.capacity = 100;
    e.lifetime = {1.0f, 1.0f};
    const std::vector<StatelessRun> runs = statelessRuns(e, 2.0);
    ASSERT_EQ(runs.size(), 1u);
    EXPECT_EQ(runs[0].count, 100u);
    EXPECT_EQ(runs[0].firstSerial, 2000000u - 100u + 1u);  // serials up to floor(2 s x 1e6/s)
    ParticleSnapshot s = evaluateStateless(e, 3, 0, 2.0f);
    ASSERT_EQ(s.count(), 100u);
    EXPECT_EQ(s.birth.front(), 1999901u);
    EXPECT_EQ(s.birth.back(), 2000000u);
}

// A stateless emitter in a world stores nothing and is evaluated at the world's time.
TEST(Stateless, WorldEvaluatesAtItsTime) {
    test::ScopedWorld w(1, 3);
    EmitterId id = createEmitter(w.id, sparks());
    for (int i = 0; i < 30; ++i) {
        EXPECT_EQ(stepWorld(w.id, 0.01f).alive, 0u);  // nothing simulated
    }
    ParticleSnapshot a = readParticles(w.id, id);
    ParticleSnapshot b = evaluateStateless(sparks(), 3, 0, static_cast<float>(worldTime(w.id)));
    ASSERT_EQ(a.count(), b.count());
    for (std::size_t i = 0; i < a.count(); ++i) {
        EXPECT_EQ(a.position[i], b.position[i]);
    }
}

}  // namespace
}  // namespace spindrift
