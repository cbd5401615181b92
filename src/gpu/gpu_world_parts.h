// What the files of the Vulkan backend's world share beyond gpu_world.h. The
// world is split by job:
//   gpu_world.cpp     device settings, set and pipeline layouts, lifetime,
//                     forces and colliders;
//   gpu_emitters.cpp  per-emitter pipelines, descriptor sets, slot buffers,
//                     parameters and read-back;
//   gpu_step.cpp      a step's submission, birth schedules, frames in flight,
//                     timestamps, and collecting counts and events;
//   gpu_fields.cpp    sampled field images (set 2).
// Bindings, buffer headers, push constants and limits are those of
// src/kernels/layout.glsl, which effects_update.comp includes too.
#pragma once

#include "gpu/gpu_world.h"
#include "kernels/layout.glsl"

#include <cstdint>
#include <span>

namespace spindrift::gpu {

using kernels::DeadHeader;
using kernels::EventsHeader;
using kernels::ScheduleHeader;
using kernels::StepCounters;
using kernels::StepPush;
using kernels::TableHeader;
inline constexpr std::uint32_t kBindingCount = kernels::SD_EMITTER_BINDINGS;
inline constexpr std::uint32_t kListBindingCount = kernels::SD_LIST_BINDINGS;
inline constexpr std::uint32_t kWorkgroupSize = kernels::SD_UPDATE_WORKGROUP;

/// The PASS specialization constant of effects_update.comp.
enum class Pass : std::uint32_t {
    RecycleUpdate = kernels::SD_PASS_RECYCLE_UPDATE,
    SpawnUpdate = kernels::SD_PASS_SPAWN_UPDATE,
    SpawnEmit = kernels::SD_PASS_SPAWN_EMIT,
    SpawnFinish = kernels::SD_PASS_SPAWN_FINISH,
    SubEmit = kernels::SD_PASS_SUB_EMIT,
};

// gpu_world.cpp
/// A pool for `sets` sets of storage buffers, `buffers` descriptors in all.
VkDescriptorPool createDescriptorPool(Device& d, std::uint32_t sets, std::uint32_t buffers);
/// Allocates a set of `layout` from `pool` and points binding i at buffers[i].
VkDescriptorSet writeSet(Device& d, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                         std::span<Buffer* const> buffers);

// gpu_emitters.cpp
/// The pipeline of `pass` for emitter `e` in this world, created on first use.
VkPipeline pipelineFor(GpuWorld& w, Pass pass, const EmitterState& e);
void destroyEmitter(Device& d, GpuEmitter& e);

// gpu_step.cpp
/// The compute queue's timestamps, if it has any: a pool of two per frame.
void createTimestamps(GpuWorld& w);

// gpu_fields.cpp
/// Set 2's layout, sampler, placeholders and formats.
void createFields(GpuWorld& w);
void destroyFields(Device& d, GpuFields& f);

}  // namespace spindrift::gpu
