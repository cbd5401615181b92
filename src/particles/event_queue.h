// Collision and death events of a world on their way to takeEvents (world.h),
// filled by both backends step by step.
#pragma once

#include "kernels/types.glsl"

#include <spindrift/world.h>

#include <cstddef>
#include <span>
#include <vector>

namespace spindrift {

/// Steps' worth of events (WorldDef::eventCapacity each) that wait for
/// takeEvents before the oldest are dropped: a world whose events are never
/// taken (the command-line renderer's, a benchmark's) grew by up to 4096
/// events (196 kB) a step, for as long as it ran.
inline constexpr std::size_t kUntakenEventSteps = 16;

struct EventQueue {
    std::uint32_t capacity = 0;  ///< most events kept per step (WorldDef::eventCapacity)
    EventBatch batch;
    /// The fluids' strikes on bodies in the current step, every one of them:
    /// the fires count these, not what `capacity` lets through to the
    /// application (with a capacity of 0 a fire never went out). Cleared by
    /// beginStep.
    std::vector<ParticleEvent> stepStrikes;

    /// Between steps: trims the events nobody took (trimUntaken) and forgets
    /// the last step's strikes.
    void beginStep();

    /// Drops the oldest waiting events, counted in batch.dropped, once more
    /// than twice kUntakenEventSteps steps' worth wait, down to that many: the
    /// trim copies what stays, so it runs once in kUntakenEventSteps full
    /// steps at most. Call it between steps (it moves the events' indices).
    void trimUntaken();

    /// Appends one step's records (at most `capacity`; the caller counted the
    /// rest as `dropped`).
    void addStep(std::uint64_t step, std::span<const kernels::EventRecord> records, std::uint64_t dropped);
    /// Appends events made on the host (fluid impacts on bodies), at most
    /// `capacity` of them (the rest are counted as dropped), and all of them
    /// to stepStrikes.
    void addEvents(std::span<const ParticleEvent> events);
};

}  // namespace spindrift
