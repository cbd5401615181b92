// Collision and death events of a world on their way to takeEvents (world.h),
// filled by both backends step by step.
#pragma once

#include "kernels/types.glsl"

#include <spindrift/world.h>

#include <cstddef>
#include <span>

namespace spindrift {

/// Steps' worth of events (WorldDef::eventCapacity each) that wait for
/// takeEvents before the oldest are dropped: a world whose events are never
/// taken (the command-line renderer's, a benchmark's) grew by up to 4096
/// events (196 kB) a step, for as long as it ran.
inline constexpr std::size_t kUntakenEventSteps = 16;

struct EventQueue {
    std::uint32_t capacity = 0;  ///< most events kept per step (WorldDef::eventCapacity)
    EventBatch batch;

    /// Drops the oldest waiting events, counted in batch.dropped, once more
    /// than twice kUntakenEventSteps steps' worth wait, down to that many: the
    /// trim copies what stays, so it runs once in kUntakenEventSteps full
    /// steps at most. Call it between steps (it moves the events' indices).
    void trimUntaken();

    /// Appends one step's records (at most `capacity`; the caller counted the
    /// rest as `dropped`).
    void addStep(std::uint64_t step, std::span<const kernels::EventRecord> records, std::uint64_t dropped);
    /// Appends events made on the host (fluid impacts on bodies), at most
    /// `capacity` of them; the rest are counted as dropped.
    void addEvents(std::span<const ParticleEvent> events);
};

}  // namespace spindrift
