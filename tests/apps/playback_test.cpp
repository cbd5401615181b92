// The viewer's real-time playback (apps/spindrift/playback.h) driven by made-up
// frame times: steps taken and the speed reported, against closed forms.
#include "apps/spindrift/playback.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using spindrift::app::advancePlayback;
using spindrift::app::Playback;
using spindrift::app::playbackBehind;
using spindrift::app::resetPlayback;

Playback at60() {
    Playback p;
    p.dt = 1.0 / 60.0;
    p.maxStepsPerFrame = 4;
    p.speedWindow = 0.5;
    return p;
}

TEST(Playback, FramesOfTwoStepsTakeTwoStepsEach) {
    Playback p = at60();
    for (int frame = 0; frame < 60; ++frame) EXPECT_EQ(advancePlayback(p, 2.0 / 60.0), 2) << "frame " << frame;
    EXPECT_DOUBLE_EQ(p.speed, 1.0);
    EXPECT_FALSE(playbackBehind(p));
}

// Frames of 10 ms against steps of 16.7 ms: after k frames, k x 0.6 steps
// are due, and the accumulator has taken exactly the whole ones.
TEST(Playback, ShortFramesAccumulateToWholeSteps) {
    Playback p = at60();
    int taken = 0;
    for (int k = 1; k <= 300; ++k) {
        const int steps = advancePlayback(p, 0.01);
        EXPECT_LE(steps, 1);
        taken += steps;
        ASSERT_EQ(taken, (k * 6) / 10) << "after frame " << k;
    }
    EXPECT_DOUBLE_EQ(p.speed, 1.0);
}

// A machine that needs 100 ms a frame: 6 steps are due per frame, the cap
// allows 4, so the world plays at 4/6 of real time, and says so.
TEST(Playback, SlowFramesAreCappedAndReportedAsSlow) {
    Playback p = at60();
    for (int frame = 0; frame < 10; ++frame) EXPECT_EQ(advancePlayback(p, 0.1), 4);
    EXPECT_NEAR(p.speed, 4.0 / 6.0, 1e-9);
    EXPECT_TRUE(playbackBehind(p));
    EXPECT_LT(p.owed, p.dt);
}

// One frame stalled for 5 s (a reload, a breakpoint) costs 4 steps, not 300,
// and leaves nothing owed, so the next frames play normally.
TEST(Playback, ALongStallDoesNotSpiral) {
    Playback p = at60();
    EXPECT_EQ(advancePlayback(p, 5.0), 4);
    EXPECT_NEAR(p.owed, 0.0, 1e-12);
    EXPECT_EQ(advancePlayback(p, 1.0 / 60.0), 1);
    // The window that held the stall reads (5 - (5 - 4/60)) / 5 of real time.
    EXPECT_NEAR(p.speed, (4.0 / 60.0) / 5.0, 1e-9);
}

TEST(Playback, ResetForgetsOwedTimeAndSpeed) {
    Playback p = at60();
    advancePlayback(p, 1.0);   // capped: the speed drops
    advancePlayback(p, 0.01);  // owes 10 ms
    ASSERT_LT(p.speed, 1.0);
    resetPlayback(p);
    EXPECT_EQ(advancePlayback(p, 0.5 / 60.0), 0);
    EXPECT_DOUBLE_EQ(p.speed, 1.0);
}

}  // namespace
