// Graphics pipelines of the renderer: one small description per pipeline,
// one function that builds it.
#pragma once

#include "gpu/vulkan_device.h"

#include <cstdint>
#include <span>
#include <vector>

namespace spindrift::render {

/// WeightedOit: two colour attachments with one blend state (McGuire and
/// Bavoil 2013; no independentBlend needed): colour (ONE, ONE) sums, alpha
/// (ZERO, ONE_MINUS_SRC_ALPHA) multiplies the revealage.
enum class Blend { None, Additive, PremultipliedAlpha, WeightedOit };

struct PipelineDesc {
    const char* name = "";
    std::span<const std::uint32_t> vertexCode, fragmentCode;
    std::vector<VkDescriptorSetLayout> setLayouts;
    std::uint32_t pushConstantBytes = 0;  // vertex and fragment stages
    /// Vertex input: one interleaved binding of float3 attributes; 0: none.
    std::uint32_t vertexFloat3Attributes = 0;
    Blend blend = Blend::None;
    /// No colour attachment: the fragment shader writes depth only.
    bool depthOnly = false;
    bool depthTest = false;
    bool depthWrite = false;
    /// Cull faces wound clockwise as seen (closed meshes wound outward).
    bool cullBackFaces = false;
    VkRenderPass renderPass = VK_NULL_HANDLE;
};

/// A graphics pipeline with its layout.
struct Pipeline {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

/// The layout and the pipeline of `desc`; throws Error as the two below.
Pipeline makePipeline(gpu::Device& d, const PipelineDesc& desc);
/// Destroys both (either may be null) and resets `p`.
void destroyPipeline(gpu::Device& d, Pipeline& p);

/// Throws Error naming desc.name and the failing call.
VkPipeline createGraphicsPipeline(gpu::Device& d, const PipelineDesc& desc, VkPipelineLayout layout);
VkPipelineLayout createPipelineLayout(gpu::Device& d, const PipelineDesc& desc);

/// A descriptor set layout of `types[i]` at binding i, visible to the
/// vertex and fragment stages.
VkDescriptorSetLayout createSetLayout(gpu::Device& d, std::span<const VkDescriptorType> types);

}  // namespace spindrift::render
