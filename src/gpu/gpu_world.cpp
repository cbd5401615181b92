// The Vulkan backend's world: pipeline, parameter buffers and emitter slots.
#include "gpu/gpu_world.h"

#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/layout.glsl"
#include "particles/birth_schedule.h"
#include "particles/cpu_kernels.h"
#include "particles/params.h"

#include <fmt/format.h>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string_view>

namespace spindrift::gpu {
namespace {

// Binding numbers, buffer headers, push constants and limits of
// effects_update.comp are those of src/kernels/layout.glsl, which the shader
// includes too.
using kernels::DeadHeader;
using kernels::EventsHeader;
using kernels::ScheduleHeader;
using kernels::StepCounters;
using kernels::StepPush;
using kernels::TableHeader;
constexpr std::uint32_t kBindingCount = kernels::SD_EMITTER_BINDINGS;
constexpr std::uint32_t kListBindingCount = kernels::SD_LIST_BINDINGS;
constexpr std::uint32_t kWorkgroupSize = kernels::SD_UPDATE_WORKGROUP;

// The PASS specialization constant of effects_update.comp.
enum class Pass : std::uint32_t {
    RecycleUpdate = kernels::SD_PASS_RECYCLE_UPDATE,
    SpawnUpdate = kernels::SD_PASS_SPAWN_UPDATE,
    SpawnEmit = kernels::SD_PASS_SPAWN_EMIT,
    SpawnFinish = kernels::SD_PASS_SPAWN_FINISH,
};

bool validationFromEnvironment() {
    const char* v = std::getenv("SPINDRIFT_VULKAN_VALIDATION");
    return v != nullptr && *v != '\0' && std::string_view(v) != "0";
}

std::atomic<bool>& validationSetting() {
    static std::atomic<bool> on{validationFromEnvironment()};
    return on;
}

VkDescriptorSetLayout createSetLayout(Device& d, std::uint32_t count) {
    std::array<VkDescriptorSetLayoutBinding, kBindingCount> bindings{};
    for (std::uint32_t i = 0; i < count; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    auto info = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.bindingCount = count;
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(d.device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout");
    return layout;
}

VkPipelineLayout createPipelineLayout(Device& d, VkDescriptorSetLayout setLayout, VkDescriptorSetLayout listLayout,
                                      VkDescriptorSetLayout fieldLayout) {
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(StepPush)};
    std::array<VkDescriptorSetLayout, 3> layouts{setLayout, listLayout, fieldLayout};
    auto info = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    info.setLayoutCount = 3;
    info.pSetLayouts = layouts.data();
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(d.device, &info, nullptr, &layout), "vkCreatePipelineLayout");
    return layout;
}

// INTEGRATOR of effects_update.comp: the emitter's, read from its parameters.
constexpr std::uint32_t kAnyIntegrator = kernels::SD_ANY_INTEGRATOR;

// The specialization constants of effects_update.comp, in constant_id order
// (the key of GpuWorld::pipelines).
struct Specialization {
    Pass pass;
    std::uint32_t flowFields, heightMaps, cubeMaps;  // counts in the world
    std::uint32_t integrator;                        // SD_INTEGRATE_*
    std::array<std::uint32_t, kernels::SD_SPEC_COUNT> key() const {
        std::array<std::uint32_t, kernels::SD_SPEC_COUNT> k{};
        k[kernels::SD_SPEC_PASS] = static_cast<std::uint32_t>(pass);
        k[kernels::SD_SPEC_FLOW_FIELDS] = flowFields;
        k[kernels::SD_SPEC_HEIGHT_MAPS] = heightMaps;
        k[kernels::SD_SPEC_CUBE_MAPS] = cubeMaps;
        k[kernels::SD_SPEC_INTEGRATOR] = integrator;
        return k;
    }
};

// The pipeline of `pass` for emitter `e` in this world, created on first use.
// The finish pass touches no particle: it shares one variant.
VkPipeline pipelineFor(GpuWorld& w, Pass pass, const EmitterState& e) {
    Specialization spec{pass, 0, 0, 0, 0};
    if (pass != Pass::SpawnFinish) {
        spec.flowFields = static_cast<std::uint32_t>(w.fields.flows.size());
        spec.heightMaps = static_cast<std::uint32_t>(w.fields.heights.size());
        spec.cubeMaps = static_cast<std::uint32_t>(w.fields.cubes.size());
        // One integrator per pipeline only where it pays: with flow fields each
        // of RK4's stages samples them, and compiling every integrator's sample
        // sites costs lavapipe far more than a second pipeline. Without flow
        // fields all four fit in one pipeline that compiles in about a second.
        spec.integrator = spec.flowFields > 0 ? e.params.integrator : kAnyIntegrator;
    }
    auto [it, inserted] = w.pipelines.try_emplace(spec.key(), VK_NULL_HANDLE);
    if (inserted) {
        try {
            const std::array<std::uint32_t, kernels::SD_SPEC_COUNT> constants = spec.key();
            it->second = createComputePipeline(*w.device, w.pipelineLayout,
                                               std::span(shaders::kEffectsUpdate, shaders::kEffectsUpdateWords),
                                               constants, "effects_update");
        } catch (...) {
            w.pipelines.erase(it);
            throw;
        }
    }
    return it->second;
}

// A count header and the parameter array, uploaded in one submission.
template <class T>
void uploadTable(Device& d, Buffer& buffer, std::span<const T> items) {
    std::vector<char> bytes(sizeof(TableHeader) + items.size_bytes(), 0);
    const TableHeader header{static_cast<std::uint32_t>(items.size()), 0, 0, 0};
    std::memcpy(bytes.data(), &header, sizeof(header));
    if (!items.empty()) {
        std::memcpy(bytes.data() + sizeof(TableHeader), items.data(), items.size_bytes());
    }
    Transfer t{&buffer, bytes.data(), bytes.size()};
    upload(d, std::span(&t, 1));
}

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
    return b;
}

// Set 1 of a spawn emitter: alive[p] is the current list, alive[1 - p] the next.
std::array<Buffer*, kListBindingCount> listBuffers(GpuEmitter& e, std::uint32_t p, std::uint32_t frame) {
    std::array<Buffer*, kListBindingCount> b{};
    b[kernels::SD_BINDING_DEAD] = &e.dead;
    b[kernels::SD_BINDING_ALIVE_IN] = &e.alive[p];
    b[kernels::SD_BINDING_ALIVE_OUT] = &e.alive[1 - p];
    b[kernels::SD_BINDING_SCHEDULE] = &e.schedules[frame];
    return b;
}

VkDescriptorPool createDescriptorPool(Device& d, std::uint32_t sets, std::uint32_t buffers) {
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, buffers};
    auto poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = sets;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
    return pool;
}

// Allocates a set of `layout` from `pool` and points binding i at buffers[i].
VkDescriptorSet writeSet(Device& d, VkDescriptorPool pool, VkDescriptorSetLayout layout,
                         std::span<Buffer* const> buffers) {
    auto alloc = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &layout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    check(vkAllocateDescriptorSets(d.device, &alloc, &set), "vkAllocateDescriptorSets");
    std::array<VkDescriptorBufferInfo, kBindingCount> infos{};
    std::array<VkWriteDescriptorSet, kBindingCount> writes{};
    auto n = static_cast<std::uint32_t>(buffers.size());
    for (std::uint32_t i = 0; i < n; ++i) {
        infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
        writes[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[i].dstSet = set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(d.device, n, writes.data(), 0, nullptr);
    return set;
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
                std::array<Buffer*, kListBindingCount> lists = listBuffers(e, p, f);
                e.listSets[p][f] = writeSet(d, e.descriptorPool, w.listLayout, lists);
            }
        }
    }
}

void destroyEmitter(Device& d, GpuEmitter& e) {
    if (e.descriptorPool != VK_NULL_HANDLE) {
        vkDestroyDescriptorPool(d.device, e.descriptorPool, nullptr);  // frees its set
    }
    for (Buffer* b : {&e.params, &e.positions, &e.velocities, &e.ages, &e.births, &e.rotations, &e.dead,
                      &e.alive[0], &e.alive[1]}) {
        destroyBuffer(d, *b);
    }
    for (std::uint32_t f = 0; f < kMaxFramesInFlight; ++f) {
        destroyBuffer(d, e.counters[f]);
        destroyBuffer(d, e.schedules[f]);
    }
}

void allocateSlots(Device& d, GpuEmitter& e, std::uint32_t frames) {
    // Vulkan buffers cannot be empty (VkBufferCreateInfo: size > 0).
    const VkDeviceSize n = std::max<VkDeviceSize>(e.capacity, 1);
    e.params = createStorageBuffer(d, sizeof(kernels::EmitterParams));
    e.positions = createStorageBuffer(d, n * 12);
    e.velocities = createStorageBuffer(d, n * 12);
    e.ages = createStorageBuffer(d, n * 4);
    e.births = createStorageBuffer(d, n * 4);
    e.rotations = createStorageBuffer(d, n * 4);
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
// readParticles).
std::array<Transfer, 5> slotTransfers(GpuEmitter& e, ParticleArrays& p) {
    static_assert(kStoredBytesPerSlot == 12 + 12 + 4 + 4 + 4, "the arrays below");
    const VkDeviceSize n = e.capacity;
    return {{{&e.positions, p.position.data(), n * 12},
             {&e.velocities, p.velocity.data(), n * 12},
             {&e.ages, p.age.data(), n * 4},
             {&e.births, p.birth.data(), n * 4},
             {&e.rotations, p.rotation.data(), n * 4}}};
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
        const TableHeader empty{0, 0, 0, 0};
        const std::array<Transfer, 3> lists{{{&e.dead, dead.data(), dead.size() * 4},
                                             {&e.alive[0], &empty, sizeof(empty)},
                                             {&e.alive[1], &empty, sizeof(empty)}}};
        upload(d, lists);
    }
}

// Writes the spawn emitter's schedule for this step into its mapped buffer
// (read by the emit pass after the submission; host writes before
// vkQueueSubmit need no barrier) and returns how many births it owes.
std::uint32_t writeSchedule(GpuEmitter& e, std::uint32_t frame, EmitterState& s, double time, float dt) {
    BirthSchedule b = scheduleBirths(s, time, dt);
    std::uint64_t total = b.total();
    if (total > std::numeric_limits<std::uint32_t>::max()) {
        throw Error(fmt::format("emitter '{}': {} births in one step", s.def.name, total));
    }
    ScheduleHeader h{};
    h.burstRuns = static_cast<std::uint32_t>(b.bursts.size());
    h.rateSpan = static_cast<float>(b.t1 - b.t0);
    h.rateCarry = static_cast<float>(b.carry);
    h.rate = static_cast<float>(b.rate);
    h.maxAge = static_cast<float>(b.dt);
    auto* runs = reinterpret_cast<std::uint32_t*>(static_cast<char*>(e.schedules[frame].mapped) + sizeof(h));
    std::uint32_t end = 0;
    for (std::size_t r = 0; r < b.bursts.size(); ++r) {
        end += b.bursts[r].count;
        runs[2 * r] = end;
        std::memcpy(&runs[2 * r + 1], &b.bursts[r].age, 4);
    }
    h.rateFirst = end;
    std::memcpy(e.schedules[frame].mapped, &h, sizeof(h));
    return static_cast<std::uint32_t>(total);
}

void bindEmitter(GpuWorld& w, VkCommandBuffer cmd, std::uint32_t frame, std::size_t index, float dt,
                 std::uint32_t count) {
    GpuEmitter& e = *w.emitters[index];
    std::array<VkDescriptorSet, 3> sets{e.descriptorSets[frame],
                                        e.spawn ? e.listSets[e.parity][frame] : w.placeholderSet, w.fields.set};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w.pipelineLayout, 0, 3, sets.data(), 0, nullptr);
    StepPush push{dt, count, static_cast<std::uint32_t>(index), 0};
    vkCmdPushConstants(cmd, w.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
}

std::uint32_t groupsFor(std::uint32_t threads) { return (threads + kWorkgroupSize - 1) / kWorkgroupSize; }

// Takes a finished step's counts out of the mapped counters and zeroes them
// for the step that reuses the frame.
void collectCounters(GpuEmitter& e, std::uint32_t frame, EmitterState& s, StepStats& stats) {
    StepCounters c;
    std::memcpy(&c, e.counters[frame].mapped, sizeof(c));
    std::memset(e.counters[frame].mapped, 0, sizeof(c));
    for (std::size_t k = 0; k < stats.colliderHits.size() && k < kernels::SD_MAX_COLLIDERS; ++k) {
        stats.colliderHits[k].hits += c.hits[k];
    }
    s.alive = s.alive + c.born - c.died;
    stats.born += c.born;
    stats.died += c.died;
    stats.clamped += c.clamped;
    if (e.spawn) {
        // Every birth of a spawn emitter came from the emit pass, numbered
        // from the device's nextSerial in schedule order, as the CPU does.
        s.nextSerial += c.born;
    }
}

// Takes a finished step's events out of the frame's mapped buffer.
void collectEvents(GpuFrame& f, EventQueue& events) {
    EventsHeader h;
    std::memcpy(&h, f.events.mapped, sizeof(h));
    const std::uint32_t kept = std::min(h.count, h.capacity);
    const auto* records =
        reinterpret_cast<const kernels::EventRecord*>(static_cast<const char*>(f.events.mapped) + sizeof(h));
    events.addStep(f.step, std::span(records, kept), h.count - kept);
    h.count = 0;
    std::memcpy(f.events.mapped, &h, sizeof(h));
}

// Waits for frame f's step (if one is pending) and frees its command buffer.
bool waitForFrame(Device& d, GpuFrame& f) {
    if (f.cmd == VK_NULL_HANDLE) {
        return false;
    }
    check(vkWaitForFences(d.device, 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(d.device, 1, &f.fence), "vkResetFences");
    vkFreeCommandBuffers(d.device, d.commandPool, 1, &f.cmd);
    f.cmd = VK_NULL_HANDLE;
    return true;
}

// Device time (ms) of frame f's finished step, from its two timestamps.
double deviceMilliseconds(GpuWorld& w, std::uint32_t frame) {
    if (w.timestamps == VK_NULL_HANDLE) {
        return 0.0;
    }
    std::uint64_t ticks[2] = {0, 0};
    VkResult r = vkGetQueryPoolResults(w.device->device, w.timestamps, 2 * frame, 2, sizeof(ticks), ticks,
                                       sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT);
    check(r, "vkGetQueryPoolResults");
    return static_cast<double>(ticks[1] - ticks[0]) * w.timestampPeriodNs * 1e-6;
}

// The compute queue's timestamps, if it has any: a pool of two per frame.
void createTimestamps(GpuWorld& w) {
    Device& d = *w.device;
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &families, nullptr);
    std::vector<VkQueueFamilyProperties> properties(families);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &families, properties.data());
    if (properties.at(d.queueFamily).timestampValidBits == 0) {
        return;
    }
    auto info = vkStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2 * kMaxFramesInFlight;
    check(vkCreateQueryPool(d.device, &info, nullptr, &w.timestamps), "vkCreateQueryPool");
    w.timestampPeriodNs = d.properties.limits.timestampPeriod;
}

// Waits for frame f's step, if any, and collects its counts and events. The
// fence wait makes the device's writes to host-coherent memory visible (the
// step ends with a barrier to the host stage; Vulkan spec 7.9).
void collectFrame(GpuWorld& w, std::uint32_t frame, std::span<const std::unique_ptr<EmitterState>> emitters,
                  StepStats& stats, EventQueue& events) {
    GpuFrame& f = w.frames[frame];
    const std::uint64_t step = f.step;
    if (!waitForFrame(*w.device, f)) {
        return;
    }
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        if (w.emitters[i]) {
            collectCounters(*w.emitters[i], frame, *emitters[i], stats);
        }
    }
    collectEvents(f, events);
    stats.deviceMilliseconds += deviceMilliseconds(w, frame);
    stats.countedSteps += 1;
    stats.lastCountedStep = step;
}

// --- Sampled fields (set 2) ---------------------------------------------------
// Bindings of set 2 of effects_update.comp, one array of combined image
// samplers each, indexed by binding number: flowFields (sampler3D),
// heightMaps (sampler2D), cubeMaps (samplerCube).
static_assert(kernels::SD_BINDING_FLOW_FIELDS == 0 && kernels::SD_BINDING_HEIGHT_MAPS == 1 &&
              kernels::SD_BINDING_CUBE_MAPS == 2 && kernels::SD_FIELD_BINDINGS == 3);
constexpr std::array<std::uint32_t, 3> kFieldArraySizes{kMaxGpuFlowFields, kMaxGpuHeightMaps, kMaxGpuCubeMaps};
constexpr std::uint32_t kFieldDescriptors = kMaxGpuFlowFields + kMaxGpuHeightMaps + kMaxGpuCubeMaps;

// 32-bit float where the device filters it linearly (lavapipe and desktop GPUs
// do), else 16-bit float; UNDEFINED when neither.
VkFormat pickFloatFormat(const Device& d, VkFormat full, VkFormat half) {
    if (linearFilterable(d, full)) {
        return full;
    }
    return linearFilterable(d, half) ? half : VK_FORMAT_UNDEFINED;
}

bool isHalf(VkFormat f) { return f == VK_FORMAT_R16_SFLOAT || f == VK_FORMAT_R16G16B16A16_SFLOAT; }

// Texels as the image stores them: the floats as they are, or as halves.
std::vector<char> texelBytes(const float* values, std::size_t count, VkFormat format) {
    std::vector<char> bytes;
    if (isHalf(format)) {
        bytes.resize(count * 2);
        for (std::size_t i = 0; i < count; ++i) {
            std::uint16_t h = glm::packHalf1x16(values[i]);
            std::memcpy(bytes.data() + 2 * i, &h, 2);
        }
    } else {
        bytes.resize(count * 4);
        std::memcpy(bytes.data(), values, count * 4);
    }
    return bytes;
}


VkDescriptorSetLayout createFieldLayout(Device& d) {
    std::array<VkDescriptorSetLayoutBinding, 3> bindings{};
    for (std::uint32_t i = 0; i < 3; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        bindings[i].descriptorCount = kFieldArraySizes[i];
        bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    auto info = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.bindingCount = 3;
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(d.device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout(fields)");
    return layout;
}

// Points every element of set 2 at its field's image, or at the placeholder.
// Only between submissions: every submission has completed (submitOnce waits
// on its fence), so no pending command buffer uses the set.
void writeFieldSet(GpuWorld& w) {
    GpuFields& f = w.fields;
    std::array<VkDescriptorImageInfo, kFieldDescriptors> infos{};
    std::array<VkWriteDescriptorSet, 3> writes{};
    const std::array<const std::vector<Image>*, 3> images{&f.flows, &f.heights, &f.cubes};
    const std::array<const Image*, 3> placeholders{&f.placeholder3d, &f.placeholder2d, &f.placeholderCube};
    std::uint32_t at = 0;
    for (std::uint32_t b = 0; b < 3; ++b) {
        writes[b] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[b].dstSet = f.set;
        writes[b].dstBinding = b;
        writes[b].descriptorCount = kFieldArraySizes[b];
        writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[b].pImageInfo = &infos[at];
        for (std::uint32_t i = 0; i < kFieldArraySizes[b]; ++i, ++at) {
            const Image& img = i < images[b]->size() ? (*images[b])[i] : *placeholders[b];
            infos[at] = {f.sampler, img.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        }
    }
    vkUpdateDescriptorSets(w.device->device, 3, writes.data(), 0, nullptr);
}

void createFields(GpuWorld& w) {
    Device& d = *w.device;
    GpuFields& f = w.fields;
    f.flowFormat = pickFloatFormat(d, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT);
    f.heightFormat = pickFloatFormat(d, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16_SFLOAT);
    f.cubeFormat = pickFloatFormat(d, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT);
    f.sampler = createLinearSampler(d);
    f.layout = createFieldLayout(d);
    // Placeholders: R8G8B8A8_UNORM, which every device samples and filters
    // (Vulkan spec, "Required Format Support"); zeros, never read.
    const ImageShape shapes[3] = {{VK_IMAGE_VIEW_TYPE_3D, VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1},
                                  {VK_IMAGE_VIEW_TYPE_2D, VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1},
                                  {VK_IMAGE_VIEW_TYPE_CUBE, VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1}};
    Image* placeholders[3] = {&f.placeholder3d, &f.placeholder2d, &f.placeholderCube};
    for (int i = 0; i < 3; ++i) {
        *placeholders[i] = createSampledImage(d, shapes[i]);
        clearImage(d, *placeholders[i], shapes[i]);
    }
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kFieldDescriptors};
    auto poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &f.pool), "vkCreateDescriptorPool(fields)");
    auto alloc = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = f.pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &f.layout;
    check(vkAllocateDescriptorSets(d.device, &alloc, &f.set), "vkAllocateDescriptorSets(fields)");
    writeFieldSet(w);
}

void destroyFields(Device& d, GpuFields& f) {
    if (f.pool != VK_NULL_HANDLE) {
        vkDestroyDescriptorPool(d.device, f.pool, nullptr);  // frees its set
    }
    for (std::vector<Image>* images : {&f.cubes, &f.heights, &f.flows}) {
        for (Image& img : *images) {
            destroyImage(d, img);
        }
        images->clear();
    }
    for (Image* img : {&f.placeholderCube, &f.placeholder2d, &f.placeholder3d}) {
        destroyImage(d, *img);
    }
    if (f.layout != VK_NULL_HANDLE) {
        vkDestroyDescriptorSetLayout(d.device, f.layout, nullptr);
    }
    if (f.sampler != VK_NULL_HANDLE) {
        vkDestroySampler(d.device, f.sampler, nullptr);
    }
    f = GpuFields{};
}

// The checks every field shares, before anything is created.
void requireFieldRoom(const GpuWorld& w, const std::vector<Image>& images, std::uint32_t max, VkFormat format,
                      const char* what, const std::string& name) {
    const Device& d = *w.device;
    if (images.size() >= max) {
        throw Error(fmt::format("{} '{}': a vulkan world holds at most {} {}s", what, name, max, what));
    }
    if (format == VK_FORMAT_UNDEFINED) {
        throw Error(fmt::format("{} '{}': this Vulkan device ({}) cannot filter 32-bit or 16-bit float images "
                                "linearly; use backend 'cpu'",
                                what, name, d.properties.deviceName));
    }
}

void requireExtent(const Device& d, std::uint32_t size, std::uint32_t limit, const char* what,
                   const std::string& name) {
    if (size > limit) {
        throw Error(fmt::format("{} '{}': {} texels along an axis exceed this Vulkan device's limit of {} ({})", what,
                                name, size, limit, d.properties.deviceName));
    }
}

// Creates and uploads one field image; on failure nothing is left behind.
void appendField(GpuWorld& w, std::vector<Image>& images, const ImageShape& shape, const std::vector<char>& bytes) {
    waitForSteps(w);  // no step in flight may use the descriptor set rewritten below
    Device& d = *w.device;
    Image img = createSampledImage(d, shape);
    try {
        uploadImage(d, img, shape, bytes.data(), bytes.size());
        images.push_back(img);
    } catch (...) {
        destroyImage(d, img);
        throw;
    }
    writeFieldSet(w);
}

}  // namespace

void setWorldValidation(bool on) { validationSetting() = on; }

namespace {
std::vector<std::string>& presentationSetting() {
    static std::vector<std::string> extensions;
    return extensions;
}
}  // namespace

void setPresentationExtensions(std::vector<std::string> instanceExtensions) {
    presentationSetting() = std::move(instanceExtensions);
}

DeviceOptions worldDeviceOptions() {
    DeviceOptions o;
    o.validation = validationSetting().load();
    o.log = &worldDebugLog();
    o.instanceExtensions = presentationSetting();
    return o;
}

DebugLog& worldDebugLog() {
    static DebugLog log;
    return log;
}

std::unique_ptr<GpuWorld> createGpuWorld(std::uint32_t framesInFlight, std::uint32_t eventCapacity) {
    if (framesInFlight < 1 || framesInFlight > kMaxFramesInFlight) {
        throw Error(fmt::format("framesInFlight must be 1 to {}, got {}", kMaxFramesInFlight, framesInFlight));
    }
    auto w = std::make_unique<GpuWorld>();
    w->framesInFlight = framesInFlight;
    w->eventCapacity = eventCapacity;
    try {
        w->device = createDevice(worldDeviceOptions());
        Device& d = *w->device;
        w->setLayout = createSetLayout(d, kBindingCount);
        w->listLayout = createSetLayout(d, kListBindingCount);
        createFields(*w);
        w->pipelineLayout = createPipelineLayout(d, w->setLayout, w->listLayout, w->fields.layout);
        w->placeholder = createStorageBuffer(d, 64);
        w->placeholderPool = createDescriptorPool(d, 1, kListBindingCount);
        std::array<Buffer*, kListBindingCount> placeholders{&w->placeholder, &w->placeholder, &w->placeholder,
                                                             &w->placeholder};
        w->placeholderSet = writeSet(d, w->placeholderPool, w->listLayout, placeholders);
        w->forces = createStorageBuffer(d, sizeof(TableHeader) + kernels::SD_MAX_FORCES * sizeof(kernels::ForceParams));
        w->colliders = createStorageBuffer(d, sizeof(TableHeader) + kernels::SD_MAX_COLLIDERS * sizeof(kernels::ColliderParams));
        uploadForces(*w, {});
        uploadColliders(*w, {});
        createTimestamps(*w);
        for (std::uint32_t f = 0; f < framesInFlight; ++f) {
            GpuFrame& frame = w->frames[f];
            auto fenceInfo = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
            check(vkCreateFence(d.device, &fenceInfo, nullptr, &frame.fence), "vkCreateFence");
            frame.events = createHostStorageBuffer(d, sizeof(EventsHeader) +
                                                          std::max<VkDeviceSize>(eventCapacity, 1) *
                                                              sizeof(kernels::EventRecord));
            EventsHeader header{0, eventCapacity, 0, 0};
            std::memcpy(frame.events.mapped, &header, sizeof(header));
        }
    } catch (...) {
        destroyGpuWorld(*w);
        throw;
    }
    return w;
}

// Reverse order of creation; accepts a half-built world.
void destroyGpuWorld(GpuWorld& w) {
    if (!w.device) {
        return;
    }
    Device& d = *w.device;
    if (d.device != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(d.device);  // teardown, not the step loop
        if (w.timestamps != VK_NULL_HANDLE) {
            vkDestroyQueryPool(d.device, w.timestamps, nullptr);
        }
        w.sort.reset();
        for (GpuFrame& f : w.frames) {
            if (f.cmd != VK_NULL_HANDLE) {
                vkFreeCommandBuffers(d.device, d.commandPool, 1, &f.cmd);
            }
            if (f.fence != VK_NULL_HANDLE) {
                vkDestroyFence(d.device, f.fence, nullptr);
            }
            destroyBuffer(d, f.events);
            f = GpuFrame{};
        }
        for (auto& e : w.emitters) {
            if (e) {
                destroyEmitter(d, *e);
            }
        }
        w.emitters.clear();
        if (w.placeholderPool != VK_NULL_HANDLE) {
            vkDestroyDescriptorPool(d.device, w.placeholderPool, nullptr);
        }
        destroyBuffer(d, w.placeholder);
        destroyFields(d, w.fields);
        destroyBuffer(d, w.colliders);
        destroyBuffer(d, w.forces);
        for (auto& [key, p] : w.pipelines) {
            vkDestroyPipeline(d.device, p, nullptr);
        }
        w.pipelines.clear();
        if (w.pipelineLayout != VK_NULL_HANDLE) {
            vkDestroyPipelineLayout(d.device, w.pipelineLayout, nullptr);
        }
        for (VkDescriptorSetLayout l : {w.listLayout, w.setLayout}) {
            if (l != VK_NULL_HANDLE) {
                vkDestroyDescriptorSetLayout(d.device, l, nullptr);
            }
        }
    }
    destroyDevice(d);
    w.device.reset();
}

void uploadForces(GpuWorld& w, std::span<const kernels::ForceParams> forces) {
    waitForSteps(w);
    uploadTable(*w.device, w.forces, forces);
}

void uploadColliders(GpuWorld& w, std::span<const kernels::ColliderParams> colliders) {
    waitForSteps(w);
    uploadTable(*w.device, w.colliders, colliders);
}

void addFlowField(GpuWorld& w, const FlowGrid& grid, const std::string& name) {
    GpuFields& f = w.fields;
    requireFieldRoom(w, f.flows, kMaxGpuFlowFields, f.flowFormat, "flow field", name);
    const std::uint32_t limit = w.device->properties.limits.maxImageDimension3D;
    requireExtent(*w.device, std::max({grid.nx, grid.ny, grid.nz}), limit, "flow field", name);
    // x fastest, then y, then z: the layout of FlowGrid and of a 3D image copy.
    std::vector<glm::vec4> texels(grid.velocity.size());
    for (std::size_t i = 0; i < texels.size(); ++i) {
        texels[i] = glm::vec4(grid.velocity[i], 0.0f);
    }
    appendField(w, f.flows, {VK_IMAGE_VIEW_TYPE_3D, f.flowFormat, grid.nx, grid.ny, grid.nz},
                texelBytes(&texels.data()->x, texels.size() * 4, f.flowFormat));
}

void addHeightMap(GpuWorld& w, const HeightMap& map, const std::string& name) {
    GpuFields& f = w.fields;
    requireFieldRoom(w, f.heights, kMaxGpuHeightMaps, f.heightFormat, "height map", name);
    const std::uint32_t limit = w.device->properties.limits.maxImageDimension2D;
    requireExtent(*w.device, std::max(map.nx, map.nz), limit, "height map", name);
    // x fastest, then z: image x is the terrain's x, image y its z.
    appendField(w, f.heights, {VK_IMAGE_VIEW_TYPE_2D, f.heightFormat, map.nx, map.nz, 1},
                texelBytes(map.height.data(), map.height.size(), f.heightFormat));
}

void addCubeMap(GpuWorld& w, const DepthCubeMap& cube, const std::string& name) {
    GpuFields& f = w.fields;
    requireFieldRoom(w, f.cubes, kMaxGpuCubeMaps, f.cubeFormat, "cube map", name);
    const std::uint32_t limit = w.device->properties.limits.maxImageDimensionCube;
    requireExtent(*w.device, cube.resolution, limit, "cube map", name);
    // Texel (face, u, v) at (face * res + v) * res + u: layer = face in Vulkan's
    // order (+x, -x, +y, -y, +z, -z; src/core/cube_map.h), row v, column u.
    appendField(w, f.cubes, {VK_IMAGE_VIEW_TYPE_CUBE, f.cubeFormat, cube.resolution, cube.resolution, 1},
                texelBytes(&cube.texels.data()->x, cube.texels.size() * 4, f.cubeFormat));
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

void waitForSteps(GpuWorld& w) {
    for (std::uint32_t f = 0; f < w.framesInFlight; ++f) {
        GpuFrame& frame = w.frames[f];
        if (frame.cmd != VK_NULL_HANDLE) {
            check(vkWaitForFences(w.device->device, 1, &frame.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        }
    }
}

void collectAll(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, StepStats& stats,
                EventQueue& events) {
    // Frames are reused round robin: the next to submit holds the oldest
    // pending step (or none).
    for (std::uint32_t k = 0; k < w.framesInFlight; ++k) {
        collectFrame(w, static_cast<std::uint32_t>((w.submitted + k) % w.framesInFlight), emitters, stats, events);
    }
}

void stepEmitters(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, double time, float dt,
                  std::uint64_t step, StepStats& stats, EventQueue& events) {
    Device& d = *w.device;
    // This frame's counters, schedules and events buffer were last used by
    // step `step - framesInFlight`, collected at the end of the previous call.
    const auto frame = static_cast<std::uint32_t>(w.submitted % w.framesInFlight);

    // Births owed this step, per emitter (spawn mode), from the shared schedule.
    std::vector<std::uint32_t> births(w.emitters.size(), 0);
    // The pipelines of each emitter's passes (compiled here on first use, not
    // while recording).
    std::vector<std::array<VkPipeline, 3>> pipelines(w.emitters.size());
    bool anySpawn = false;
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        GpuEmitter* e = w.emitters[i].get();
        if (!e || e->capacity == 0) {
            continue;
        }
        if (e->spawn) {
            births[i] = writeSchedule(*e, frame, *emitters[i], time, dt);
            anySpawn = true;
            pipelines[i] = {pipelineFor(w, Pass::SpawnUpdate, *emitters[i]),
                            pipelineFor(w, Pass::SpawnEmit, *emitters[i]),
                            pipelineFor(w, Pass::SpawnFinish, *emitters[i])};
        } else {
            pipelines[i][0] = pipelineFor(w, Pass::RecycleUpdate, *emitters[i]);
        }
    }
    auto spawning = [&](std::size_t i) {
        GpuEmitter* e = w.emitters[i].get();
        return e && e->spawn && e->capacity > 0;
    };

    VkCommandBuffer cmd = beginOneTime(d);
    if (w.timestamps != VK_NULL_HANDLE) {
        vkCmdResetQueryPool(cmd, w.timestamps, 2 * frame, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, w.timestamps, 2 * frame);
    }
    // Earlier steps' and uploads' writes (lists, the indirect dispatch)
    // before this step reads them, also as an indirect command.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    // Update: recycle emitters over every slot, spawn emitters over their
    // current alive list (its size written by the GPU last step). Emitters
    // touch disjoint buffers and only add to shared counters atomically, so
    // the dispatches of one pass need no barrier between them.
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        GpuEmitter* e = w.emitters[i].get();
        if (e && e->capacity > 0) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[i][0]);
            bindEmitter(w, cmd, frame, i, dt, e->capacity);
            if (e->spawn) {
                vkCmdDispatchIndirect(cmd, e->dead.buffer, 0);
            } else {
                vkCmdDispatch(cmd, groupsFor(e->capacity), 1, 1);
            }
        }
    }
    if (anySpawn) {
        // Emit: the dead stack is complete once every update is done.
        computeToCompute(cmd);
        for (std::size_t i = 0; i < w.emitters.size(); ++i) {
            if (spawning(i) && births[i] > 0) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[i][1]);
                bindEmitter(w, cmd, frame, i, dt, births[i]);
                // Births beyond the capacity cannot find a slot: thread 0
                // counts them, so the dispatch stays within the device limit.
                vkCmdDispatch(cmd, groupsFor(std::min(births[i], w.emitters[i]->capacity)), 1, 1);
            }
        }
        // Finish: pop the taken slots, number the births, write the next
        // update's dispatch.
        computeToCompute(cmd);
        for (std::size_t i = 0; i < w.emitters.size(); ++i) {
            if (spawning(i)) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines[i][2]);
                bindEmitter(w, cmd, frame, i, dt, births[i]);
                vkCmdDispatch(cmd, 1, 1, 1);
            }
        }
        // The next step's update reads the dispatch and the lists.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }
    // Counters and events are read through the mapping after the fence: make
    // the shader's writes available to the host (Vulkan spec 7.9, host access).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
            VK_ACCESS_HOST_READ_BIT);
    if (w.timestamps != VK_NULL_HANDLE) {
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, w.timestamps, 2 * frame + 1);
    }
    VkResult r = vkEndCommandBuffer(cmd);
    if (r == VK_SUCCESS) {
        auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        r = vkQueueSubmit(d.queue, 1, &submit, w.frames[frame].fence);
    }
    if (r != VK_SUCCESS) {
        vkFreeCommandBuffers(d.device, d.commandPool, 1, &cmd);
        check(r, "vkQueueSubmit(step)");
    }
    w.frames[frame].cmd = cmd;
    w.frames[frame].step = step;
    w.submitted += 1;
    for (auto& e : w.emitters) {
        if (e && e->spawn) {
            e->parity = 1 - e->parity;  // the next list becomes the current one
        }
    }
    // Collect step `step - (framesInFlight - 1)`, whose frame the next call
    // reuses: with one frame that is this step (a wait), with more an earlier
    // one that is usually done, so the host and the device overlap.
    collectFrame(w, static_cast<std::uint32_t>(w.submitted % w.framesInFlight), emitters, stats, events);
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
    download(*w.device, slotTransfers(e, p));
    // What the device does not store, recomputed by the kernel that the
    // shader uses for the same purpose.
    for (std::size_t i = 0; i < n; ++i) {
        kernels::Particle q{};
        q.age = p.age[i];
        q.birth = p.birth[i];
        q = kernels::restoreDerived(params, q);
        p.lifetime[i] = q.lifetime;
        p.angularVelocity[i] = q.angularVelocity;
        p.color[i] = q.color;
        p.size[i] = q.size;
    }
    return p;
}

TransferStats transferStats(const GpuWorld& w) { return {w.device->bytesUploaded, w.device->bytesDownloaded}; }

}  // namespace spindrift::gpu
