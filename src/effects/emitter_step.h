// The CPU backend: one step of one state-preserving emitter over its
// structure-of-arrays slots (the world's hub, src/world, calls it per emitter).
#pragma once

#include "core/parallel.h"
#include "particles/cpu_kernels.h"
#include "particles/emitter_state.h"

#include <spindrift/world.h>

#include <cstdint>
#include <vector>

namespace spindrift {

/// A step's events on the CPU backend, in emitter and slot order: at most
/// `capacity` records, the rest counted.
struct StepEvents {
    std::uint32_t capacity = 0;
    std::vector<kernels::EventRecord> records;
    std::uint64_t dropped = 0;
};

/// Advances emitter `e` (index `index` of its world) in world step `step` by
/// dt from `time` (s), reading forces, colliders and fields through `ctx`;
/// adds its births, deaths and hits to `stats` and its events to `events`,
/// and keeps this step's spawn requests for its sub-emitters. A sub-emitter
/// gets its `parent`, stepped before it in the same world step.
void stepEmitter(WorkerPool& pool, const kernels::KernelContext& ctx, EmitterState& e, std::uint32_t index,
                 std::uint64_t step, double time, float dt, const EmitterState* parent, StepStats& stats,
                 StepEvents& events);

}  // namespace spindrift
