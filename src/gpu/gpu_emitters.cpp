// The Vulkan backend's emitters: pipelines by specialization, descriptor
// sets, slot buffers, the initial upload, parameters and read-back.
#include "gpu/gpu_world_parts.h"

#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "particles/cpu_kernels.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>

namespace spindrift::gpu {
namespace {

std::array<Buffer*, kBindingCount> bindingBuffers(GpuWorld& w, GpuEmitter& e, std::uint32_t frame) {
    std::array<Buffer*, kBindingCount> b{};
    b[kernels::SD_BINDING_EMITTER] = &e.params;
    b[kernels::SD_BINDING_FORCES] = &w.forces;
    b[kernels::SD_BINDING_COLLIDERS] = &w.colliders;
    b[kernels::SD_BINDING_POSITIONS] = &e.positions;
    b[kernels::SD_BINDING_VELOCITIES] = &e.velocities;
    b[kernels::SD_BINDING_AGES] = &e.ages;
    b[kernels::SD_BINDING_BIRTHS] = &e.births;
    b[kernels::SD_BINDING_ROTATIONS] = &e.rotations;
    b[kernels::SD_BINDING_COUNTERS] = &e.counters[frame];
    b[kernels::SD_BINDING_EVENTS] = &w.frames[frame].events;
    b[kernels::SD_BINDING_TRAILS] = &e.trail;
    static_assert(kernels::SD_BINDING_DEATH_REQUESTS == kernels::SD_BINDING_BIRTH_REQUESTS + kernels::SD_SPAWN_ON_DEATH);
    static_assert(kernels::SD_BINDING_COLLISION_REQUESTS ==
                  kernels::SD_BINDING_BIRTH_REQUESTS + kernels::SD_SPAWN_ON_COLLISION);
    for (std::uint32_t kind = 0; kind < kernels::SD_SPAWN_EVENT_KINDS; ++kind) {
        Buffer& r = e.requests[kind];
        b[kernels::SD_BINDING_BIRTH_REQUESTS + kind] = r.buffer != VK_NULL_HANDLE ? &r : &w.placeholder;
    }
    return b;
}

// Set 1 of a spawn emitter: alive[p] is the current list, alive[1 - p] the next.
std::array<Buffer*, kListBindingCount> listBuffers(GpuWorld& w, GpuEmitter& e, std::uint32_t p,
                                                   std::uint32_t frame) {
    std::array<Buffer*, kListBindingCount> b{};
    b[kernels::SD_BINDING_DEAD] = &e.dead;
    b[kernels::SD_BINDING_ALIVE_IN] = &e.alive[p];
    b[kernels::SD_BINDING_ALIVE_OUT] = &e.alive[1 - p];
    b[kernels::SD_BINDING_SCHEDULE] = &e.schedules[frame];
    b[kernels::SD_BINDING_PARENT_REQUESTS] =
        e.parent >= 0 ? &w.emitters[static_cast<std::size_t>(e.parent)]->requests[e.parentKind] : &w.placeholder;
    return b;
}

// Set 0 of every emitter per frame in flight; a spawn emitter also gets its
// set-1 variants, one per role of its alive lists and frame.
void createDescriptorSets(GpuWorld& w, GpuEmitter& e) {
    Device& d = *w.device;
    const std::uint32_t frames = w.framesInFlight;
    e.descriptorPool = e.spawn ? createDescriptorPool(d, 3 * frames, frames * (kBindingCount + 2 * kListBindingCount))
                               : createDescriptorPool(d, frames, frames * kBindingCount);
    for (std::uint32_t f = 0; f < frames; ++f) {
        std::array<Buffer*, kBindingCount> buffers = bindingBuffers(w, e, f);
        e.descriptorSets[f] = writeSet(d, e.descriptorPool, w.setLayout, buffers);
        if (e.spawn) {
            for (std::uint32_t p = 0; p < 2; ++p) {
                std::array<Buffer*, kListBindingCount> lists = listBuffers(w, e, p, f);
                e.listSets[p][f] = writeSet(d, e.descriptorPool, w.listLayout, lists);
            }
        }
    }
}

}  // namespace

void destroyEmitter(Device& d, GpuEmitter& e) {
    if (e.descriptorPool != VK_NULL_HANDLE) {
        vkDestroyDescriptorPool(d.device, e.descriptorPool, nullptr);  // frees its set
    }
    for (Buffer* b : {&e.params, &e.positions, &e.velocities, &e.ages, &e.births, &e.rotations, &e.trail, &e.dead,
                      &e.alive[0], &e.alive[1], &e.requests[0], &e.requests[1], &e.requests[2]}) {
        destroyBuffer(d, *b);
    }
    for (std::uint32_t f = 0; f < kMaxFramesInFlight; ++f) {
        destroyBuffer(d, e.counters[f]);
        destroyBuffer(d, e.schedules[f]);
    }
}

namespace {

void allocateSlots(Device& d, GpuEmitter& e, std::uint32_t frames) {
    // Vulkan buffers cannot be empty (VkBufferCreateInfo: size > 0).
    const VkDeviceSize n = std::max<VkDeviceSize>(e.capacity, 1);
    e.params = createStorageBuffer(d, sizeof(kernels::EmitterParams));
    e.positions = createStorageBuffer(d, n * 12);
    e.velocities = createStorageBuffer(d, n * 12);
    e.ages = createStorageBuffer(d, n * 4);
    e.births = createStorageBuffer(d, n * 4);
    e.rotations = createStorageBuffer(d, n * 4);
    e.trail = createStorageBuffer(d, std::max<VkDeviceSize>(VkDeviceSize{e.capacity} * e.trailPoints, 1) * 12);
    for (std::uint32_t f = 0; f < frames; ++f) {
        e.counters[f] = createHostStorageBuffer(d, sizeof(StepCounters));
        std::memset(e.counters[f].mapped, 0, sizeof(StepCounters));
    }
    if (e.spawn) {
        // The dead buffer's header is also the update pass's indirect dispatch.
        e.dead = createBuffer(d, sizeof(DeadHeader) + n * 4,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                  VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                              VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        e.alive[0] = createStorageBuffer(d, sizeof(TableHeader) + n * 4);
        e.alive[1] = createStorageBuffer(d, sizeof(TableHeader) + n * 4);
        for (std::uint32_t f = 0; f < frames; ++f) {
            e.schedules[f] =
                createHostStorageBuffer(d, sizeof(ScheduleHeader) + std::max<VkDeviceSize>(e.scheduleRuns, 1) * 8);
        }
    }
}

// The stored slot arrays of an emitter paired with host arrays of the same
// layout; serves both directions (upload at creation, download on
// readParticles), with the trail's positions when the emitter keeps them
// (p.trail sized to match).
std::vector<Transfer> slotTransfers(GpuEmitter& e, ParticleArrays& p) {
    static_assert(kStoredBytesPerSlot == 12 + 12 + 4 + 4 + 4, "the arrays below");
    const VkDeviceSize n = e.capacity;
    std::vector<Transfer> t{{&e.positions, p.position.data(), n * 12},
                            {&e.velocities, p.velocity.data(), n * 12},
                            {&e.ages, p.age.data(), n * 4},
                            {&e.births, p.birth.data(), n * 4},
                            {&e.rotations, p.rotation.data(), n * 4}};
    if (e.trailPoints > 0) {
        t.push_back({&e.trail, p.trail.data(), n * e.trailPoints * 12});
    }
    return t;
}

void uploadSlots(Device& d, GpuEmitter& e, const EmitterState& s) {
    // Transfer's host pointer serves both directions, so it is not const: work
    // on a copy (once per emitter, at creation only).
    kernels::EmitterParams params = s.params;
    ParticleArrays p = s.particles;
    const std::array<Transfer, 1> parameters{{{&e.params, &params, sizeof(params)}}};
    upload(d, parameters);
    upload(d, slotTransfers(e, p));
    if (e.spawn) {
        // Every slot dead, stacked as the CPU's free list: slot 0 on top.
        std::vector<std::uint32_t> dead(sizeof(DeadHeader) / 4 + s.freeSlots.size(), 0);
        DeadHeader header{0, 1, 1, static_cast<std::uint32_t>(s.freeSlots.size()), 0, s.nextSerial, 0, 0};
        std::memcpy(dead.data(), &header, sizeof(header));
        std::copy(s.freeSlots.begin(), s.freeSlots.end(), dead.begin() + sizeof(DeadHeader) / 4);
        TableHeader empty{0, 0, 0, 0};
        const std::array<Transfer, 3> lists{{{&e.dead, dead.data(), dead.size() * 4},
                                             {&e.alive[0], &empty, sizeof(empty)},
                                             {&e.alive[1], &empty, sizeof(empty)}}};
        upload(d, lists);
    }
}

}  // namespace

// INTEGRATOR of effects_update.comp: the emitter's, read from its parameters.
constexpr std::uint32_t kAnyIntegrator = kernels::SD_ANY_INTEGRATOR;

// The specialization constants of effects_update.comp, in constant_id order
// (with the pass, the key of GpuWorld::pipelines).
struct Specialization {
    std::uint32_t flowFields, heightMaps, cubeMaps;  // counts in the world
    std::uint32_t integrator;                        // SD_INTEGRATE_*
    std::uint32_t curlNoise;                         // 1: the emitter selects a curl-noise force
    std::array<std::uint32_t, kernels::SD_SPEC_COUNT> constants() const {
        std::array<std::uint32_t, kernels::SD_SPEC_COUNT> k{};
        k[kernels::SD_SPEC_FLOW_FIELDS] = flowFields;
        k[kernels::SD_SPEC_HEIGHT_MAPS] = heightMaps;
        k[kernels::SD_SPEC_CUBE_MAPS] = cubeMaps;
        k[kernels::SD_SPEC_INTEGRATOR] = integrator;
        k[kernels::SD_SPEC_CURL_NOISE] = curlNoise;
        return k;
    }
};

namespace {

// The SPIR-V of one pass of effects_update.comp.
std::span<const std::uint32_t> effectsUpdateModule(Pass pass) {
    switch (pass) {
    case Pass::RecycleUpdate:
        return {shaders::kEffectsUpdatePassRecycleUpdate, shaders::kEffectsUpdatePassRecycleUpdateWords};
    case Pass::SpawnUpdate:
        return {shaders::kEffectsUpdatePassSpawnUpdate, shaders::kEffectsUpdatePassSpawnUpdateWords};
    case Pass::SpawnEmit:
        return {shaders::kEffectsUpdatePassSpawnEmit, shaders::kEffectsUpdatePassSpawnEmitWords};
    case Pass::SpawnFinish:
        return {shaders::kEffectsUpdatePassSpawnFinish, shaders::kEffectsUpdatePassSpawnFinishWords};
    case Pass::SubEmit:
        return {shaders::kEffectsUpdatePassSubEmit, shaders::kEffectsUpdatePassSubEmitWords};
    }
    throw Error("effects_update: no module for this pass");
}

}  // namespace

// The pipeline of `pass` for emitter `e` in this world, created on first use.
// The finish pass touches no particle: it shares one variant.
VkPipeline pipelineFor(GpuWorld& w, Pass pass, const EmitterState& e) {
    Specialization spec{0, 0, 0, 0, 0};
    if (pass != Pass::SpawnFinish) {
        spec.flowFields = static_cast<std::uint32_t>(w.fields.flows.size());
        spec.heightMaps = static_cast<std::uint32_t>(w.fields.heights.size());
        spec.cubeMaps = static_cast<std::uint32_t>(w.fields.cubes.size());
        // One integrator per pipeline only where it pays: with flow fields each
        // of RK4's stages samples them, and compiling every integrator's sample
        // sites costs lavapipe far more than a second pipeline. Without flow
        // fields all four fit in one pipeline that compiles in about a second.
        // Curl noise is live only in the pipelines of emitters that select
        // it, one integrator each as with flow fields, so its inlined copies
        // (one per forcingAt) cost the other pipelines nothing at creation.
        spec.curlNoise = (e.params.forceMask & w.curlNoiseForces) != 0u ? 1u : 0u;
        spec.integrator = spec.flowFields > 0 || spec.curlNoise != 0u ? e.params.integrator : kAnyIntegrator;
    }
    const std::array<std::uint32_t, kernels::SD_SPEC_COUNT> constants = spec.constants();
    auto [it, inserted] = w.pipelines.try_emplace({static_cast<std::uint32_t>(pass), constants}, VK_NULL_HANDLE);
    if (inserted) {
        try {
            it->second = createComputePipeline(*w.device, w.pipelineLayout, effectsUpdateModule(pass), constants,
                                               "effects_update");
        } catch (...) {
            w.pipelines.erase(it);
            throw;
        }
    }
    return it->second;
}

void addEmitter(GpuWorld& w, const EmitterState& initial) {
    if (initial.def.stateless) {
        w.emitters.push_back(nullptr);  // a closed form: evaluated where it is read
        return;
    }
    Device& d = *w.device;
    auto groups = (initial.def.capacity + kWorkgroupSize - 1) / kWorkgroupSize;
    if (groups > d.properties.limits.maxComputeWorkGroupCount[0]) {
        throw Error(fmt::format("emitter '{}': capacity {} exceeds this device's {} workgroups of {}",
                                initial.def.name, initial.def.capacity,
                                d.properties.limits.maxComputeWorkGroupCount[0], kWorkgroupSize));
    }
    auto e = std::make_unique<GpuEmitter>();
    e->capacity = initial.def.capacity;
    e->spawn = initial.def.lifecycle == Lifecycle::Spawn;
    e->scheduleRuns = static_cast<std::uint32_t>(initial.def.bursts.size());
    e->trailPoints = initial.def.trail.points;
    if (initial.def.spawnOn.enabled()) {
        e->parent = initial.def.spawnOn.parent.index - 1;
        e->parentKind = static_cast<std::uint32_t>(initial.def.spawnOn.event);
    }
    try {
        allocateSlots(d, *e, w.framesInFlight);
        uploadSlots(d, *e, initial);
        createDescriptorSets(w, *e);
    } catch (...) {
        destroyEmitter(d, *e);
        throw;
    }
    w.emitters.push_back(std::move(e));
}

void followEvents(GpuWorld& w, std::size_t index, std::uint32_t kind) {
    GpuEmitter& e = *w.emitters.at(index);
    Buffer& r = e.requests[kind];
    if (r.buffer != VK_NULL_HANDLE) {
        return;  // another sub-emitter follows the same kind
    }
    waitForSteps(w);
    Device& d = *w.device;
    r = createStorageBuffer(d, sizeof(EventsHeader) +
                                   std::max<VkDeviceSize>(e.capacity, 1) * sizeof(kernels::SpawnRequest));
    EventsHeader header{0, e.capacity, 0, 0};
    const std::array<Transfer, 1> t{{{&r, &header, sizeof(header)}}};
    upload(d, t);
    // Point the emitter's sets at the new buffer (no step is using them).
    for (std::uint32_t f = 0; f < w.framesInFlight; ++f) {
        VkDescriptorBufferInfo info{r.buffer, 0, VK_WHOLE_SIZE};
        auto write = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        write.dstSet = e.descriptorSets[f];
        write.dstBinding = kernels::SD_BINDING_BIRTH_REQUESTS + kind;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        write.pBufferInfo = &info;
        vkUpdateDescriptorSets(d.device, 1, &write, 0, nullptr);
    }
}

void setEmitterParams(GpuWorld& w, std::size_t index, const kernels::EmitterParams& params) {
    GpuEmitter& e = *w.emitters.at(index);
    waitForSteps(w);
    kernels::EmitterParams copy = params;  // Transfer's host pointer is not const
    const std::array<Transfer, 1> parameters{{{&e.params, &copy, sizeof(copy)}}};
    upload(*w.device, parameters);
}

ParticleArrays readSlots(GpuWorld& w, std::size_t index, const kernels::EmitterParams& params) {
    waitForSteps(w);
    GpuEmitter& e = *w.emitters.at(index);
    const std::size_t n = e.capacity;
    ParticleArrays p;
    p.resize(n);
    p.trail.resize(n * e.trailPoints);
    download(*w.device, slotTransfers(e, p));
    // What the device does not store and the CPU's slots do (lifetime and
    // spin; colour and size are restored from the slots by readParticles),
    // recomputed by the kernel that the shader uses for the same purpose.
    for (std::size_t i = 0; i < n; ++i) {
        kernels::Particle q{};
        q.birth = p.birth[i];
        q = kernels::restoreBirthDraws(params, q);
        p.lifetime[i] = q.lifetime;
        p.angularVelocity[i] = q.angularVelocity;
    }
    return p;
}

}  // namespace spindrift::gpu
