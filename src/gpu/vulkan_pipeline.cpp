// Compute pipelines and barriers shared by the GPU passes.
#include "gpu/vulkan_pipeline.h"

#include <spindrift/errors.h>

#include <fmt/format.h>

#include <string>
#include <vector>

namespace spindrift::gpu {

VkPipeline createComputePipeline(Device& d, VkPipelineLayout layout, std::span<const std::uint32_t> code,
                                 std::span<const std::uint32_t> constants, const char* name) {
    auto moduleInfo = vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    moduleInfo.codeSize = code.size_bytes();
    moduleInfo.pCode = code.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(d.device, &moduleInfo, nullptr, &module),
          fmt::format("vkCreateShaderModule({})", name).c_str());
    std::vector<VkSpecializationMapEntry> entries(constants.size());
    for (std::uint32_t i = 0; i < entries.size(); ++i) {
        entries[i] = {i, i * 4, 4};
    }
    VkSpecializationInfo specialization{static_cast<std::uint32_t>(entries.size()), entries.data(),
                                        constants.size_bytes(), constants.data()};
    auto info = vkStruct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = constants.empty() ? nullptr : &specialization;
    info.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkResult r = vkCreateComputePipelines(d.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    // A module may be destroyed once its pipelines exist (Vulkan spec, vkDestroyShaderModule).
    vkDestroyShaderModule(d.device, module, nullptr);
    check(r, fmt::format("vkCreateComputePipelines({})", name).c_str());
    return pipeline;
}

namespace {

/// One pipeline per pass of a shader whose specialization constant 0 picks
/// the pass: pipelines[p] runs pass p. Throws Error as createComputePipeline,
/// having destroyed the pipelines it made.
void createPassPipelines(Device& d, VkPipelineLayout layout, std::span<const std::uint32_t> code,
                         std::span<VkPipeline> pipelines, const char* name) {
    for (std::uint32_t pass = 0; pass < pipelines.size(); ++pass) {
        const std::uint32_t constants[1] = {pass};
        try {
            pipelines[pass] = createComputePipeline(d, layout, code, constants, name);
        } catch (...) {
            for (std::uint32_t made = 0; made < pass; ++made) {  // none left behind
                vkDestroyPipeline(d.device, pipelines[made], nullptr);
                pipelines[made] = VK_NULL_HANDLE;
            }
            throw;
        }
    }
}

}  // namespace

StorageLayouts createStorageLayouts(Device& d, std::uint32_t bindings, std::uint32_t pushBytes,
                                    std::span<VkDescriptorSet> sets, const char* name) {
    auto call = [&](const char* what) { return fmt::format("{}({})", what, name); };
    StorageLayouts l;
    std::vector<VkDescriptorSetLayoutBinding> layoutBindings(bindings);
    for (std::uint32_t i = 0; i < bindings; ++i) {
        layoutBindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    }
    auto setInfo = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    setInfo.bindingCount = bindings;
    setInfo.pBindings = layoutBindings.data();
    check(vkCreateDescriptorSetLayout(d.device, &setInfo, nullptr, &l.setLayout),
          call("vkCreateDescriptorSetLayout").c_str());
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes};
    auto layoutInfo = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &l.setLayout;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &range;
    check(vkCreatePipelineLayout(d.device, &layoutInfo, nullptr, &l.pipelineLayout),
          call("vkCreatePipelineLayout").c_str());
    const auto count = static_cast<std::uint32_t>(sets.size());
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, count * bindings};
    auto poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = count;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &l.pool), call("vkCreateDescriptorPool").c_str());
    const std::vector<VkDescriptorSetLayout> layouts(count, l.setLayout);
    auto alloc = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = l.pool;
    alloc.descriptorSetCount = count;
    alloc.pSetLayouts = layouts.data();
    check(vkAllocateDescriptorSets(d.device, &alloc, sets.data()), call("vkAllocateDescriptorSets").c_str());
    return l;
}

void destroyComputePasses(Device& d, std::initializer_list<VkPipeline> pipelines, VkDescriptorPool pool,
                          VkPipelineLayout pipelineLayout, VkDescriptorSetLayout setLayout) {
    for (VkPipeline p : pipelines) {
        if (p != VK_NULL_HANDLE) vkDestroyPipeline(d.device, p, nullptr);
    }
    if (pool != VK_NULL_HANDLE) vkDestroyDescriptorPool(d.device, pool, nullptr);
    if (pipelineLayout != VK_NULL_HANDLE) vkDestroyPipelineLayout(d.device, pipelineLayout, nullptr);
    if (setLayout != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(d.device, setLayout, nullptr);
}

void createComputePasses(Device& d, std::uint32_t bindings, std::uint32_t pushBytes, std::uint32_t sets,
                         std::span<const std::uint32_t> code, std::uint32_t passes, const char* name,
                         ComputePasses& out) {
    out.sets.assign(sets, VK_NULL_HANDLE);
    const StorageLayouts l = createStorageLayouts(d, bindings, pushBytes, out.sets, name);
    out.setLayout = l.setLayout;
    out.pipelineLayout = l.pipelineLayout;
    out.pool = l.pool;
    out.pipelines.assign(passes, VK_NULL_HANDLE);
    createPassPipelines(d, out.pipelineLayout, code, out.pipelines, name);
}

void destroyComputePasses(Device& d, ComputePasses& passes) {
    for (VkPipeline p : passes.pipelines) {
        if (p != VK_NULL_HANDLE) vkDestroyPipeline(d.device, p, nullptr);
    }
    passes.pipelines.clear();
    destroyComputePasses(d, {}, passes.pool, passes.pipelineLayout, passes.setLayout);
    passes = ComputePasses{};
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
    auto b = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void computeToCompute(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void writeStorageSet(Device& d, VkDescriptorSet set, std::span<const Buffer* const> buffers) {
    std::vector<VkDescriptorBufferInfo> infos(buffers.size());
    std::vector<VkWriteDescriptorSet> writes(buffers.size());
    for (std::size_t i = 0; i < buffers.size(); ++i) {
        infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
        writes[i] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[i].dstSet = set;
        writes[i].dstBinding = static_cast<std::uint32_t>(i);
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(d.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

void dispatchCompute(VkCommandBuffer cmd, VkPipeline pipeline, VkPipelineLayout layout, VkDescriptorSet set,
                     const void* push, std::uint32_t pushBytes, std::uint32_t groups) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, pushBytes, push);
    vkCmdDispatch(cmd, groups, 1, 1);
}

std::uint32_t workgroupsFor(const Device& d, std::uint64_t items, std::uint32_t workgroup, const char* pass,
                            const char* what) {
    const std::uint64_t groups = (items + workgroup - 1) / workgroup;
    const std::uint32_t maxGroups = d.properties.limits.maxComputeWorkGroupCount[0];
    if (groups > maxGroups) {
        throw Error(fmt::format("{}: {} {} need {} workgroups of {}; this device dispatches at most {}", pass, items,
                                what, groups, workgroup, maxGroups));
    }
    return static_cast<std::uint32_t>(groups);
}

}  // namespace spindrift::gpu
