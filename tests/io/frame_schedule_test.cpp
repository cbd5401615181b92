// Which step each video frame shows, against the closed form
// stepsBefore(k) = floor(k / (fps dt)).
#include "io/frame_schedule.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using spindrift::io::FrameSchedule;

TEST(IoFrameSchedule, Dt60At24FpsTakesFloorOfTwoAndAHalfStepsPerFrame) {
    // The scene's dt is a float: 1/60 rounds up slightly, which must not drop
    // the step that frame 2 (5 steps, exactly 1/12 s) lands on.
    const FrameSchedule schedule(24.0, static_cast<double>(1.0f / 60.0f));
    for (std::uint64_t k = 0; k < 24 * 600; ++k) {  // ten minutes of video
        ASSERT_EQ(schedule.stepsBefore(k), k * 60 / 24) << "frame " << k;
    }
}

TEST(IoFrameSchedule, StartTimeShiftsEveryFrameByWholeFrames) {
    // Frame k of a video starting at 1.5 s is meant for 1.5 + k / 24 s: at
    // dt = 1/60 that is floor(90 + 2.5 k) steps.
    const FrameSchedule schedule(24.0, static_cast<double>(1.0f / 60.0f), 1.5);
    for (std::uint64_t k = 0; k < 24 * 60; ++k) {
        ASSERT_EQ(schedule.stepsBefore(k), 90 + k * 60 / 24) << "frame " << k;
    }
}

TEST(IoFrameSchedule, WholeStepsPerFrameAndFractionalRatios) {
    const FrameSchedule thirty(30.0, static_cast<double>(1.0f / 60.0f));
    const FrameSchedule seventy(70.0, 0.01);  // 1.43 steps per frame: never ahead of the frame time
    const FrameSchedule oneTwenty(120.0, static_cast<double>(1.0f / 60.0f));  // 2 frames per step
    for (std::uint64_t k = 0; k < 5000; ++k) {
        ASSERT_EQ(thirty.stepsBefore(k), 2 * k);
        ASSERT_EQ(seventy.stepsBefore(k), k * 100 / 70) << "frame " << k;
        ASSERT_EQ(oneTwenty.stepsBefore(k), k / 2) << "frame " << k;
    }
}

TEST(IoFrameSchedule, FrameCountIsCeilOfSecondsTimesFps) {
    EXPECT_EQ(FrameSchedule::frameCount(4.0, 30.0), 120u);
    EXPECT_EQ(FrameSchedule::frameCount(static_cast<double>(0.1f), 30.0), 3u);  // 3.0000001 is 3 frames
    EXPECT_EQ(FrameSchedule::frameCount(0.11, 30.0), 4u);
    EXPECT_EQ(FrameSchedule::frameCount(0.001, 30.0), 1u);
}

}  // namespace
