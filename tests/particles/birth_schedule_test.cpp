// The birth schedule of a spawn emitter (src/particles/birth_schedule.h)
// against its closed forms: a rate r owes floor(carry + r dt) births in a step
// and keeps the fraction; the rate's j-th birth is born when the count
// reaches j + 1, (j + 1 - carry) / r into the step, so its age at the step's
// end is dt minus that; a burst at time b is t1 - b old; nothing beyond the
// capacity is held.
#include "particles/birth_schedule.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace spindrift {
namespace {

EmitterState spawnEmitter(float rate, std::uint32_t capacity) {
    EmitterState e;
    e.def.lifecycle = Lifecycle::Spawn;
    e.def.rate = rate;
    e.def.capacity = capacity;
    return e;
}

// Float arithmetic on times of a few seconds: a few ulp of 1 s.
constexpr float kAgeTolerance = 1e-6f;

TEST(BirthSchedule, RateOwesWholeBirthsAndCarriesTheFraction) {
    EmitterState e = spawnEmitter(100.0f, 1000);
    const float dt = 1.0f / 60.0f;  // 1.666... births a step
    const BirthSchedule first = scheduleBirths(e, 0.0, dt);
    EXPECT_EQ(first.total(), 1u);
    EXPECT_NEAR(e.emissionCarry, 100.0 * dt - 1.0, 1e-9);
    const BirthSchedule second = scheduleBirths(e, dt, dt);
    EXPECT_EQ(second.total(), 2u);  // 0.667 + 1.667 = 2.33
    // Over 60 steps the rate owes exactly its 100 births a second.
    std::uint64_t born = first.total() + second.total();
    for (int step = 2; step < 60; ++step) {
        born += scheduleBirths(e, step * static_cast<double>(dt), dt).total();
    }
    EXPECT_EQ(born, 100u);
}

TEST(BirthSchedule, RateBirthsAreSpreadOverTheStep) {
    EmitterState e = spawnEmitter(240.0f, 1000);
    e.emissionCarry = 0.25;
    const float dt = 0.05f;  // 0.25 + 12 = 12.25: 12 births
    const BirthSchedule s = scheduleBirths(e, 1.0, dt);
    const std::vector<float> ages = s.ages(1000);
    ASSERT_EQ(ages.size(), 12u);
    for (std::size_t j = 0; j < ages.size(); ++j) {
        const double bornAfterStart = (static_cast<double>(j) + 1.0 - 0.25) / 240.0;
        EXPECT_NEAR(ages[j], dt - bornAfterStart, kAgeTolerance) << "birth " << j;
    }
    // Ages fall with the birth's index: none born together in one sheet.
    for (std::size_t j = 1; j < ages.size(); ++j) {
        EXPECT_LT(ages[j], ages[j - 1]);
    }
}

TEST(BirthSchedule, BurstsComeFirstWithTheirOwnAge) {
    EmitterState e = spawnEmitter(60.0f, 1000);
    e.def.bursts = {{1.01f, 5}, {2.0f, 7}, {1.02f, 3}};
    const BirthSchedule s = scheduleBirths(e, 1.0, 0.05f);  // [1.0, 1.05): the bursts at 1.01 and 1.02
    const std::vector<float> ages = s.ages(1000);
    ASSERT_EQ(ages.size(), 5u + 3u + 3u);  // and the rate's 3
    for (std::size_t k = 0; k < 5; ++k) EXPECT_NEAR(ages[k], 0.04f, kAgeTolerance);
    for (std::size_t k = 5; k < 8; ++k) EXPECT_NEAR(ages[k], 0.03f, kAgeTolerance);
    EXPECT_NEAR(ages[8], 0.05f - 1.0f / 60.0f, kAgeTolerance);
}

TEST(BirthSchedule, HoldsAtMostTheCapacityAndCountsTheRest) {
    // A rate of 1e12 once stored every owed age (1.7e10 a step): now the
    // schedule holds the capacity and counts the rest.
    EmitterState e = spawnEmitter(1e12f, 100);
    e.def.bursts = {{0.0f, 40}};
    const BirthSchedule s = scheduleBirths(e, 0.0, 1.0f / 60.0f);
    EXPECT_EQ(s.total(), 100u);
    EXPECT_EQ(s.ages(std::numeric_limits<std::uint64_t>::max()).size(), 100u);
    // Owed: 40 from the burst and floor(rate dt) from the rate, both floats
    // as given (1e12f is 999999995904), multiplied in double.
    const double owed = 40.0 + std::floor(static_cast<double>(1e12f) * static_cast<double>(1.0f / 60.0f));
    EXPECT_NEAR(static_cast<double>(s.dropped), owed - 100.0, 1.0);
}

TEST(BirthSchedule, TheHeaderIsWhatTheDeviceReads) {
    EmitterState e = spawnEmitter(90.0f, 1000);
    e.def.bursts = {{0.5f, 4}};
    e.emissionCarry = 0.5;
    const BirthSchedule s = scheduleBirths(e, 0.5, 0.1f);
    const kernels::ScheduleHeader h = s.header();
    EXPECT_EQ(h.burstRuns, 1u);
    EXPECT_EQ(h.rateFirst, 4u);  // the rate's births follow the burst's 4
    EXPECT_FLOAT_EQ(h.rateCarry, 0.5f);
    EXPECT_FLOAT_EQ(h.rate, 90.0f);
    EXPECT_FLOAT_EQ(h.maxAge, 0.1f);
    EXPECT_NEAR(h.rateSpan, 0.1f, kAgeTolerance);
}

}  // namespace
}  // namespace spindrift
