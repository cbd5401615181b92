// Bloom and the tone map (see light_pass.h and docs/rendering.md, "Light").
#include "render/light_pass.h"

#include "gpu/shaders.h"
#include "render/render_pipelines.h"

#include <algorithm>

namespace spindrift::render {
namespace {

static_assert(static_cast<std::uint32_t>(ToneMap::None) == kernels::SD_TONE_MAP_NONE);
static_assert(static_cast<std::uint32_t>(ToneMap::Aces) == kernels::SD_TONE_MAP_ACES);
static_assert(kernels::SD_LIGHT_SET == 1u && kernels::SD_LIGHT_BINDING_SOURCE == 0u &&
              kernels::SD_LIGHT_BINDING_BLOOM == 1u && kernels::SD_LIGHT_BINDINGS == 2u);

template <class T>
std::span<const std::uint32_t> code(const T* words, std::size_t count) {
    return {words, count};
}

// One colour attachment of a bloom level, left ready to be sampled
// (render_target.h): `add` loads it (the upsample adds onto the level),
// otherwise every texel is overwritten.
VkRenderPass createLevelPass(gpu::Device& d, bool add) {
    return createSampledColourPass(d, kHdrFormat, add ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_DONT_CARE,
                                   "bloom");
}

void writeSet(Renderer& r, VkDescriptorSet set, VkImageView source, VkImageView bloom) {
    VkDescriptorImageInfo images[2] = {{r.linearSampler, source, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                       {r.linearSampler, bloom, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
    VkWriteDescriptorSet writes[2];
    for (std::uint32_t i = 0; i < 2; ++i) {
        writes[i] = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[i].dstSet = set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        writes[i].pImageInfo = &images[i];
    }
    vkUpdateDescriptorSets(r.device->device, 2, writes, 0, nullptr);
}

// One full-screen triangle of `pipeline` reading `set` into `framebuffer`.
void fullScreenPass(Renderer& r, VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer, glm::uvec2 size,
                    const Pipeline& pipeline, VkDescriptorSet set, glm::vec4 values) {
    auto info = gpu::vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    info.renderPass = pass;
    info.framebuffer = framebuffer;
    info.renderArea = {{0, 0}, {size.x, size.y}};
    vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport viewport{0.0f, 0.0f, float(size.x), float(size.y), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {size.x, size.y}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, set};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline.layout, 0, 2, sets, 0, nullptr);
    const kernels::LightPush push{values};
    vkCmdPushConstants(cmd, pipeline.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                       sizeof(push), &push);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
}

}  // namespace

void createLight(Renderer& r) {
    namespace sh = gpu::shaders;
    gpu::Device& d = *r.device;
    Light& l = r.light;
    const VkDescriptorType types[kernels::SD_LIGHT_BINDINGS] = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                                                VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER};
    l.layout = createSetLayout(d, types);
    const bool bloom = r.def.bloom > 0.0f;
    // Sets: the tone map's, and with bloom the threshold's and one per level.
    const std::uint32_t sets = bloom ? 2u + kBloomLevels : 1u;
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * sets};
    auto poolInfo = gpu::vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = sets;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    gpu::check(vkCreateDescriptorPool(d.device, &poolInfo, nullptr, &l.pool), "vkCreateDescriptorPool (light)");
    std::vector<VkDescriptorSetLayout> layouts(sets, l.layout);
    std::vector<VkDescriptorSet> allocated(sets);
    auto alloc = gpu::vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = l.pool;
    alloc.descriptorSetCount = sets;
    alloc.pSetLayouts = layouts.data();
    gpu::check(vkAllocateDescriptorSets(d.device, &alloc, allocated.data()), "vkAllocateDescriptorSets (light)");
    l.toneMapSet = allocated[0];

    PipelineDesc toneMap;
    toneMap.name = "tone map";
    toneMap.vertexCode = code(sh::kBackgroundVert, sh::kBackgroundVertWords);
    toneMap.fragmentCode = code(sh::kToneMapFrag, sh::kToneMapFragWords);
    toneMap.setLayouts = {r.frameLayout, l.layout};
    toneMap.pushConstantBytes = sizeof(kernels::LightPush);
    toneMap.renderPass = r.passes.toneMap;
    l.toneMap = makePipeline(d, toneMap);

    // Unused bindings read the placeholder (never a level being written).
    const VkImageView placeholder = r.placeholderImage.view;
    if (!bloom) {
        writeSet(r, l.toneMapSet, r.target.hdr.view, placeholder);
        return;
    }
    l.down = createLevelPass(d, false);
    l.up = createLevelPass(d, true);
    glm::uvec2 levelSize{(r.def.width + kernels::SD_BLOOM_DIVISOR - 1) / kernels::SD_BLOOM_DIVISOR,
                         (r.def.height + kernels::SD_BLOOM_DIVISOR - 1) / kernels::SD_BLOOM_DIVISOR};
    for (std::uint32_t i = 0; i < kBloomLevels; ++i) {
        l.sizes[i] = glm::max(levelSize, glm::uvec2(1));
        gpu::ImageShape shape{VK_IMAGE_VIEW_TYPE_2D, kHdrFormat, l.sizes[i].x, l.sizes[i].y, 1,
                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                              VK_IMAGE_ASPECT_COLOR_BIT};
        l.levels[i] = gpu::createSampledImage(d, shape);
        // One framebuffer serves both passes: they are compatible (same
        // format and samples; load operations and layouts do not count).
        l.framebuffers[i] = createSingleFramebuffer(d, l.down, l.levels[i], l.sizes[i].x, l.sizes[i].y, "bloom");
        l.levelSets[i] = allocated[2 + i];
        writeSet(r, l.levelSets[i], l.levels[i].view, placeholder);
        levelSize = (l.sizes[i] + 1u) / 2u;
    }
    l.thresholdSet = allocated[1];
    writeSet(r, l.thresholdSet, r.target.hdr.view, placeholder);
    writeSet(r, l.toneMapSet, r.target.hdr.view, l.levels[0].view);

    PipelineDesc threshold = toneMap;
    threshold.name = "bloom threshold";
    threshold.fragmentCode = code(sh::kBloomThresholdFrag, sh::kBloomThresholdFragWords);
    threshold.renderPass = l.down;
    l.threshold = makePipeline(d, threshold);
    PipelineDesc blur = threshold;
    blur.name = "bloom down";
    blur.fragmentCode = code(sh::kBloomBlurFrag, sh::kBloomBlurFragWords);
    l.blurDown = makePipeline(d, blur);
    blur.name = "bloom up";
    blur.blend = Blend::Additive;
    blur.renderPass = l.up;
    l.blurUp = makePipeline(d, blur);
}

void destroyLight(Renderer& r) {
    gpu::Device& d = *r.device;
    Light& l = r.light;
    for (Pipeline* p : {&l.threshold, &l.blurDown, &l.blurUp, &l.toneMap}) {
        destroyPipeline(d, *p);
    }
    for (std::uint32_t i = 0; i < kBloomLevels; ++i) {
        vkDestroyFramebuffer(d.device, l.framebuffers[i], nullptr);
        if (l.levels[i].image != VK_NULL_HANDLE) {
            gpu::destroyImage(d, l.levels[i]);
        }
    }
    vkDestroyRenderPass(d.device, l.down, nullptr);
    vkDestroyRenderPass(d.device, l.up, nullptr);
    vkDestroyDescriptorPool(d.device, l.pool, nullptr);
    vkDestroyDescriptorSetLayout(d.device, l.layout, nullptr);
    l = Light{};
}

void recordLight(Renderer& r, VkCommandBuffer cmd) {
    Light& l = r.light;
    // The float frame, finished by the last render pass, is read from here on.
    imageBarrier(cmd, r.target.hdr.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_SHADER_READ_BIT);
    const bool bloom = l.down != VK_NULL_HANDLE;
    if (bloom) {
        fullScreenPass(r, cmd, l.down, l.framebuffers[0], l.sizes[0], l.threshold, l.thresholdSet,
                       glm::vec4(glm::vec2(l.sizes[0]), 0.0f, 0.0f));
        // Down: each level from the one above, offsets of one finer texel.
        for (std::uint32_t i = 1; i < kBloomLevels; ++i) {
            const glm::vec2 texel = 1.0f / glm::vec2(l.sizes[i - 1]);
            fullScreenPass(r, cmd, l.down, l.framebuffers[i], l.sizes[i], l.blurDown, l.levelSets[i - 1],
                           glm::vec4(texel, 0.0f, 0.0f));
        }
        // Up: each level adds the (already summed) one below it, offsets of
        // half a coarser texel; level 0 ends as the sum of every level.
        for (std::uint32_t i = kBloomLevels - 1; i-- > 0;) {
            const glm::vec2 half = 0.5f / glm::vec2(l.sizes[i + 1]);
            fullScreenPass(r, cmd, l.up, l.framebuffers[i], l.sizes[i], l.blurUp, l.levelSets[i + 1],
                           glm::vec4(half, 0.0f, 0.0f));
        }
    }
    // Level 0 holds the sum of kBloomLevels blurred copies of the light above
    // the threshold: their mean, times the strength, is added.
    const float weight = bloom ? r.def.bloom / float(kBloomLevels) : 0.0f;
    fullScreenPass(r, cmd, r.passes.toneMap, r.target.framebufferToneMap, {r.target.width, r.target.height},
                   l.toneMap, l.toneMapSet,
                   glm::vec4(r.def.exposure, weight, float(static_cast<std::uint32_t>(r.def.toneMap)), 0.0f));
}

}  // namespace spindrift::render
