// Collision and death events of a world on their way to takeEvents (world.h),
// filled by both backends step by step.
#pragma once

#include "kernels/types.glsl"

#include <spindrift/world.h>

#include <span>

namespace spindrift {

struct EventQueue {
    std::uint32_t capacity = 0;  ///< most events kept per step (WorldDef::eventCapacity)
    EventBatch batch;

    /// Appends one step's records (at most `capacity`; the caller counted the
    /// rest as `dropped`).
    void addStep(std::uint64_t step, std::span<const kernels::EventRecord> records, std::uint64_t dropped);
    /// Appends events made on the host (fluid impacts on bodies), at most
    /// `capacity` of them; the rest are counted as dropped.
    void addEvents(std::span<const ParticleEvent> events);
};

}  // namespace spindrift
