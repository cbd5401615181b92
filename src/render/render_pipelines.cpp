// Graphics pipelines of the renderer (see render_pipelines.h).
#include "render/render_pipelines.h"

#include <spindrift/effects.h>

#include <fmt/format.h>

namespace spindrift::render {
namespace {

VkShaderModule createModule(gpu::Device& d, std::span<const std::uint32_t> code, const char* name) {
    auto info = gpu::vkStruct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = code.size_bytes();
    info.pCode = code.data();
    VkShaderModule module = VK_NULL_HANDLE;
    VkResult r = vkCreateShaderModule(d.device, &info, nullptr, &module);
    if (r != VK_SUCCESS) {
        throw Error(fmt::format("{}: vkCreateShaderModule failed: {}", name, gpu::resultName(r)));
    }
    return module;
}

VkPipelineColorBlendAttachmentState blendState(Blend blend) {
    VkPipelineColorBlendAttachmentState b{};
    b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                       VK_COLOR_COMPONENT_A_BIT;
    if (blend == Blend::None) {
        return b;
    }
    b.blendEnable = VK_TRUE;
    b.colorBlendOp = VK_BLEND_OP_ADD;
    b.alphaBlendOp = VK_BLEND_OP_ADD;
    if (blend == Blend::WeightedOit) {  // colour sums, alpha the product of (1 - a)
        b.srcColorBlendFactor = b.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
        b.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;
        b.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        return b;
    }
    // Shaders output colour premultiplied by alpha: "over" is (1, 1 - a);
    // additive light is (1, 1), alpha kept as the destination's.
    b.blendEnable = VK_TRUE;
    b.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
    b.dstColorBlendFactor = blend == Blend::Additive ? VK_BLEND_FACTOR_ONE : VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    b.colorBlendOp = VK_BLEND_OP_ADD;
    b.srcAlphaBlendFactor = blend == Blend::Additive ? VK_BLEND_FACTOR_ZERO : VK_BLEND_FACTOR_ONE;
    b.dstAlphaBlendFactor = blend == Blend::Additive ? VK_BLEND_FACTOR_ONE : VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    b.alphaBlendOp = VK_BLEND_OP_ADD;
    return b;
}

}  // namespace

VkDescriptorSetLayout createSetLayout(gpu::Device& d, std::span<const VkDescriptorType> types) {
    std::vector<VkDescriptorSetLayoutBinding> bindings(types.size());
    for (std::uint32_t i = 0; i < types.size(); ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = types[i];
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    }
    auto info = gpu::vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.bindingCount = static_cast<std::uint32_t>(bindings.size());
    info.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    gpu::check(vkCreateDescriptorSetLayout(d.device, &info, nullptr, &layout), "vkCreateDescriptorSetLayout");
    return layout;
}

VkPipelineLayout createPipelineLayout(gpu::Device& d, const PipelineDesc& desc) {
    VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, desc.pushConstantBytes};
    auto info = gpu::vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    info.setLayoutCount = static_cast<std::uint32_t>(desc.setLayouts.size());
    info.pSetLayouts = desc.setLayouts.data();
    info.pushConstantRangeCount = desc.pushConstantBytes > 0 ? 1u : 0u;
    info.pPushConstantRanges = &range;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    gpu::check(vkCreatePipelineLayout(d.device, &info, nullptr, &layout), "vkCreatePipelineLayout");
    return layout;
}

VkPipeline createGraphicsPipeline(gpu::Device& d, const PipelineDesc& desc, VkPipelineLayout layout) {
    VkShaderModule vs = createModule(d, desc.vertexCode, desc.name);
    VkShaderModule fs = VK_NULL_HANDLE;
    try {
        fs = createModule(d, desc.fragmentCode, desc.name);
    } catch (...) {
        vkDestroyShaderModule(d.device, vs, nullptr);
        throw;
    }
    VkPipelineShaderStageCreateInfo stages[2] = {
        gpu::vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO),
        gpu::vkStruct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO)};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;
    stages[1].pName = "main";

    VkVertexInputBindingDescription binding{0, desc.vertexFloat3Attributes * 12u, VK_VERTEX_INPUT_RATE_VERTEX};
    std::vector<VkVertexInputAttributeDescription> attributes;
    for (std::uint32_t i = 0; i < desc.vertexFloat3Attributes; ++i) {
        attributes.push_back({i, 0, VK_FORMAT_R32G32B32_SFLOAT, i * 12u});
    }
    auto input = gpu::vkStruct<VkPipelineVertexInputStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
    if (desc.vertexFloat3Attributes > 0) {
        input.vertexBindingDescriptionCount = 1;
        input.pVertexBindingDescriptions = &binding;
        input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(attributes.size());
        input.pVertexAttributeDescriptions = attributes.data();
    }
    auto assembly = gpu::vkStruct<VkPipelineInputAssemblyStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    auto viewport = gpu::vkStruct<VkPipelineViewportStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    auto raster = gpu::vkStruct<VkPipelineRasterizationStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    // Vulkan's signed-area formula carries a minus sign for its y-down
    // framebuffer (spec, "Basic Polygon Rasterization"): a triangle wound
    // counter-clockwise as the viewer sees it is front-facing.
    raster.cullMode = desc.cullBackFaces ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    auto multisample = gpu::vkStruct<VkPipelineMultisampleStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    auto depth = gpu::vkStruct<VkPipelineDepthStencilStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
    depth.depthTestEnable = desc.depthTest ? VK_TRUE : VK_FALSE;
    depth.depthWriteEnable = desc.depthWrite ? VK_TRUE : VK_FALSE;
    depth.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    // Identical states: the independentBlend feature is not enabled.
    VkPipelineColorBlendAttachmentState attachments[2] = {blendState(desc.blend), blendState(desc.blend)};
    auto blend = gpu::vkStruct<VkPipelineColorBlendStateCreateInfo>(
        VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
    blend.attachmentCount = desc.depthOnly ? 0u : desc.blend == Blend::WeightedOit ? 2u : 1u;
    blend.pAttachments = attachments;
    VkDynamicState dynamicStates[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    auto dynamic = gpu::vkStruct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamicStates;

    auto info = gpu::vkStruct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend;
    info.pDynamicState = &dynamic;
    info.layout = layout;
    info.renderPass = desc.renderPass;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkResult r = vkCreateGraphicsPipelines(d.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline);
    vkDestroyShaderModule(d.device, vs, nullptr);
    vkDestroyShaderModule(d.device, fs, nullptr);
    if (r != VK_SUCCESS) {
        throw Error(fmt::format("{}: vkCreateGraphicsPipelines failed: {}", desc.name, gpu::resultName(r)));
    }
    return pipeline;
}

Pipeline makePipeline(gpu::Device& d, const PipelineDesc& desc) {
    Pipeline p;
    p.layout = createPipelineLayout(d, desc);
    try {
        p.pipeline = createGraphicsPipeline(d, desc, p.layout);
    } catch (...) {
        vkDestroyPipelineLayout(d.device, p.layout, nullptr);
        throw;
    }
    return p;
}

void destroyPipeline(gpu::Device& d, Pipeline& p) {
    vkDestroyPipeline(d.device, p.pipeline, nullptr);
    vkDestroyPipelineLayout(d.device, p.layout, nullptr);
    p = Pipeline{};
}

}  // namespace spindrift::render
