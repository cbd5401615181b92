// Real-time playback for the viewer: wall-clock time accumulates and is spent
// in whole fixed steps of the scene's dt, so the world plays at the speed of
// the clock whatever the frame rate. A pure clock-free struct (the caller
// passes each frame's wall time), so tests drive it with made-up frame times.
#pragma once

#include <algorithm>
#include <cmath>

namespace spindrift::app {

struct Playback {
    double dt = 1.0 / 60.0;  // s simulated per step
    /// Most steps one frame may take. Beyond it the owed time is dropped:
    /// otherwise a frame slower than its steps makes the next frame take
    /// more steps, which makes it slower still (the spiral of death).
    int maxStepsPerFrame = 4;
    /// Wall time over which the speed is measured (s): long enough that
    /// the whole steps of a few frames average out, short enough to follow
    /// a change of scene load.
    double speedWindow = 0.5;

    double owed = 0.0;        // s of wall time not yet simulated, < dt after each frame
    double windowWall = 0.0;  // s of wall time in the current speed window
    double windowDropped = 0.0;  // s of it the cap dropped
    /// Simulated seconds per wall second over the last full window: 1 when
    /// the machine keeps up, less by the time the cap dropped. Time owed is
    /// simulated a frame later, so only dropped time counts: the ratio is
    /// exact, not blurred by the rounding to whole steps.
    double speed = 1.0;
};

/// Whole steps owed after `wallSeconds` more of wall time (a frame), at most
/// maxStepsPerFrame; updates the speed once a window of wall time is full.
inline int advancePlayback(Playback& p, double wallSeconds) {
    p.owed += std::max(wallSeconds, 0.0);
    // The tolerance absorbs rounding of dt (frames of exactly 2 dt give 2
    // steps, not 1 and a remainder of almost dt), as `render` does.
    int steps = static_cast<int>(std::floor(p.owed / p.dt + 1e-6));
    if (steps > p.maxStepsPerFrame) {
        steps = p.maxStepsPerFrame;
        p.windowDropped += p.owed - steps * p.dt;
        p.owed = steps * p.dt;
    }
    p.owed = std::max(p.owed - steps * p.dt, 0.0);
    p.windowWall += std::max(wallSeconds, 0.0);
    if (p.windowWall >= p.speedWindow) {
        p.speed = (p.windowWall - p.windowDropped) / p.windowWall;
        p.windowWall = p.windowDropped = 0.0;
    }
    return steps;
}

/// After a pause, a restart or a reload: the time spent there is not owed,
/// and the speed is measured afresh.
inline void resetPlayback(Playback& p) {
    p.owed = p.windowWall = p.windowDropped = 0.0;
    p.speed = 1.0;
}

/// True when the world played measurably slower than the clock over the
/// last window (the panel then says so): a 1 % margin, so one frame a
/// little over the cap in a window does not flag it.
inline bool playbackBehind(const Playback& p) { return p.speed < 0.99; }

}  // namespace spindrift::app
