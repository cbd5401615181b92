// The renderer's float colour and depth targets, the sRGB image the tone map
// writes, their render passes and the read-back of a finished frame.
#include "render/render_target.h"

#include <spindrift/effects.h>

#include <cstring>
#include <string>

namespace spindrift::render {
namespace {

// A render pass of one attachment, one subpass and two dependencies (in and
// out); throws Error naming `what`.
VkRenderPass createOneAttachmentPass(gpu::Device& d, const VkAttachmentDescription& a,
                                     const VkSubpassDescription& subpass, const VkSubpassDependency (&dependencies)[2],
                                     const char* what) {
    auto info = gpu::vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = 1;
    info.pAttachments = &a;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = dependencies;
    VkRenderPass pass = VK_NULL_HANDLE;
    const std::string call = std::string("vkCreateRenderPass (") + what + ")";
    gpu::check(vkCreateRenderPass(d.device, &info, nullptr, &pass), call.c_str());
    return pass;
}

VkAttachmentDescription attachment(VkFormat format, bool clear, VkImageLayout initial, VkImageLayout final,
                                   bool store) {
    VkAttachmentDescription a{};
    a.format = format;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = initial;
    a.finalLayout = final;
    return a;
}

// Pass A clears and leaves colour ready to be copied and depth read-only for
// pass B; pass B loads both and leaves colour ready to be copied (read-back
// or the viewer's blit). Nothing in pass B writes depth, so there it is
// read-only both as the attachment and as the sampled image soft particles
// read (a read-only layout may be both at once; Vulkan spec, "Render Pass",
// attachment and descriptor in the same subpass).
VkRenderPass createPass(gpu::Device& d, bool first) {
    VkAttachmentDescription attachments[2] = {
        attachment(kHdrFormat, first, first ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, true),
        attachment(kDepthFormat, first, first ? VK_IMAGE_LAYOUT_UNDEFINED : kDepthReadLayout, kDepthReadLayout,
                   first)};
    VkAttachmentReference colourRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference depthRef{1, first ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : kDepthReadLayout};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &colourRef;
    subpass.pDepthStencilAttachment = &depthRef;
    const VkPipelineStageFlags attachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                  VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                  VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    const VkAccessFlags attachmentAccess = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                                           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                           VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    // Before: the previous frame's (or pass A's) copies out of the colour
    // target, its depth writes, and the previous frame's light passes reading
    // it. After: copies out of it, pass B's tests.
    VkSubpassDependency dependencies[2] = {};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | attachmentStages;
    dependencies[0].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT | attachmentAccess;
    dependencies[0].dstStageMask = attachmentStages | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[0].dstAccessMask = attachmentAccess | VK_ACCESS_SHADER_READ_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = attachmentStages;
    dependencies[1].srcAccessMask = attachmentAccess;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | attachmentStages | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | attachmentAccess | VK_ACCESS_SHADER_READ_BIT;
    auto info = gpu::vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = 2;
    info.pAttachments = attachments;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = dependencies;
    VkRenderPass pass = VK_NULL_HANDLE;
    gpu::check(vkCreateRenderPass(d.device, &info, nullptr, &pass), "vkCreateRenderPass");
    return pass;
}

// The tone map's pass: every pixel of the sRGB image written (nothing
// loaded), left ready to be copied (read-back or the viewer's blit). Before:
// the previous frame's copy out of it; the float frame and the bloom are
// made readable by their own barrier and passes. After: the copy.
VkRenderPass createToneMapPass(gpu::Device& d) {
    VkAttachmentDescription colour = attachment(kColourFormat, false, VK_IMAGE_LAYOUT_UNDEFINED,
                                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, true);
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency dependencies[2] = {};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    return createOneAttachmentPass(d, colour, subpass, dependencies, "tone map");
}

VkFramebuffer createFramebuffer(gpu::Device& d, VkRenderPass pass, const RenderTarget& t, bool toneMap) {
    VkImageView views[2] = {t.hdr.view, t.depth.view};
    if (toneMap) {
        views[0] = t.colour.view;
    }
    auto info = gpu::vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
    info.renderPass = pass;
    info.attachmentCount = toneMap ? 1u : 2u;
    info.pAttachments = views;
    info.width = t.width;
    info.height = t.height;
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    gpu::check(vkCreateFramebuffer(d.device, &info, nullptr, &fb), "vkCreateFramebuffer");
    return fb;
}

bool supports(const gpu::Device& d, VkFormat format, VkFormatFeatureFlags needed) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(d.physical, format, &props);
    return (props.optimalTilingFeatures & needed) == needed;
}

}  // namespace

RenderPasses createRenderPasses(gpu::Device& d) {
    if (!supports(d, kHdrFormat,
                  VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) ||
        !supports(d, kColourFormat, VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) ||
        !supports(d, kDepthFormat, VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT)) {
        throw Error("render: the Vulkan device cannot blend into and filter R16G16B16A16_SFLOAT, draw into "
                    "R8G8B8A8_SRGB or has no sampled D32_SFLOAT depth");
    }
    RenderPasses p;
    p.first = createPass(d, true);
    p.second = createPass(d, false);
    p.toneMap = createToneMapPass(d);
    return p;
}

RenderTarget createRenderTarget(gpu::Device& d, const RenderPasses& passes, std::uint32_t width,
                                std::uint32_t height) {
    RenderTarget t;
    t.width = width;
    t.height = height;
    gpu::ImageShape hdr{VK_IMAGE_VIEW_TYPE_2D, kHdrFormat, width, height, 1,
                        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                            VK_IMAGE_USAGE_SAMPLED_BIT,
                        VK_IMAGE_ASPECT_COLOR_BIT};
    t.hdr = gpu::createSampledImage(d, hdr);
    gpu::ImageShape colour{VK_IMAGE_VIEW_TYPE_2D, kColourFormat, width, height, 1,
                           VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                           VK_IMAGE_ASPECT_COLOR_BIT};
    t.colour = gpu::createSampledImage(d, colour);
    gpu::ImageShape depth{VK_IMAGE_VIEW_TYPE_2D, kDepthFormat, width, height, 1,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                          VK_IMAGE_ASPECT_DEPTH_BIT};
    t.depth = gpu::createSampledImage(d, depth);
    gpu::ImageShape behind{VK_IMAGE_VIEW_TYPE_2D, kHdrFormat, width, height, 1,
                           VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT};
    t.behind = gpu::createSampledImage(d, behind);
    t.framebufferA = createFramebuffer(d, passes.first, t, false);
    t.framebufferB = createFramebuffer(d, passes.second, t, false);
    t.framebufferToneMap = createFramebuffer(d, passes.toneMap, t, true);
    t.readback = gpu::createBuffer(d, VkDeviceSize{width} * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    // `behind` is sampled by pass B: give it a defined layout once (after
    // that every frame copies into it and returns it to this layout).
    gpu::submitOnce(d, [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, t.behind.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_SHADER_READ_BIT);
    });
    return t;
}

void destroyRenderTarget(gpu::Device& d, RenderTarget& t) {
    vkDestroyFramebuffer(d.device, t.framebufferA, nullptr);
    vkDestroyFramebuffer(d.device, t.framebufferB, nullptr);
    vkDestroyFramebuffer(d.device, t.framebufferToneMap, nullptr);
    gpu::destroyImage(d, t.hdr);
    gpu::destroyImage(d, t.colour);
    gpu::destroyImage(d, t.depth);
    gpu::destroyImage(d, t.behind);
    gpu::destroyBuffer(d, t.readback);
    t = RenderTarget{};
}

void destroyRenderPasses(gpu::Device& d, RenderPasses& p) {
    vkDestroyRenderPass(d.device, p.first, nullptr);
    vkDestroyRenderPass(d.device, p.second, nullptr);
    vkDestroyRenderPass(d.device, p.toneMap, nullptr);
    p = RenderPasses{};
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess) {
    gpu::imageBarrier(cmd, image, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}, from, to, srcStage, srcAccess, dstStage,
                      dstAccess);
}

void recordCopyBehind(VkCommandBuffer cmd, const RenderTarget& t) {
    imageBarrier(cmd, t.behind.image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageCopy region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.extent = {t.width, t.height, 1};
    vkCmdCopyImage(cmd, t.hdr.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.behind.image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    imageBarrier(cmd, t.behind.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_SHADER_READ_BIT);
}

void recordReadback(VkCommandBuffer cmd, const RenderTarget& t) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {t.width, t.height, 1};
    vkCmdCopyImageToBuffer(cmd, t.colour.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.readback.buffer, 1, &region);
    auto b = gpu::vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &b, 0, nullptr, 0,
                         nullptr);
}

Frame readFrame(const RenderTarget& t) {
    Frame f;
    f.width = t.width;
    f.height = t.height;
    f.rgba.resize(std::size_t{t.width} * t.height * 4);
    std::memcpy(f.rgba.data(), t.readback.mapped, f.rgba.size());
    return f;
}

// Before: earlier passes that read or wrote the image; after: fragment
// shaders read it.
VkRenderPass createSampledColourPass(gpu::Device& d, VkFormat format, VkAttachmentLoadOp loadOp, const char* what) {
    VkAttachmentDescription a{};
    a.format = format;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = loadOp;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout =
        loadOp == VK_ATTACHMENT_LOAD_OP_LOAD ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency dependencies[2] = {};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    return createOneAttachmentPass(d, a, subpass, dependencies, what);
}

VkRenderPass createSampledDepthPass(gpu::Device& d, const char* what) {
    VkAttachmentDescription a{};
    a.format = kDepthFormat;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    a.finalLayout = kDepthReadLayout;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.pDepthStencilAttachment = &ref;
    VkSubpassDependency dependencies[2] = {};
    // The last frame's reads of the image finish before it is cleared ...
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[0].srcAccessMask = 0;
    dependencies[0].dstStageMask =
        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].dstAccessMask =
        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    // ... and this frame's depths are written before they are sampled.
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask =
        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
    return createOneAttachmentPass(d, a, subpass, dependencies, what);
}

VkFramebuffer createSingleFramebuffer(gpu::Device& d, VkRenderPass pass, const gpu::Image& image,
                                      std::uint32_t width, std::uint32_t height, const char* what) {
    auto info = gpu::vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
    info.renderPass = pass;
    info.attachmentCount = 1;
    info.pAttachments = &image.view;
    info.width = width;
    info.height = height;
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    const std::string call = std::string("vkCreateFramebuffer (") + what + ")";
    gpu::check(vkCreateFramebuffer(d.device, &info, nullptr, &fb), call.c_str());
    return fb;
}

}  // namespace spindrift::render
