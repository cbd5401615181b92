// Progress reporting: throttled, silent for short runs, redrawn on terminals.
#include "io/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>
#include <string>

namespace {

using spindrift::io::ProgressReporter;

/// Simulates a run of `steps` steps taking `secondsPerStep` each.
std::string simulate(bool terminal, std::uint64_t steps, double secondsPerStep) {
    std::ostringstream out;
    ProgressReporter::Options options;
    options.terminal = terminal;
    ProgressReporter progress(out, steps, options);
    for (std::uint64_t i = 1; i <= steps; ++i) progress.update(i, 10 * i, secondsPerStep * static_cast<double>(i));
    progress.finish(steps, 10 * steps, secondsPerStep * static_cast<double>(steps));
    return out.str();
}

TEST(IoProgress, ShortRunsPrintNothing) {
    EXPECT_EQ(simulate(false, 100, 0.001), "");  // 0.1 s
    EXPECT_EQ(simulate(true, 100, 0.004), "");   // 0.4 s
}

TEST(IoProgress, LogLinesAreThrottledToTwoSeconds) {
    // 10 s in 1000 steps: a line at about 2, 4, 6, 8, 10 s, and the final one.
    const std::string text = simulate(false, 1000, 0.01);
    const auto lines = std::count(text.begin(), text.end(), '\n');
    EXPECT_GE(lines, 5);
    EXPECT_LE(lines, 6);
    EXPECT_EQ(text.find('\r'), std::string::npos);
    EXPECT_NE(text.find("step 1000/1000 (100%)  alive 10000"), std::string::npos) << text;
}

TEST(IoProgress, TerminalRedrawsOneLine) {
    const std::string text = simulate(true, 200, 0.01);  // 2 s
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
    EXPECT_GT(std::count(text.begin(), text.end(), '\r'), 10);
    EXPECT_EQ(text.back(), '\n');
}

TEST(IoProgress, LineShowsRateAndEta) {
    // 50 of 200 steps at 100 ms/step: 150 steps left = 15 s.
    EXPECT_EQ(ProgressReporter::line(50, 200, 1234, 0.1), "step 50/200 (25%)  alive 1234  100.00 ms/step  ETA 0:15");
    EXPECT_EQ(ProgressReporter::line(1, 10000, 0, 1.0), "step 1/10000 (0%)  alive 0  1000.00 ms/step  ETA 2:46:39");
}

TEST(IoProgress, FrameLineShowsFramesPerSecondAndEta) {
    // 30 of 120 frames at 200 ms/frame: 5 fps, 90 frames left = 18 s.
    EXPECT_EQ(ProgressReporter::frameLine(30, 120, 0.2), "frame 30/120 (25%)  5.0 fps  ETA 0:18");
}

TEST(IoProgress, FramesUnitReportsFrames) {
    std::ostringstream out;
    ProgressReporter::Options options;
    options.unit = ProgressReporter::Unit::Frames;
    ProgressReporter progress(out, 10, options);
    for (std::uint64_t i = 1; i <= 10; ++i) progress.update(i, 0, 0.5 * static_cast<double>(i));
    progress.finish(10, 0, 5.0);
    EXPECT_NE(out.str().find("frame 10/10 (100%)  2.0 fps  ETA 0:00"), std::string::npos) << out.str();
    EXPECT_EQ(out.str().find("step"), std::string::npos) << out.str();
}

TEST(IoProgress, RateComesFromTheStepsSinceTheLastReport) {
    // 1 s per step for the first 4 steps, then 10 ms per step.
    std::ostringstream out;
    ProgressReporter progress(out, 1000, ProgressReporter::Options{});
    double t = 0.0;
    for (std::uint64_t i = 1; i <= 500; ++i) {
        t += i <= 4 ? 1.0 : 0.01;
        progress.update(i, 0, t);
    }
    const std::string text = out.str();
    // First line at 2 s (step 2, average 1000 ms); the next at 4 s (step 4);
    // the one after covers steps 5.. only: 10 ms/step.
    EXPECT_NE(text.find("step 2/1000 (0%)  alive 0  1000.00 ms/step"), std::string::npos) << text;
    EXPECT_NE(text.find("10.00 ms/step"), std::string::npos) << text;
}

}  // namespace
