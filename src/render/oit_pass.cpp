// Weighted blended OIT (see oit_pass.h): 16-bit float targets as in the
// paper (the weights are clamped to [1e-2, 3e3] for them,
// kernels::oitWeight): RGBA16F holds the weighted colour sums and, in alpha,
// the revealage; R16F the sum of the weights.
#include "render/oit_pass.h"

#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "render/render_pipelines.h"
#include "render/sprite_pass.h"

#include <spindrift/effects.h>

#include <algorithm>

namespace spindrift::render {
namespace {

constexpr VkFormat kSumsFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kWeightsFormat = VK_FORMAT_R16_SFLOAT;

VkAttachmentDescription target(VkFormat format) {
    VkAttachmentDescription a{};
    a.format = format;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    return a;
}

// Sums and weights cleared, written, left for the composite to sample;
// pass A's depth loaded, tested, kept for pass B.
VkRenderPass createAccumulationPass(gpu::Device& d) {
    VkAttachmentDescription depth{};
    depth.format = kDepthFormat;
    depth.samples = VK_SAMPLE_COUNT_1_BIT;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    depth.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.initialLayout = kDepthReadLayout;
    depth.finalLayout = kDepthReadLayout;
    VkAttachmentDescription attachments[3] = {target(kSumsFormat), target(kWeightsFormat), depth};
    VkAttachmentReference colourRefs[2] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                           {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
    VkAttachmentReference depthRef{2, kDepthReadLayout};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 2;
    subpass.pColorAttachments = colourRefs;
    subpass.pDepthStencilAttachment = &depthRef;
    const VkPipelineStageFlags tests =
        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    // Before: pass A's depth writes, and the previous frame's composite
    // reading the targets this pass clears. After: the composite reads
    // them, pass B tests and samples the depth.
    VkSubpassDependency dependencies[2] = {};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = tests | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstStageMask =
        tests | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_SHADER_READ_BIT |
                                    VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | tests;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | tests;
    dependencies[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    auto info = gpu::vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = 3;
    info.pAttachments = attachments;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = dependencies;
    VkRenderPass pass = VK_NULL_HANDLE;
    gpu::check(vkCreateRenderPass(d.device, &info, nullptr, &pass), "vkCreateRenderPass");
    return pass;
}

void createTargets(Renderer& r) {
    gpu::Device& d = *r.device;
    OitTargets& o = r.oit;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    o.sums = gpu::createSampledImage(
        d, {VK_IMAGE_VIEW_TYPE_2D, kSumsFormat, r.target.width, r.target.height, 1, usage, VK_IMAGE_ASPECT_COLOR_BIT});
    o.weights = gpu::createSampledImage(d, {VK_IMAGE_VIEW_TYPE_2D, kWeightsFormat, r.target.width,
                                              r.target.height, 1, usage, VK_IMAGE_ASPECT_COLOR_BIT});
    o.pass = createAccumulationPass(d);
    VkImageView views[3] = {o.sums.view, o.weights.view, r.target.depth.view};
    auto info = gpu::vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
    info.renderPass = o.pass;
    info.attachmentCount = 3;
    info.pAttachments = views;
    info.width = r.target.width;
    info.height = r.target.height;
    info.layers = 1;
    gpu::check(vkCreateFramebuffer(d.device, &info, nullptr, &o.framebuffer), "vkCreateFramebuffer");
}

void createCompositeSet(Renderer& r) {
    gpu::Device& d = *r.device;
    OitTargets& o = r.oit;
    const VkDescriptorType types[kernels::SD_OIT_BINDINGS] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                              VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    o.layout = createSetLayout(d, types);
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kernels::SD_OIT_BINDINGS};
    auto pool = gpu::vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    pool.maxSets = 1;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &size;
    gpu::check(vkCreateDescriptorPool(d.device, &pool, nullptr, &o.pool), "vkCreateDescriptorPool");
    auto alloc = gpu::vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = o.pool;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &o.layout;
    gpu::check(vkAllocateDescriptorSets(d.device, &alloc, &o.set), "vkAllocateDescriptorSets");
    VkDescriptorImageInfo images[kernels::SD_OIT_BINDINGS];
    images[kernels::SD_OIT_BINDING_ACCUM] = {r.nearestSampler, o.sums.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    images[kernels::SD_OIT_BINDING_WEIGHTS] = {r.nearestSampler, o.weights.view,
                                              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet writes[kernels::SD_OIT_BINDINGS];
    for (std::uint32_t i = 0; i < kernels::SD_OIT_BINDINGS; ++i) {
        writes[i] = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[i].dstSet = o.set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[i].pImageInfo = &images[i];
    }
    vkUpdateDescriptorSets(d.device, kernels::SD_OIT_BINDINGS, writes, 0, nullptr);
}

void createPipelines(Renderer& r) {
    namespace s = gpu::shaders;
    gpu::Device& d = *r.device;
    PipelineDesc accumulate;
    accumulate.name = "OIT accumulation";
    accumulate.vertexCode = {s::kSpritesVert, s::kSpritesVertWords};
    accumulate.fragmentCode = {s::kSpritesOitFrag, s::kSpritesOitFragWords};
    accumulate.setLayouts = {r.frameLayout, r.spriteLayout};
    accumulate.pushConstantBytes = sizeof(kernels::SpriteDraw);
    accumulate.blend = Blend::WeightedOit;
    accumulate.depthTest = true;
    accumulate.renderPass = r.oit.pass;
    r.oit.accumulate = makePipeline(d, accumulate);

    PipelineDesc composite;
    composite.name = "OIT composite";
    composite.vertexCode = {s::kOitCompositeVert, s::kOitCompositeVertWords};
    composite.fragmentCode = {s::kOitCompositeFrag, s::kOitCompositeFragWords};
    composite.setLayouts = {r.frameLayout, r.oit.layout};
    composite.blend = Blend::PremultipliedAlpha;
    composite.renderPass = r.passes.second;
    r.oit.composite = makePipeline(d, composite);
}

}  // namespace

void createOit(Renderer& r) {
    const bool used = std::any_of(r.emitters.begin(), r.emitters.end(),
                                  [](const SpriteEmitter& s) { return s.blend == SpriteBlend::WeightedOit; });
    if (!used) {
        return;
    }
    createTargets(r);
    createCompositeSet(r);
    createPipelines(r);
}

void destroyOit(Renderer& r) {
    OitTargets& o = r.oit;
    if (o.pass == VK_NULL_HANDLE) {
        return;
    }
    gpu::Device& d = *r.device;
    for (Pipeline* p : {&o.accumulate, &o.composite}) {
        destroyPipeline(d, *p);
    }
    vkDestroyDescriptorPool(d.device, o.pool, nullptr);
    vkDestroyDescriptorSetLayout(d.device, o.layout, nullptr);
    vkDestroyFramebuffer(d.device, o.framebuffer, nullptr);
    vkDestroyRenderPass(d.device, o.pass, nullptr);
    for (gpu::Image* i : {&o.sums, &o.weights}) {
        if (i->image != VK_NULL_HANDLE) {
            gpu::destroyImage(d, *i);
        }
    }
    o = OitTargets{};
}

void recordOitAccumulation(Renderer& r, VkCommandBuffer cmd) {
    if (r.oit.pass == VK_NULL_HANDLE) {
        return;
    }
    // Sums 0, revealage (alpha of target 0) 1: nothing covers yet.
    VkClearValue clear[3] = {};
    clear[0].color = {{0.0f, 0.0f, 0.0f, 1.0f}};
    auto info = gpu::vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    info.renderPass = r.oit.pass;
    info.framebuffer = r.oit.framebuffer;
    info.renderArea = {{0, 0}, {r.target.width, r.target.height}};
    info.clearValueCount = 3;
    info.pClearValues = clear;
    vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport viewport{0.0f, 0.0f, float(r.target.width), float(r.target.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {r.target.width, r.target.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    recordSpriteGroup(r, cmd, r.oit.accumulate, r.oit.accumulate, SpriteBlend::WeightedOit);
    vkCmdEndRenderPass(cmd);
}

void recordOitComposite(Renderer& r, VkCommandBuffer cmd) {
    if (r.oit.pass == VK_NULL_HANDLE) {
        return;
    }
    const Pipeline& p = r.oit.composite;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, r.oit.set};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 2, sets, 0, nullptr);
    vkCmdDraw(cmd, 3, 1, 0, 0);
}

}  // namespace spindrift::render
