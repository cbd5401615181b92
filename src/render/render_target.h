// The renderer's targets and passes (render_target.cpp).
#pragma once

#include "gpu/vulkan_buffer.h"

#include <spindrift/render.h>

namespace spindrift::render {

/// sRGB colour: blending happens in linear light, the read-back bytes are
/// sRGB-encoded as a PNG expects. 32-bit float depth.
inline constexpr VkFormat kColourFormat = VK_FORMAT_R8G8B8A8_SRGB;
inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
/// Depth after pass A: tested (never written) by pass B and the OIT
/// accumulation, and sampled by soft particles.
inline constexpr VkImageLayout kDepthReadLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;

struct RenderPasses {
    VkRenderPass first = VK_NULL_HANDLE;   // clears: background, colliders
    VkRenderPass second = VK_NULL_HANDLE;  // loads: fluid splats, sprites
};

/// Colour and depth targets, the copy of the colour between the passes (what
/// refraction sees behind the water), and the host-visible read-back buffer.
struct RenderTarget {
    std::uint32_t width = 0, height = 0;
    gpu::Image colour, depth, behind;
    VkFramebuffer framebufferA = VK_NULL_HANDLE, framebufferB = VK_NULL_HANDLE;
    gpu::Buffer readback;
};

/// Throws Error where the device cannot render to the formats above.
RenderPasses createRenderPasses(gpu::Device& d);
void destroyRenderPasses(gpu::Device& d, RenderPasses& p);
RenderTarget createRenderTarget(gpu::Device& d, const RenderPasses& passes, std::uint32_t width, std::uint32_t height);
void destroyRenderTarget(gpu::Device& d, RenderTarget& t);

/// Layout transition of a single-layer colour image.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                  VkAccessFlags dstAccess);
/// Copies the colour target (TRANSFER_SRC_OPTIMAL) into `behind`.
void recordCopyBehind(VkCommandBuffer cmd, const RenderTarget& t);
/// Copies the colour target into the read-back buffer, visible to the host.
void recordReadback(VkCommandBuffer cmd, const RenderTarget& t);
/// The read-back buffer's pixels (after the frame's fence).
Frame readFrame(const RenderTarget& t);

}  // namespace spindrift::render
