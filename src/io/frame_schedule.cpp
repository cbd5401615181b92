#include "io/frame_schedule.h"

#include <algorithm>
#include <cmath>

namespace spindrift::io {

namespace {

// Relative: an absolute tolerance would stop absorbing dt's rounding error,
// which grows with the step count, on long videos.
constexpr double kRelativeTolerance = 1e-6;

}  // namespace

std::uint64_t FrameSchedule::stepsBefore(std::uint64_t frame) const {
    return static_cast<std::uint64_t>(
        std::floor((startFrames_ + static_cast<double>(frame)) * stepsPerFrame_ * (1.0 + kRelativeTolerance)));
}

std::uint64_t FrameSchedule::frameCount(double seconds, double fps) {
    const double frames = std::ceil(seconds * fps * (1.0 - kRelativeTolerance));
    return static_cast<std::uint64_t>(std::max(frames, 1.0));
}

}  // namespace spindrift::io
