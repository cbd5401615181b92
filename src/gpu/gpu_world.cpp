// The Vulkan backend's world: pipeline, parameter buffers and emitter slots.
#include "gpu/gpu_world.h"

#include "effects/params.h"
#include "effects/world_internal.h"
#include "gpu/shaders.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace spindrift::gpu {
namespace {

// Bindings of effects_update.comp, in order: emitter parameters, forces,
// colliders, the nine slot arrays (see GpuEmitter), the event counters.
constexpr std::uint32_t kBindingCount = 12;
constexpr std::uint32_t kWorkgroupSize = 64;  // local_size_x of effects_update.comp

struct PushConstants {
    float dt;
    std::uint32_t count;
};

// Event counters written by the shader: born, died, two pads, hits[32].
struct Counters {
    std::uint32_t born;
    std::uint32_t died;
    std::uint32_t pad[2];
    std::uint32_t hits[32];
};
static_assert(sizeof(Counters) == 144);

// Header of the forces and colliders buffers: count and three pads, so the
// array starts 16-byte aligned as std430 requires for its vec4 members.
constexpr VkDeviceSize kHeaderBytes = 16;

bool validationFromEnvironment() {
    const char* v = std::getenv("SPINDRIFT_VULKAN_VALIDATION");
    return v != nullptr && *v != '\0' && std::string_view(v) != "0";
}

std::atomic<bool>& validationSetting() {
    static std::atomic<bool> on{validationFromEnvironment()};
    return on;
}

VkDescriptorSetLayout createSetLayout(Device& d) {
    std::array<VkDescriptorSetLayoutBinding, kBindingCount> bindings{};
    for (std::uint32_t i = 0; i < kBindingCount; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    auto info = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.bindingCount = kBindingCount;
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(d.device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout");
    return layout;
}

VkPipelineLayout createPipelineLayout(Device& d, VkDescriptorSetLayout setLayout) {
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(PushConstants)};
    auto info = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    info.setLayoutCount = 1;
    info.pSetLayouts = &setLayout;
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(d.device, &info, nullptr, &layout), "vkCreatePipelineLayout");
    return layout;
}

VkPipeline createComputePipeline(Device& d, VkPipelineLayout layout, const std::uint32_t* code, std::size_t words) {
    auto moduleInfo = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    moduleInfo.codeSize = words * sizeof(std::uint32_t);
    moduleInfo.pCode = code;
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(d.device, &moduleInfo, nullptr, &module), "vkCreateShaderModule");
    auto info = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkResult r = vkCreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    // A module may be destroyed once its pipelines exist (Vulkan spec, vkDestroyShaderModule).
    vkDestroyShaderModule(d.device, module, nullptr);
    check(r, "vkCreateComputePipelines(effects_update)");
    return pipeline;
}

// A count header and the parameter array, uploaded in one submission.
template <class T>
void uploadTable(Device& d, Buffer& buffer, std::span<const T> items) {
    std::vector<char> bytes(kHeaderBytes + items.size_bytes(), 0);
    auto count = static_cast<std::uint32_t>(items.size());
    std::memcpy(bytes.data(), &count, sizeof(count));
    if (!items.empty()) {
        std::memcpy(bytes.data() + kHeaderBytes, items.data(), items.size_bytes());
    }
    Transfer t{&buffer, bytes.data(), bytes.size()};
    upload(d, std::span(&t, 1));
}

std::array<Buffer*, kBindingCount> bindingBuffers(GpuWorld& w, GpuEmitter& e) {
    return {&e.params,    &w.forces,    &w.colliders, &e.positions, &e.velocities, &e.ages,
            &e.lifetimes, &e.births,    &e.sizes,     &e.rotations, &e.colors,     &e.counters};
}

void createDescriptorSet(GpuWorld& w, GpuEmitter& e) {
    Device& d = *w.device;
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBindingCount};
    auto poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &e.descriptorPool), "vkCreateDescriptorPool");
    auto alloc = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = e.descriptorPool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &w.setLayout;
    check(vkAllocateDescriptorSets(d.device, &alloc, &e.descriptorSet), "vkAllocateDescriptorSets");
    std::array<VkDescriptorBufferInfo, kBindingCount> infos{};
    std::array<VkWriteDescriptorSet, kBindingCount> writes{};
    std::array<Buffer*, kBindingCount> buffers = bindingBuffers(w, e);
    for (std::uint32_t i = 0; i < kBindingCount; ++i) {
        infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
        writes[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[i].dstSet = e.descriptorSet;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(d.device, kBindingCount, writes.data(), 0, nullptr);
}

void destroyEmitter(Device& d, GpuEmitter& e) {
    if (e.descriptorPool != VK_NULL_HANDLE) {
        vkDestroyDescriptorPool(d.device, e.descriptorPool, nullptr);  // frees its set
    }
    for (Buffer* b : {&e.params, &e.positions, &e.velocities, &e.ages, &e.lifetimes, &e.births, &e.sizes,
                      &e.rotations, &e.colors, &e.counters}) {
        destroyBuffer(d, *b);
    }
}

void allocateSlots(Device& d, GpuEmitter& e) {
    // Vulkan buffers cannot be empty (VkBufferCreateInfo: size > 0).
    const VkDeviceSize n = std::max<VkDeviceSize>(e.capacity, 1);
    e.params = createStorageBuffer(d, sizeof(kernels::EmitterParams));
    e.positions = createStorageBuffer(d, n * 12);
    e.velocities = createStorageBuffer(d, n * 12);
    e.ages = createStorageBuffer(d, n * 4);
    e.lifetimes = createStorageBuffer(d, n * 4);
    e.births = createStorageBuffer(d, n * 4);
    e.sizes = createStorageBuffer(d, n * 4);
    e.rotations = createStorageBuffer(d, n * 8);
    e.colors = createStorageBuffer(d, n * 16);
    e.counters = createHostStorageBuffer(d, sizeof(Counters));
    std::memset(e.counters.mapped, 0, sizeof(Counters));
}

std::vector<glm::vec2> interleave(const std::vector<float>& a, const std::vector<float>& b) {
    std::vector<glm::vec2> out(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        out[i] = {a[i], b[i]};
    }
    return out;
}

void uploadSlots(Device& d, GpuEmitter& e, const EmitterState& s) {
    // Transfer's host pointer serves both directions, so it is not const: work
    // on a copy (once per emitter, at creation only).
    kernels::EmitterParams params = s.params;
    ParticleArrays p = s.particles;
    std::vector<glm::vec2> rotations = interleave(p.rotation, p.angularVelocity);
    const VkDeviceSize n = e.capacity;
    const std::array<Transfer, 9> transfers{{{&e.params, &params, sizeof(params)},
                                             {&e.positions, p.position.data(), n * 12},
                                             {&e.velocities, p.velocity.data(), n * 12},
                                             {&e.ages, p.age.data(), n * 4},
                                             {&e.lifetimes, p.lifetime.data(), n * 4},
                                             {&e.births, p.birth.data(), n * 4},
                                             {&e.sizes, p.size.data(), n * 4},
                                             {&e.rotations, rotations.data(), n * 8},
                                             {&e.colors, p.color.data(), n * 16}}};
    upload(d, transfers);
}

void recordUpdate(GpuWorld& w, VkCommandBuffer cmd, GpuEmitter& e, float dt) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w.pipelineLayout, 0, 1, &e.descriptorSet, 0,
                            nullptr);
    PushConstants push{dt, e.capacity};
    vkCmdPushConstants(cmd, w.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, (e.capacity + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1);
}

// Takes the step's counts out of the mapped counters and zeroes them for the
// next step (after the fence, so the device is done with them).
void collectCounters(GpuEmitter& e, EmitterState& s, StepStats& stats) {
    Counters c;
    std::memcpy(&c, e.counters.mapped, sizeof(c));
    std::memset(e.counters.mapped, 0, sizeof(c));
    for (std::size_t k = 0; k < stats.colliderHits.size() && k < 32; ++k) {
        stats.colliderHits[k].hits += c.hits[k];
    }
    s.alive = s.alive + c.born - c.died;
    stats.born += c.born;
    stats.died += c.died;
}

}  // namespace

void setWorldValidation(bool on) { validationSetting() = on; }

DebugLog& worldDebugLog() {
    static DebugLog log;
    return log;
}

std::unique_ptr<GpuWorld> createGpuWorld() {
    auto w = std::make_unique<GpuWorld>();
    try {
        w->device = createDevice({validationSetting().load(), &worldDebugLog()});
        Device& d = *w->device;
        w->setLayout = createSetLayout(d);
        w->pipelineLayout = createPipelineLayout(d, w->setLayout);
        w->updatePipeline =
            createComputePipeline(d, w->pipelineLayout, shaders::kEffectsUpdate, shaders::kEffectsUpdateWords);
        w->forces = createStorageBuffer(d, kHeaderBytes + kMaxForces * sizeof(kernels::ForceParams));
        w->colliders = createStorageBuffer(d, kHeaderBytes + kMaxColliders * sizeof(kernels::ColliderParams));
        uploadForces(*w, {});
        uploadColliders(*w, {});
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
        vkDeviceWaitIdle(d.device);
        for (auto& e : w.emitters) {
            if (e) {
                destroyEmitter(d, *e);
            }
        }
        w.emitters.clear();
        destroyBuffer(d, w.colliders);
        destroyBuffer(d, w.forces);
        if (w.updatePipeline != VK_NULL_HANDLE) {
            vkDestroyPipeline(d.device, w.updatePipeline, nullptr);
        }
        if (w.pipelineLayout != VK_NULL_HANDLE) {
            vkDestroyPipelineLayout(d.device, w.pipelineLayout, nullptr);
        }
        if (w.setLayout != VK_NULL_HANDLE) {
            vkDestroyDescriptorSetLayout(d.device, w.setLayout, nullptr);
        }
    }
    destroyDevice(d);
    w.device.reset();
}

void uploadForces(GpuWorld& w, std::span<const kernels::ForceParams> forces) {
    uploadTable(*w.device, w.forces, forces);
}

void uploadColliders(GpuWorld& w, std::span<const kernels::ColliderParams> colliders) {
    uploadTable(*w.device, w.colliders, colliders);
}

void addEmitter(GpuWorld& w, const EmitterState& initial) {
    if (initial.def.stateless) {
        w.emitters.push_back(nullptr);  // a closed form: evaluated where it is read
        return;
    }
    if (initial.def.lifecycle != Lifecycle::Recycle) {
        throw Error(fmt::format("emitter '{}': spawn-mode emitters are not supported on the vulkan backend yet; "
                                "use lifecycle 'recycle', a stateless emitter, or backend 'cpu'",
                                initial.def.name));
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
    try {
        allocateSlots(d, *e);
        uploadSlots(d, *e, initial);
        createDescriptorSet(w, *e);
    } catch (...) {
        destroyEmitter(d, *e);
        throw;
    }
    w.emitters.push_back(std::move(e));
}

void stepEmitters(GpuWorld& w, std::span<const std::unique_ptr<EmitterState>> emitters, float dt, StepStats& stats) {
    Device& d = *w.device;
    submitOnce(d, [&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, w.updatePipeline);
        // Emitters touch disjoint slot buffers and only add to their own
        // counters, so their dispatches need no barrier between them.
        for (auto& e : w.emitters) {
            if (e && e->capacity > 0) {
                recordUpdate(w, cmd, *e, dt);
            }
        }
        // Counters are read through the mapping after the fence: make the
        // shader's writes available to the host (Vulkan spec 7.9, host access).
        auto barrier = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                             nullptr, 0, nullptr);
    });
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        if (w.emitters[i]) {
            collectCounters(*w.emitters[i], *emitters[i], stats);
        }
    }
}

ParticleArrays readSlots(GpuWorld& w, std::size_t index) {
    GpuEmitter& e = *w.emitters.at(index);
    const VkDeviceSize n = e.capacity;
    ParticleArrays p;
    p.resize(n);
    std::vector<glm::vec2> rotations(n);
    const std::array<Transfer, 8> transfers{{{&e.positions, p.position.data(), n * 12},
                                             {&e.velocities, p.velocity.data(), n * 12},
                                             {&e.ages, p.age.data(), n * 4},
                                             {&e.lifetimes, p.lifetime.data(), n * 4},
                                             {&e.births, p.birth.data(), n * 4},
                                             {&e.sizes, p.size.data(), n * 4},
                                             {&e.rotations, rotations.data(), n * 8},
                                             {&e.colors, p.color.data(), n * 16}}};
    download(*w.device, transfers);
    for (std::size_t i = 0; i < n; ++i) {
        p.rotation[i] = rotations[i].x;
        p.angularVelocity[i] = rotations[i].y;
    }
    return p;
}

TransferStats transferStats(const GpuWorld& w) { return {w.device->bytesUploaded, w.device->bytesDownloaded}; }

}  // namespace spindrift::gpu

namespace spindrift::gpu {

void GpuWorldDeleter::operator()(GpuWorld* w) const {
    if (w != nullptr) {
        destroyGpuWorld(*w);
        delete w;
    }
}

}  // namespace spindrift::gpu
