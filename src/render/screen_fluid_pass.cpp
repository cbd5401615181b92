// The screen-space liquid's passes (see screen_fluid_pass.h and
// docs/rendering.md, "Screen-space liquid").
#include "render/screen_fluid_pass.h"

#include "gpu/shaders.h"
#include "render/render_pipelines.h"
#include "render/surface_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace spindrift::render {
namespace {

// Thickness is a sum: it needs a blendable float format (R16G16B16A16_SFLOAT
// blends on every Vulkan device). The smoothed depth needs 32-bit floats
// (metres over a view several metres deep, to a fraction of a millimetre);
// R32_SFLOAT is a colour attachment everywhere and is read with texelFetch
// (linear filtering of it is optional).
constexpr VkFormat kThicknessFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kSmoothFormat = VK_FORMAT_R32_SFLOAT;
// Smoothing: two rounds of across-then-down.
constexpr int kSmoothRounds = 2;
// The bilateral filter's depth falloff, in sphere radii: taps farther in
// depth than about this count for little (the surfaces of two bodies of
// water, one in front of the other, stay apart).
constexpr float kDepthFalloffRadii = 2.0f;
// The thickness kernel's radius, in fluid spacings: at 2 a lattice's sum is
// even to a few per cent; at the spheres' 0.75 it shows the lattice.
constexpr float kThicknessSpacings = 2.0f;

template <class T>
std::span<const std::uint32_t> code(const T* words, std::size_t count) {
    return {words, count};
}

void writeSet(Renderer& r, VkDescriptorSet set, VkImageView depth, VkImageLayout depthLayout) {
    static_assert(kernels::SD_SCREEN_FLUID_BINDING_DEPTH == 0 && kernels::SD_SCREEN_FLUID_BINDING_THICKNESS == 1);
    VkDescriptorImageInfo images[2] = {
        {r.nearestSampler, depth, depthLayout},
        {r.linearSampler, r.screen.thickness.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    auto w = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.dstBinding = 0;
    w.descriptorCount = 2;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = images;
    vkUpdateDescriptorSets(r.device->device, 1, &w, 0, nullptr);
}

void destroyImages(gpu::Device& d, ScreenFluid& s) {
    if (s.depth.image == VK_NULL_HANDLE) {
        return;
    }
    for (VkFramebuffer fb : {s.depthFramebuffer, s.thicknessFramebuffer, s.framebufferA, s.framebufferB}) {
        vkDestroyFramebuffer(d.device, fb, nullptr);
    }
    for (gpu::Image* i : {&s.depth, &s.thickness, &s.a, &s.b}) {
        gpu::destroyImage(d, *i);
    }
    s.depthFramebuffer = s.thicknessFramebuffer = s.framebufferA = s.framebufferB = VK_NULL_HANDLE;
    s.width = s.height = 0;
    s.scale = 0.0f;
}

void createImages(Renderer& r) {
    gpu::Device& d = *r.device;
    ScreenFluid& s = r.screen;
    const float scale = r.def.fluid.surfaceScale;
    s.width = std::max(1u, static_cast<std::uint32_t>(std::lround(float(r.def.width) * scale)));
    s.height = std::max(1u, static_cast<std::uint32_t>(std::lround(float(r.def.height) * scale)));
    s.scale = scale;
    const VkImageUsageFlags colour = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    s.depth = gpu::createSampledImage(d, {VK_IMAGE_VIEW_TYPE_2D, kDepthFormat, s.width, s.height, 1,
                                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                          VK_IMAGE_ASPECT_DEPTH_BIT});
    s.thickness = gpu::createSampledImage(
        d, {VK_IMAGE_VIEW_TYPE_2D, kThicknessFormat, s.width, s.height, 1, colour, VK_IMAGE_ASPECT_COLOR_BIT});
    s.a = gpu::createSampledImage(
        d, {VK_IMAGE_VIEW_TYPE_2D, kSmoothFormat, s.width, s.height, 1, colour, VK_IMAGE_ASPECT_COLOR_BIT});
    s.b = gpu::createSampledImage(
        d, {VK_IMAGE_VIEW_TYPE_2D, kSmoothFormat, s.width, s.height, 1, colour, VK_IMAGE_ASPECT_COLOR_BIT});
    const char* what = "screen-space liquid";
    s.depthFramebuffer = createSingleFramebuffer(d, s.depthPass, s.depth, s.width, s.height, what);
    s.thicknessFramebuffer = createSingleFramebuffer(d, s.thicknessPass, s.thickness, s.width, s.height, what);
    s.framebufferA = createSingleFramebuffer(d, s.smoothPass, s.a, s.width, s.height, what);
    s.framebufferB = createSingleFramebuffer(d, s.smoothPass, s.b, s.width, s.height, what);
    writeSet(r, s.readDepth, s.depth.view, kDepthReadLayout);
    writeSet(r, s.readA, s.a.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    writeSet(r, s.readB, s.b.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

void checkFormats(gpu::Device& d) {
    auto has = [&](VkFormat format, VkFormatFeatureFlags needed) {
        VkFormatProperties props{};
        vkGetPhysicalDeviceFormatProperties(d.physical, format, &props);
        return (props.optimalTilingFeatures & needed) == needed;
    };
    if (!has(kSmoothFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) ||
        !has(kThicknessFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT |
                                   VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT)) {
        throw Error("render: the Vulkan device cannot draw into or sample R32_SFLOAT and R16G16B16A16_SFLOAT "
                    "(screen-space liquid)");
    }
}

// Passes, descriptor sets and pipelines: once, on the first frame that
// draws a 3D fluid as a liquid.
void createScreenFluid(Renderer& r) {
    namespace sh = gpu::shaders;
    gpu::Device& d = *r.device;
    ScreenFluid& s = r.screen;
    checkFormats(d);
    s.depthPass = createSampledDepthPass(d, "screen-space liquid");
    s.thicknessPass = createSampledColourPass(d, kThicknessFormat, VK_ATTACHMENT_LOAD_OP_CLEAR, "screen-space liquid");
    s.smoothPass = createSampledColourPass(d, kSmoothFormat, VK_ATTACHMENT_LOAD_OP_DONT_CARE, "screen-space liquid");
    const VkDescriptorType types[2] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                       VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    s.layout = createSetLayout(d, types);
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6};
    auto poolInfo = gpu::vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 3;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    gpu::check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &s.pool), "vkCreateDescriptorPool");
    VkDescriptorSetLayout layouts[3] = {s.layout, s.layout, s.layout};
    VkDescriptorSet sets[3];
    auto alloc = gpu::vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = s.pool;
    alloc.descriptorSetCount = 3;
    alloc.pSetLayouts = layouts;
    gpu::check(vkAllocateDescriptorSets(d.device, &alloc, sets), "vkAllocateDescriptorSets");
    s.readDepth = sets[0];
    s.readA = sets[1];
    s.readB = sets[2];

    PipelineDesc spheres;
    spheres.name = "screen-space liquid depth";
    spheres.vertexCode = code(sh::kScreenFluidSphereVert, sh::kScreenFluidSphereVertWords);
    spheres.fragmentCode = code(sh::kScreenFluidDepthFrag, sh::kScreenFluidDepthFragWords);
    spheres.setLayouts = {r.frameLayout, r.splatLayout};
    spheres.pushConstantBytes = sizeof(kernels::ScreenFluidPush);
    spheres.depthTest = true;
    spheres.depthWrite = true;
    spheres.depthOnly = true;
    spheres.renderPass = s.depthPass;
    s.spheres = makePipeline(d, spheres);

    PipelineDesc thickness = spheres;
    thickness.name = "screen-space liquid thickness";
    thickness.fragmentCode = code(sh::kScreenFluidThicknessFrag, sh::kScreenFluidThicknessFragWords);
    thickness.depthTest = false;
    thickness.depthWrite = false;
    thickness.depthOnly = false;
    thickness.blend = Blend::Additive;
    thickness.renderPass = s.thicknessPass;
    s.thicknessSpheres = makePipeline(d, thickness);

    PipelineDesc smooth;
    smooth.name = "screen-space liquid smoothing";
    smooth.vertexCode = code(sh::kBackgroundVert, sh::kBackgroundVertWords);
    smooth.fragmentCode = code(sh::kScreenFluidSmoothFrag, sh::kScreenFluidSmoothFragWords);
    smooth.setLayouts = {r.frameLayout, s.layout};
    smooth.pushConstantBytes = sizeof(kernels::ScreenFluidPush);
    smooth.renderPass = s.smoothPass;
    s.smooth = makePipeline(d, smooth);

    PipelineDesc composite = smooth;
    composite.name = "screen-space liquid";
    composite.fragmentCode = code(sh::kScreenFluidFrag, sh::kScreenFluidFragWords);
    composite.blend = Blend::PremultipliedAlpha;
    composite.renderPass = r.passes.second;
    s.composite = makePipeline(d, composite);
}

// The camera's shape for the shaders (ScreenFluidPush::view) and the
// spheres' radius of the first drawn fluid (one radius per frame: a world
// rarely has two 3D fluids of different spacings).
kernels::ScreenFluidPush pushFor(const Renderer& r) {
    const CameraDef& c = r.def.camera;
    const float aspect = float(r.def.width) / float(r.def.height);
    kernels::ScreenFluidPush push{};
    if (c.orthographic) {
        push.view = glm::vec4(0.5f * c.orthoHeight * aspect, 0.5f * c.orthoHeight, 1.0f, 0.0f);
    } else {
        const float t = std::tan(0.5f * glm::radians(c.fovDegrees));
        push.view = glm::vec4(t * aspect, t, 0.0f, 0.0f);
    }
    for (const SplatFluid& f : r.fluids) {
        if (f.screen && f.particles > 0) {
            push.pass.w = kScreenSphereSpacings * f.spacing;
            break;
        }
    }
    return push;
}

void beginPass(const ScreenFluid& s, VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer,
               VkClearValue clear) {
    auto info = gpu::vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    info.renderPass = pass;
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

void drawSpheres(Renderer& r, VkCommandBuffer cmd, const Pipeline& p, const kernels::ScreenFluidPush& push) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, r.splatSet};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 2, sets, 0, nullptr);
    vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                       &push);
    for (const SplatFluid& f : r.fluids) {
        if (f.screen && f.particles > 0) {
            vkCmdDraw(cmd, 6, f.particles, 0, f.first);
        }
    }
}

void smoothPass(Renderer& r, VkCommandBuffer cmd, VkFramebuffer into, VkDescriptorSet from,
                kernels::ScreenFluidPush push, glm::vec2 step) {
    ScreenFluid& s = r.screen;
    beginPass(s, cmd, s.smoothPass, into, VkClearValue{});
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.smooth.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, from};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.smooth.layout, 0, 2, sets, 0, nullptr);
    push.pass = glm::vec4(step, kDepthFalloffRadii * push.pass.w, push.pass.w);
    vkCmdPushConstants(cmd, s.smooth.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
}

}  // namespace

void prepareScreenFluid(Renderer& r) {
    ScreenFluid& s = r.screen;
    s.drawn = false;
    for (const SplatFluid& f : r.fluids) {
        s.drawn = s.drawn || (f.screen && f.particles > 0);
    }
    if (!s.drawn) {
        return;
    }
    if (s.depthPass == VK_NULL_HANDLE) {
        createScreenFluid(r);
    }
    if (s.depth.image != VK_NULL_HANDLE && s.scale != r.def.fluid.surfaceScale) {
        vkDeviceWaitIdle(r.device->device);  // a viewer's frame in flight may still read them
        destroyImages(*r.device, s);
    }
    if (s.depth.image == VK_NULL_HANDLE) {
        createImages(r);
    }
}

void destroyScreenFluid(Renderer& r) {
    gpu::Device& d = *r.device;
    ScreenFluid& s = r.screen;
    if (s.depthPass == VK_NULL_HANDLE) {
        return;
    }
    destroyImages(d, s);
    for (Pipeline* p : {&s.spheres, &s.thicknessSpheres, &s.smooth, &s.composite}) {
        destroyPipeline(d, *p);
    }
    vkDestroyDescriptorPool(d.device, s.pool, nullptr);
    vkDestroyDescriptorSetLayout(d.device, s.layout, nullptr);
    for (VkRenderPass pass : {s.depthPass, s.thicknessPass, s.smoothPass}) {
        vkDestroyRenderPass(d.device, pass, nullptr);
    }
    s = ScreenFluid{};
}

void recordScreenFluidField(Renderer& r, VkCommandBuffer cmd) {
    ScreenFluid& s = r.screen;
    if (!s.drawn) {
        return;
    }
    kernels::ScreenFluidPush push = pushFor(r);
    {  // Step 1: the nearest sphere's view depth.
        VkClearValue clear{};
        clear.depthStencil = {1.0f, 0};
        beginPass(s, cmd, s.depthPass, s.depthFramebuffer, clear);
        drawSpheres(r, cmd, s.spheres, push);
        vkCmdEndRenderPass(cmd);
    }
    {  // Step 2: the thickness, a kernel kThicknessSpacings wide per
       // particle whose integral over the screen plane (pi R^2 / 4 for
       // (1 - q^2)^3 over radius R) is the particle's volume, spacing^3.
        beginPass(s, cmd, s.thicknessPass, s.thicknessFramebuffer, VkClearValue{});
        const float spacing = push.pass.w / kScreenSphereSpacings;
        kernels::ScreenFluidPush thickness = push;
        thickness.pass.w = kThicknessSpacings * spacing;
        thickness.pass.z = spacing * spacing * spacing /
                           (0.25f * std::numbers::pi_v<float> * thickness.pass.w * thickness.pass.w);
        drawSpheres(r, cmd, s.thicknessSpheres, thickness);
        vkCmdEndRenderPass(cmd);
    }
    // Steps 3 and 4: the depth smoothed, across then down, twice.
    VkDescriptorSet from = s.readDepth;
    for (int round = 0; round < kSmoothRounds; ++round) {
        smoothPass(r, cmd, s.framebufferA, from, push, {1.0f, 0.0f});
        smoothPass(r, cmd, s.framebufferB, s.readA, push, {0.0f, 1.0f});
        from = s.readB;
    }
}

void recordScreenFluidComposite(Renderer& r, VkCommandBuffer cmd) {
    const ScreenFluid& s = r.screen;
    if (!s.drawn) {
        return;
    }
    const kernels::ScreenFluidPush push = pushFor(r);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.composite.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, s.readB};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, s.composite.layout, 0, 2, sets, 0, nullptr);
    vkCmdPushConstants(cmd, s.composite.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
}

}  // namespace spindrift::render
