// Which simulation step each video frame shows.
#pragma once

#include <cstdint>

namespace spindrift::io {

/// Frames k = 0 .. frames-1 are meant for world time k / fps, but the world
/// only exists at whole steps of dt, and 1/fps need not be a multiple of dt.
/// Frame k shows the last step not beyond its time: the world after
/// floor(k / (fps dt)) steps. The division carries a relative tolerance of
/// 1e-6 so that float rounding of dt (1/60 is not exact) cannot drop a step
/// the frame time lands on exactly: at dt = 1/60 and 24 fps, frame 2 is
/// after 5 steps, not 4.
class FrameSchedule {
  public:
    /// `start` (s, >= 0): world time of frame 0; frame k is meant for
    /// start + k / fps.
    FrameSchedule(double fps, double dt, double start = 0.0)
        : stepsPerFrame_(1.0 / (fps * dt)), startFrames_(start * fps) {}

    /// Steps taken before frame k is drawn.
    std::uint64_t stepsBefore(std::uint64_t frame) const;

    /// The number of frames in `seconds` at `fps`: ceil(seconds fps), with the
    /// same tolerance (4 s at 30 fps is 120 frames), at least 1.
    static std::uint64_t frameCount(double seconds, double fps);

  private:
    double stepsPerFrame_;
    double startFrames_;  // start time in frame units
};

}  // namespace spindrift::io
