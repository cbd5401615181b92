// The Vulkan backend's world: device settings, descriptor set and pipeline
// layouts, creation and destruction, forces and colliders (see
// gpu_world_parts.h for the other jobs' files).
#include "gpu/gpu_world.h"

#include "gpu/gpu_world_parts.h"
#include "gpu/vulkan_pipeline.h"

#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace spindrift::gpu {
namespace {

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

}  // namespace

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
        std::array<Buffer*, kListBindingCount> placeholders{};
        placeholders.fill(&w->placeholder);
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
    w.curlNoiseForces = 0;
    for (std::size_t i = 0; i < forces.size() && i < kernels::SD_MAX_FORCES; ++i) {
        if (forces[i].kind == kernels::SD_FORCE_CURL_NOISE) {
            w.curlNoiseForces |= 1u << i;
        }
    }
}

void uploadColliders(GpuWorld& w, std::span<const kernels::ColliderParams> colliders) {
    waitForSteps(w);
    uploadTable(*w.device, w.colliders, colliders);
}

TransferStats transferStats(const GpuWorld& w) { return {w.device->bytesUploaded, w.device->bytesDownloaded}; }

}  // namespace spindrift::gpu
