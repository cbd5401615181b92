// The renderer's targets and passes (render_target.cpp).
#pragma once

#include "gpu/vulkan_buffer.h"

#include <spindrift/render.h>

namespace spindrift::render {

/// The frame is drawn in linear light into 16-bit floats (light above 1
/// keeps its energy for bloom and the tone map; R16G16B16A16_SFLOAT blends
/// and filters on every Vulkan device, the spec's required format features),
/// then the tone map writes the sRGB image that is read back and presented:
/// its bytes are sRGB-encoded as a PNG expects. 32-bit float depth.
inline constexpr VkFormat kHdrFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kColourFormat = VK_FORMAT_R8G8B8A8_SRGB;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
/// Depth after pass A: tested (never written) by pass B and the OIT
/// accumulation, and sampled by soft particles.
inline constexpr VkImageLayout kDepthReadLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;

struct RenderPasses {
    VkRenderPass first = VK_NULL_HANDLE;    // clears: background, colliders (float target)
    VkRenderPass second = VK_NULL_HANDLE;   // loads: fluid splats, sprites (float target)
    VkRenderPass toneMap = VK_NULL_HANDLE;  // writes the sRGB image from the float target
};

/// The float colour and depth targets, the copy of the float colour between
/// the passes (what refraction sees behind the water), the tone-mapped sRGB
/// image (`colour`, left in TRANSFER_SRC_OPTIMAL: read back or presented),
/// and the host-visible read-back buffer.
struct RenderTarget {
    std::uint32_t width = 0, height = 0;
    gpu::Image hdr, colour, depth, behind;
    VkFramebuffer framebufferA = VK_NULL_HANDLE, framebufferB = VK_NULL_HANDLE;
    VkFramebuffer framebufferToneMap = VK_NULL_HANDLE;
    gpu::Buffer readback;
};

/// Throws Error where the device cannot render to the formats above.
/// One colour attachment of `format` that fragment shaders draw and then
/// sample (the liquid surface's field passes, the bloom levels): loadOp
/// LOAD expects the image ready to be sampled and keeps it, CLEAR and
/// DONT_CARE overwrite it. `what` names the pass in errors.
VkRenderPass createSampledColourPass(gpu::Device& d, VkFormat format, VkAttachmentLoadOp loadOp, const char* what);
/// One depth attachment (kDepthFormat), cleared to 1 and left in
/// kDepthReadLayout for fragment shaders to sample (the screen-space liquid's
/// sphere depths).
VkRenderPass createSampledDepthPass(gpu::Device& d, const char* what);
/// A framebuffer of the single attachment `image` for `pass`.
VkFramebuffer createSingleFramebuffer(gpu::Device& d, VkRenderPass pass, const gpu::Image& image,
                                      std::uint32_t width, std::uint32_t height, const char* what);
RenderPasses createRenderPasses(gpu::Device& d);
void destroyRenderPasses(gpu::Device& d, RenderPasses& p);
RenderTarget createRenderTarget(gpu::Device& d, const RenderPasses& passes, std::uint32_t width, std::uint32_t height);
void destroyRenderTarget(gpu::Device& d, RenderTarget& t);

/// Layout transition of a single-layer colour image.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess);
/// Copies the float colour target (TRANSFER_SRC_OPTIMAL) into `behind`.
void recordCopyBehind(VkCommandBuffer cmd, const RenderTarget& t);
/// Copies the sRGB image into the read-back buffer, visible to the host.
void recordReadback(VkCommandBuffer cmd, const RenderTarget& t);
/// The read-back buffer's pixels (after the frame's fence).
Frame readFrame(const RenderTarget& t);

}  // namespace spindrift::render
