// The viewer's presentation (viewer.cpp): a GLFW window's Vulkan surface and
// swapchain on the renderer's device, the overlay pass Dear ImGui draws in,
// and the blit of the renderer's colour target into the acquired image. Kept
// apart from the viewer's session and panel, which need none of it.
#pragma once

#include "gpu/vulkan_device.h"
#include "render/render_target.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdint>
#include <vector>

namespace spindrift::app {

struct Swapchain {
    VkSwapchainKHR swapchain = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    std::uint32_t minImages = 2;
    std::vector<VkImage> images;
    std::vector<VkImageView> views;
    std::vector<VkFramebuffer> framebuffers;
    /// Per image: a semaphore may be signalled again only once the present
    /// that waited on it is done, which is known per image (its next acquire).
    std::vector<VkSemaphore> rendered;
};

/// Everything that presents on one device: surface, swapchain, the overlay
/// pass ImGui draws in, the frame's command buffer and synchronisation.
struct Presenter {
    gpu::Device* d = nullptr;
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkSurfaceFormatKHR surfaceFormat{};
    VkPresentModeKHR presentMode = VK_PRESENT_MODE_FIFO_KHR;
    VkRenderPass overlay = VK_NULL_HANDLE;
    Swapchain chain;
    VkDescriptorPool imguiPool = VK_NULL_HANDLE;
    bool imgui = false;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence done = VK_NULL_HANDLE;        // created signalled: no frame pending
    VkSemaphore acquired = VK_NULL_HANDLE;
};

/// The instance extensions a surface needs, for every device built from now on.
void requestPresentation();
/// Surface, swapchain, overlay pass, ImGui's Vulkan backend, command buffer
/// and synchronisation on `d` for `window`.
Presenter createPresenter(gpu::Device& d, GLFWwindow* window);
void destroyPresenter(Presenter& p);
/// After a resize: waits for the device, then rebuilds the swapchain at the
/// window's framebuffer size (waiting while it is minimised).
void recreateSwapchain(Presenter& p, GLFWwindow* window);
/// The largest rectangle of the frame's aspect (fw x fh) centred in the
/// window: its lower corner, or with `end` its upper one.
VkOffset3D fitted(std::uint32_t fw, std::uint32_t fh, VkExtent2D win, bool end);
/// After recordFrame: the frame blitted (scaled, letterboxed) into swapchain
/// image `index`, then ImGui's draw data over it; leaves it PRESENT_SRC.
void recordPresent(Presenter& p, const render::RenderTarget& target, std::uint32_t index);

}  // namespace spindrift::app
