// The Vulkan backend's world: forces, colliders and every recycle emitter's
// slots live in device buffers; a step is one dispatch of effects_update.comp
// per emitter and moves no particle data; readSlots copies one emitter back.
#pragma once

#include "effects/emitter_state.h"
#include "gpu/vulkan_buffer.h"

#include <spindrift/world.h>

#include <memory>
#include <span>
#include <vector>

namespace spindrift::gpu {

/// One state-preserving emitter on the device (structure of arrays, as the
/// CPU's ParticleArrays; rotation and angular velocity interleaved as vec2).
struct GpuEmitter {
    std::uint32_t capacity = 0;
    Buffer params, positions, velocities, ages, lifetimes, births, sizes, rotations, colors;
    Buffer counters;  // host-visible: born, died, 2 pads, hits[32]
    VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
    VkDescriptorSet descriptorSet = VK_NULL_HANDLE;
};

struct GpuWorld {
    std::unique_ptr<Device> device;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkPipeline updatePipeline = VK_NULL_HANDLE;
    Buffer forces;     // uint count, 3 pads, ForceParams[kMaxForces]
    Buffer colliders;  // uint count, 3 pads, ColliderParams[kMaxColliders]
    /// Indexed like World::emitters; null for stateless emitters.
    std::vector<std::unique_ptr<GpuEmitter>> emitters;
};

/// Validation for GPU worlds created from now on. Default: on when the
/// environment variable SPINDRIFT_VULKAN_VALIDATION is set and not "0".
void setWorldValidation(bool on);
/// Where the debug messengers of all validated GPU worlds write.
DebugLog& worldDebugLog();

std::unique_ptr<GpuWorld> createGpuWorld();
void destroyGpuWorld(GpuWorld& w);

void uploadForces(GpuWorld& w, std::span<const kernels::ForceParams> forces);
void uploadColliders(GpuWorld& w, std::span<const kernels::ColliderParams> colliders);

/// Appends an emitter: a recycle emitter's initialised slots (initialiseSlots)
/// are uploaded once; a stateless one gets no device state. Throws Error for
/// spawn mode (not supported on the GPU yet).
void addEmitter(GpuWorld& w, const EmitterState& initial);

/// One step of every state-preserving emitter: one submission, one dispatch
/// each. Adds births, deaths and hits to `stats` and updates EmitterState::alive.
void stepEmitters(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, float dt, StepStats& stats);

/// Copies all slots of emitter `index` back to the host.
ParticleArrays readSlots(GpuWorld& w, std::size_t index);

TransferStats transferStats(const GpuWorld& w);

}  // namespace spindrift::gpu
