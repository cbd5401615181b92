// The liquid surface's passes (see surface_pass.h and docs/rendering.md,
// "Liquid surface").
#include "render/surface_pass.h"

#include "gpu/shaders.h"
#include "render/collider_mesh.h"
#include "render/render_pipelines.h"
#include "render/surface_field.h"

#include <spindrift/effects.h>

#include <algorithm>
#include <cmath>

namespace spindrift::render {
namespace {

// Sums of kernels need blending into floats; R16G16B16A16_SFLOAT blends on
// every Vulkan device (the spec's required format features).
constexpr VkFormat kFieldFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

template <class T>
std::span<const std::uint32_t> code(const T* words, std::size_t count) {
    return {words, count};
}

// One colour attachment, cleared, left ready to be sampled (render_target.h).
VkRenderPass createFieldPass(gpu::Device& d) {
    return createSampledColourPass(d, kFieldFormat, VK_ATTACHMENT_LOAD_OP_CLEAR, "liquid surface");
}

void writeSampler(Renderer& r, VkDescriptorSet set, const gpu::Image& image) {
    VkDescriptorImageInfo info{r.linearSampler, image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    auto w = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.dstBinding = kernels::SD_SURFACE_BINDING_FIELD;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &info;
    vkUpdateDescriptorSets(r.device->device, 1, &w, 0, nullptr);
}

void destroyImages(gpu::Device& d, SurfaceField& s) {
    if (s.a.image == VK_NULL_HANDLE) {
        return;
    }
    vkDestroyFramebuffer(d.device, s.framebufferA, nullptr);
    vkDestroyFramebuffer(d.device, s.framebufferB, nullptr);
    gpu::destroyImage(d, s.a);
    gpu::destroyImage(d, s.b);
    s.framebufferA = s.framebufferB = VK_NULL_HANDLE;
    s.width = s.height = 0;
    s.scale = 0.0f;
}

void createImages(Renderer& r) {
    gpu::Device& d = *r.device;
    SurfaceField& s = r.surface;
    const float scale = r.def.fluid.surfaceScale;
    s.width = std::max(1u, static_cast<std::uint32_t>(std::lround(float(r.def.width) * scale)));
    s.height = std::max(1u, static_cast<std::uint32_t>(std::lround(float(r.def.height) * scale)));
    s.scale = scale;
    gpu::ImageShape shape{VK_IMAGE_VIEW_TYPE_2D, kFieldFormat, s.width, s.height, 1,
                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_COLOR_BIT};
    s.a = gpu::createSampledImage(d, shape);
    s.b = gpu::createSampledImage(d, shape);
    s.framebufferA = createSingleFramebuffer(d, s.pass, s.a, s.width, s.height, "liquid surface");
    s.framebufferB = createSingleFramebuffer(d, s.pass, s.b, s.width, s.height, "liquid surface");
    writeSampler(r, s.readA, s.a);
    writeSampler(r, s.readB, s.b);
}

void beginFieldPass(Renderer& r, VkCommandBuffer cmd, VkFramebuffer framebuffer) {
    const SurfaceField& s = r.surface;
    VkClearValue clear{};
    auto info = gpu::vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    info.renderPass = s.pass;
    info.framebuffer = framebuffer;
    info.renderArea = {{0, 0}, {s.width, s.height}};
    info.clearValueCount = 1;
    info.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport viewport{0.0f, 0.0f, float(s.width), float(s.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {s.width, s.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

// A full-field pass of `pipeline` (the blur or the depth) reading `from`.
void fieldPass(Renderer& r, VkCommandBuffer cmd, const Pipeline& pipeline, VkFramebuffer into, VkDescriptorSet from,
               glm::vec2 step) {
    beginFieldPass(r, cmd, into);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, from};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout, 0, 2, sets, 0, nullptr);
    const kernels::SurfacePush push{glm::vec4(step, 0.0f, 0.0f)};
    vkCmdPushConstants(cmd, pipeline.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
}

}  // namespace

void createSurface(Renderer& r) {
    namespace sh = gpu::shaders;
    gpu::Device& d = *r.device;
    SurfaceField& s = r.surface;
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(d.physical, kFieldFormat, &props);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
    if ((props.optimalTilingFeatures & needed) != needed) {
        throw Error("render: the Vulkan device cannot blend into or filter R16G16B16A16_SFLOAT (liquid surface)");
    }
    s.pass = createFieldPass(d);
    static_assert(kernels::SD_SURFACE_BINDING_FIELD == 0);
    const VkDescriptorType types[1] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    s.layout = createSetLayout(d, types);
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2};
    auto poolInfo = gpu::vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 2;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    gpu::check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &s.pool), "vkCreateDescriptorPool");
    VkDescriptorSetLayout layouts[2] = {s.layout, s.layout};
    VkDescriptorSet sets[2];
    auto alloc = gpu::vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = s.pool;
    alloc.descriptorSetCount = 2;
    alloc.pSetLayouts = layouts;
    gpu::check(vkAllocateDescriptorSets(d.device, &alloc, sets), "vkAllocateDescriptorSets");
    s.readA = sets[0];
    s.readB = sets[1];

    PipelineDesc field;
    field.name = "liquid surface field";
    field.vertexCode = code(sh::kSurfaceFieldVert, sh::kSurfaceFieldVertWords);
    field.fragmentCode = code(sh::kSurfaceFieldFrag, sh::kSurfaceFieldFragWords);
    field.setLayouts = {r.frameLayout, r.splatLayout};
    field.blend = Blend::Additive;
    field.renderPass = s.pass;
    r.surfaceField = makePipeline(d, field);

    PipelineDesc blurDesc;
    blurDesc.name = "liquid surface blur";
    blurDesc.vertexCode = code(sh::kBackgroundVert, sh::kBackgroundVertWords);
    blurDesc.fragmentCode = code(sh::kSurfaceBlurFrag, sh::kSurfaceBlurFragWords);
    blurDesc.setLayouts = {r.frameLayout, s.layout};
    blurDesc.pushConstantBytes = sizeof(kernels::SurfacePush);
    blurDesc.renderPass = s.pass;
    r.surfaceBlur = makePipeline(d, blurDesc);
    PipelineDesc depth = blurDesc;
    depth.name = "liquid surface depth";
    depth.fragmentCode = code(sh::kSurfaceDepthFrag, sh::kSurfaceDepthFragWords);
    r.surfaceDepth = makePipeline(d, depth);

    PipelineDesc composite;
    composite.name = "liquid surface";
    composite.vertexCode = code(sh::kSurfaceVert, sh::kSurfaceVertWords);
    composite.fragmentCode = code(sh::kSurfaceFrag, sh::kSurfaceFragWords);
    composite.setLayouts = {r.frameLayout, s.layout};
    composite.pushConstantBytes = sizeof(kernels::SurfacePush);
    composite.blend = Blend::PremultipliedAlpha;
    composite.depthTest = true;
    composite.renderPass = r.passes.second;
    r.surfaceComposite = makePipeline(d, composite);
}

void destroySurface(Renderer& r) {
    gpu::Device& d = *r.device;
    SurfaceField& s = r.surface;
    destroyImages(d, s);
    for (Pipeline* p : {&r.surfaceField, &r.surfaceBlur, &r.surfaceDepth, &r.surfaceComposite}) {
        destroyPipeline(d, *p);
    }
    vkDestroyDescriptorPool(d.device, s.pool, nullptr);
    vkDestroyDescriptorSetLayout(d.device, s.layout, nullptr);
    vkDestroyRenderPass(d.device, s.pass, nullptr);
    s = SurfaceField{};
}

void prepareSurface(Renderer& r) {
    SurfaceField& s = r.surface;
    s.drawn = false;
    for (const SplatFluid& f : r.fluids) {
        s.drawn = s.drawn || (f.surface && f.particles > 0);
    }
    if (!s.drawn) {
        return;
    }
    if (s.a.image != VK_NULL_HANDLE && s.scale != r.def.fluid.surfaceScale) {
        vkDeviceWaitIdle(r.device->device);  // a viewer's frame in flight may still read them
        destroyImages(*r.device, s);
    }
    if (s.a.image == VK_NULL_HANDLE) {
        createImages(r);
    }
}

void recordSurfaceField(Renderer& r, VkCommandBuffer cmd) {
    SurfaceField& s = r.surface;
    if (!s.drawn) {
        return;
    }
    beginFieldPass(r, cmd, s.framebufferA);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.surfaceField.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, r.splatSet};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.surfaceField.layout, 0, 2, sets, 0, nullptr);
    for (const SplatFluid& f : r.fluids) {
        if (f.surface && f.particles > 0) {
            vkCmdDraw(cmd, 6, f.particles, 0, f.first);
        }
    }
    vkCmdEndRenderPass(cmd);
    fieldPass(r, cmd, r.surfaceBlur, s.framebufferB, s.readA, {1.0f / float(s.width), 0.0f});
    fieldPass(r, cmd, r.surfaceBlur, s.framebufferA, s.readB, {0.0f, 1.0f / float(s.height)});
    fieldPass(r, cmd, r.surfaceDepth, s.framebufferB, s.readA, {0.0f, 0.0f});
}

void recordSurfaceComposite(Renderer& r, VkCommandBuffer cmd) {
    if (!r.surface.drawn) {
        return;
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.surfaceComposite.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, r.surface.readB};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.surfaceComposite.layout, 0, 2, sets, 0, nullptr);
    // A quad far larger than the view (planeExtent's reach), in z = 0.
    const float aspect = float(r.def.width) / float(r.def.height);
    const kernels::SurfacePush push{glm::vec4(4.0f * planeExtent(r.def.camera, aspect), 0.0f, 0.0f, 0.0f)};
    vkCmdPushConstants(cmd, r.surfaceComposite.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    vkCmdDraw(cmd, 6, 1, 0, 0);
}

}  // namespace spindrift::render
