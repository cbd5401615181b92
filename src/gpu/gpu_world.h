// The Vulkan backend's world: forces, colliders and every state-preserving
// emitter's slots live in device buffers; a step is one submission of the
// passes of effects_update.comp and moves no particle data; readSlots copies
// one emitter back. Spawn-mode emitters keep their dead-slot stack and alive
// lists on the device too: birth and death happen there. Flow fields, terrain
// height maps and depth cube maps are images sampled with the hardware's linear
// filter (set 2 of effects_update.comp), uploaded once.
#pragma once

#include "gpu/device_settings.h"
#include "gpu/gpu_sort.h"
#include "gpu/vulkan_buffer.h"
#include "kernels/layout.glsl"
#include "particles/emitter_state.h"
#include "particles/event_queue.h"
#include "particles/fields.h"

#include <spindrift/world.h>

#include <array>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace spindrift::gpu {

/// Most sampled fields of each kind one Vulkan world holds: the sizes of the
/// sampler arrays of effects_update.comp (set 2), from src/kernels/layout.glsl.
/// Creating one more throws Error.
inline constexpr std::uint32_t kMaxGpuFlowFields = kernels::SD_MAX_FLOW_FIELDS;
inline constexpr std::uint32_t kMaxGpuHeightMaps = kernels::SD_MAX_HEIGHT_MAPS;
inline constexpr std::uint32_t kMaxGpuCubeMaps = kernels::SD_MAX_CUBE_MAPS;

/// The sampled fields of a world: one image per field, one linear
/// clamp-to-edge sampler, one descriptor set (set 2) whose unused array
/// elements show a 1x1 placeholder image.
struct GpuFields {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    Image placeholder3d, placeholder2d, placeholderCube;
    std::vector<Image> flows, heights, cubes;
    /// Formats chosen at creation: 32-bit float where the device filters it
    /// linearly, else 16-bit float; VK_FORMAT_UNDEFINED: neither (refused).
    VkFormat flowFormat = VK_FORMAT_UNDEFINED;    // xyz velocity, w unused
    VkFormat heightFormat = VK_FORMAT_UNDEFINED;  // height
    VkFormat cubeFormat = VK_FORMAT_UNDEFINED;    // normal xyz, depth w
};

/// Bytes a GPU emitter stores per slot: position 12, velocity 12, age 4,
/// birth serial 4, rotation 4 (GpuEmitter). Creation uploads and readParticles
/// downloads exactly this much per slot, plus 12 per trail point of an
/// emitter with a trail.
inline constexpr std::size_t kStoredBytesPerSlot = 12 + 12 + 4 + 4 + 4;

/// Most steps a GPU world runs ahead of the host (WorldDef::framesInFlight).
inline constexpr std::uint32_t kMaxFramesInFlight = 3;

/// One state-preserving emitter on the device: structure of arrays, as the
/// CPU's ParticleArrays, of what changes after birth only (the shader
/// recomputes lifetime, angular velocity, colour and size with
/// kernels::restoreDerived). What the host writes or reads per step has one
/// copy per frame in flight.
struct GpuEmitter {
    std::uint32_t capacity = 0;
    Buffer params, positions, velocities, ages, births, rotations;
    /// EmitterDef::trail's positions, trailPoints per slot (one placeholder
    /// entry without a trail), written by the update and emit passes.
    Buffer trail;
    std::uint32_t trailPoints = 0;
    std::uint32_t trailHead = 0;  // this step's (EmitterState::trailHead)
    std::uint32_t step = 0;          // this step's index, low 32 bits (spawn requests)
    std::uint32_t requestKinds = 0;  // EmitterState::requestKinds
    /// This step's spawn requests per event kind (EventsHeader, SpawnRequest
    /// [capacity]) for the kinds some sub-emitter follows (followEvents);
    /// no buffer for the others (the placeholder is bound).
    Buffer requests[kernels::SD_SPAWN_EVENT_KINDS];
    /// A sub-emitter's parent (index into GpuWorld::emitters) and the kind of
    /// its requests it reads; -1: none.
    std::int64_t parent = -1;
    std::uint32_t parentKind = 0;
    Buffer counters[kMaxFramesInFlight];  // host-visible: kernels::StepCounters
    VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
    VkDescriptorSet descriptorSets[kMaxFramesInFlight] = {};  // set 0, per frame

    // Spawn mode only (set 1 of effects_update.comp).
    bool spawn = false;
    Buffer dead;      // kernels::DeadHeader, dead slot stack
    Buffer alive[2];  // kernels::TableHeader, slot indices
    Buffer schedules[kMaxFramesInFlight];  // host-visible: kernels::ScheduleHeader, burst runs
    // Births the frame's schedule left out (beyond the capacity), added to
    // the device's clamped count when the frame is collected.
    std::uint64_t scheduleDropped[kMaxFramesInFlight] = {};
    std::uint32_t scheduleRuns = 0;  // burst runs a schedule buffer holds
    /// listSets[p][f]: alive[p] is the current list, alive[1 - p] the next,
    /// with frame f's schedule.
    VkDescriptorSet listSets[2][kMaxFramesInFlight] = {};
    std::uint32_t parity = 0;  // flips with every submitted step
};

/// One step in flight: its command buffer, the fence that says it is done,
/// and the events buffer the host reads then.
struct GpuFrame {
    VkFence fence = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // null when no step is pending
    std::uint64_t step = 0;
    Buffer events;  // host-visible: kernels::EventsHeader, EventRecord[capacity]
};

struct GpuWorld {
    std::unique_ptr<Device> device;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkDescriptorSetLayout listLayout = VK_NULL_HANDLE;  // set 1: spawn-mode lists
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    /// Pipelines of effects_update.comp by pass (SD_PASS_*, one module each)
    /// and specialization (field counts, integrator), created the first time
    /// a step needs one: llvmpipe compiles at creation, and only the variants
    /// a world runs are worth compiling.
    std::map<std::pair<std::uint32_t, std::array<std::uint32_t, kernels::SD_SPEC_COUNT>>, VkPipeline> pipelines;
    /// Bit i: force i is a curl-noise force (the CURL_NOISE specialization
    /// constant of an emitter that selects one).
    std::uint32_t curlNoiseForces = 0;
    /// Set 1 of recycle emitters: the recycle pass never reads it, but the
    /// shader module declares it, so something valid must be bound.
    Buffer placeholder;
    VkDescriptorPool placeholderPool = VK_NULL_HANDLE;
    VkDescriptorSet placeholderSet = VK_NULL_HANDLE;
    Buffer forces;     // kernels::TableHeader, ForceParams[SD_MAX_FORCES]
    Buffer colliders;  // kernels::TableHeader, ColliderParams[SD_MAX_COLLIDERS]
    GpuFields fields;
    /// Indexed like World::emitters; null for stateless emitters.
    std::vector<std::unique_ptr<GpuEmitter>> emitters;
    /// Back-to-front sort (gpu_sort.h), created at the first sort.
    std::unique_ptr<GpuSort> sort;
    std::uint32_t framesInFlight = 1;
    std::uint32_t eventCapacity = 0;
    GpuFrame frames[kMaxFramesInFlight];
    /// Two timestamps per frame (start and end of its step); null where the
    /// compute queue has none (timestampValidBits == 0).
    VkQueryPool timestamps = VK_NULL_HANDLE;
    double timestampPeriodNs = 0.0;  // ns per timestamp tick
    std::uint64_t submitted = 0;  // steps submitted so far; frame submitted % framesInFlight is next
};

/// framesInFlight in [1, kMaxFramesInFlight]; eventCapacity: most events
/// recorded per step (0: none).
std::unique_ptr<GpuWorld> createGpuWorld(std::uint32_t framesInFlight = 1, std::uint32_t eventCapacity = 0);
void destroyGpuWorld(GpuWorld& w);

void uploadForces(GpuWorld& w, std::span<const kernels::ForceParams> forces);
void uploadColliders(GpuWorld& w, std::span<const kernels::ColliderParams> colliders);

/// Append one sampled field, indexed from 0 in the order of the calls (as
/// ForceParams::flowField and ColliderParams::dataIndex count them), uploaded
/// once. Throws Error naming `name` beyond the maximum counts above, the
/// device's image size limits, or without linear filtering of float formats.
void addFlowField(GpuWorld& w, const FlowGrid& grid, const std::string& name);
void addHeightMap(GpuWorld& w, const HeightMap& map, const std::string& name);
void addCubeMap(GpuWorld& w, const DepthCubeMap& cube, const std::string& name);

/// Appends an emitter: a state-preserving emitter's initialised slots
/// (initialiseSlots) are uploaded once, with, in spawn mode, its dead stack in
/// the order of the CPU's free list; a stateless one gets no device state.
void addEmitter(GpuWorld& w, const EmitterState& initial);

/// Submits step `step`, [time, time + dt), of every state-preserving emitter:
/// one submission. Spawn emitters' births follow the CPU's schedule
/// (scheduleBirths), numbered on the device. Then waits for and collects
/// step `step - (framesInFlight - 1)` (this one with one frame in flight), so
/// at most framesInFlight - 1 steps stay pending: collecting adds the step's births, deaths, clamped
/// births and hits to `stats` (countedSteps, lastCountedStep), updates
/// EmitterState::alive and nextSerial, and hands its events to `events`.
void stepEmitters(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, double time, float dt,
                  std::uint64_t step, StepStats& stats, EventQueue& events);

/// Waits for every step in flight and collects them, oldest first.
void collectAll(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, StepStats& stats,
                EventQueue& events);

/// Waits until the device has finished every submitted step (collects
/// nothing): before the host reads or rewrites what a step uses.
void waitForSteps(GpuWorld& w);

/// Emitter `index` keeps its spawn requests of `kind` (SD_SPAWN_ON_*) on the
/// device from the next step on, for a sub-emitter about to be added (its
/// descriptor sets bind them). Waits for the steps in flight.
void followEvents(GpuWorld& w, std::size_t index, std::uint32_t kind);

/// Replaces emitter `index`'s parameters on the device, after the steps in
/// flight (which read them) have finished.
void setEmitterParams(GpuWorld& w, std::size_t index, const kernels::EmitterParams& params);

/// Copies all slots of emitter `index` back to the host, with the attributes
/// the device does not store restored from `params` (its EmitterParams).
ParticleArrays readSlots(GpuWorld& w, std::size_t index, const kernels::EmitterParams& params);

TransferStats transferStats(const GpuWorld& w);

}  // namespace spindrift::gpu
