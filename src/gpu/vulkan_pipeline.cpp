// Compute pipelines and barriers shared by the GPU passes.
#include "gpu/vulkan_pipeline.h"

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

}  // namespace spindrift::gpu
