// The viewer's presentation: see presenter.h.
#include "presenter.h"

#include "gpu/device_settings.h"

#include <spindrift/world.h>

#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace spindrift::app {
namespace {

using gpu::check;
using gpu::vkStruct;

VkSurfaceFormatKHR chooseFormat(const gpu::Device& d, VkSurfaceKHR surface) {
    std::uint32_t n = 0;
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(d.physical, surface, &n, nullptr), "vkGetPhysicalDeviceSurfaceFormatsKHR");
    std::vector<VkSurfaceFormatKHR> formats(n);
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(d.physical, surface, &n, formats.data()),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
    auto blittable = [&](VkFormat f) {
        VkFormatProperties p{};
        vkGetPhysicalDeviceFormatProperties(d.physical, f, &p);
        return (p.optimalTilingFeatures & VK_FORMAT_FEATURE_BLIT_DST_BIT) != 0;
    };
    // sRGB first: the blit then keeps the renderer's sRGB bytes as they are
    // (decode and re-encode), like the PNGs of `spindrift render`.
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_SRGB}) {
        for (const VkSurfaceFormatKHR& f : formats) {
            if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR && blittable(f.format)) return f;
        }
    }
    for (const VkSurfaceFormatKHR& f : formats) {
        if (blittable(f.format)) return f;
    }
    throw Error("view: no surface format the renderer's frame can be blitted to");
}

VkPresentModeKHR choosePresentMode(const gpu::Device& d, VkSurfaceKHR surface) {
    std::uint32_t n = 0;
    check(vkGetPhysicalDeviceSurfacePresentModesKHR(d.physical, surface, &n, nullptr),
          "vkGetPhysicalDeviceSurfacePresentModesKHR");
    std::vector<VkPresentModeKHR> modes(n);
    check(vkGetPhysicalDeviceSurfacePresentModesKHR(d.physical, surface, &n, modes.data()),
          "vkGetPhysicalDeviceSurfacePresentModesKHR");
    // Mailbox: no tearing and never blocks on a display that may have no
    // vblank (Xvfb); FIFO is the one mode every driver has.
    return std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end()
               ? VK_PRESENT_MODE_MAILBOX_KHR
               : VK_PRESENT_MODE_FIFO_KHR;
}

/// The pass ImGui draws in: it loads the blitted frame and hands the image to
/// the presentation engine.
VkRenderPass createOverlayPass(const gpu::Device& d, VkFormat format) {
    VkAttachmentDescription colour{};
    colour.format = format;
    colour.samples = VK_SAMPLE_COUNT_1_BIT;
    colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    colour.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colour.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    auto info = vkStruct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = 1;
    info.pAttachments = &colour;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &dep;
    VkRenderPass pass = VK_NULL_HANDLE;
    check(vkCreateRenderPass(d.device, &info, nullptr, &pass), "vkCreateRenderPass");
    return pass;
}

void destroyChainViews(const gpu::Device& d, Swapchain& c) {
    for (VkFramebuffer f : c.framebuffers) vkDestroyFramebuffer(d.device, f, nullptr);
    for (VkImageView v : c.views) vkDestroyImageView(d.device, v, nullptr);
    for (VkSemaphore s : c.rendered) vkDestroySemaphore(d.device, s, nullptr);
    c.framebuffers.clear();
    c.views.clear();
    c.rendered.clear();
    c.images.clear();
}

/// (Re)creates the swapchain at the window's framebuffer size, retiring the
/// old one. The caller has waited for the device to be idle.
void createSwapchain(Presenter& p, GLFWwindow* window) {
    gpu::Device& d = *p.d;
    VkSurfaceCapabilitiesKHR caps{};
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(d.physical, p.surface, &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    if ((caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) == 0) {
        throw Error("view: the swapchain's images cannot be blitted to (no TRANSFER_DST usage)");
    }
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == 0xFFFFFFFFu) {  // the surface takes the swapchain's size
        int w = 0, h = 0;
        glfwGetFramebufferSize(window, &w, &h);
        extent.width = std::clamp(std::uint32_t(w), caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(std::uint32_t(h), caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    std::uint32_t images = std::max(caps.minImageCount + 1, 2u);
    if (caps.maxImageCount > 0) images = std::min(images, caps.maxImageCount);

    Swapchain old = std::move(p.chain);
    destroyChainViews(d, old);
    p.chain = Swapchain{};
    Swapchain& c = p.chain;
    c.format = p.surfaceFormat.format;
    c.extent = extent;
    c.minImages = std::max(images, 2u);
    auto info = vkStruct<VkSwapchainCreateInfoKHR>(VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR);
    info.surface = p.surface;
    info.minImageCount = images;
    info.imageFormat = p.surfaceFormat.format;
    info.imageColorSpace = p.surfaceFormat.colorSpace;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR) != 0
                              ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                              : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
    info.presentMode = p.presentMode;
    info.clipped = VK_TRUE;
    info.oldSwapchain = old.swapchain;
    check(vkCreateSwapchainKHR(d.device, &info, nullptr, &c.swapchain), "vkCreateSwapchainKHR");
    vkDestroySwapchainKHR(d.device, old.swapchain, nullptr);

    std::uint32_t n = 0;
    check(vkGetSwapchainImagesKHR(d.device, c.swapchain, &n, nullptr), "vkGetSwapchainImagesKHR");
    c.images.resize(n);
    check(vkGetSwapchainImagesKHR(d.device, c.swapchain, &n, c.images.data()), "vkGetSwapchainImagesKHR");
    for (VkImage image : c.images) {
        auto view = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        view.image = image;
        view.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view.format = c.format;
        view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        c.views.push_back(VK_NULL_HANDLE);
        check(vkCreateImageView(d.device, &view, nullptr, &c.views.back()), "vkCreateImageView");
        auto fb = vkStruct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        fb.renderPass = p.overlay;
        fb.attachmentCount = 1;
        fb.pAttachments = &c.views.back();
        fb.width = extent.width;
        fb.height = extent.height;
        fb.layers = 1;
        c.framebuffers.push_back(VK_NULL_HANDLE);
        check(vkCreateFramebuffer(d.device, &fb, nullptr, &c.framebuffers.back()), "vkCreateFramebuffer");
        auto sem = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        c.rendered.push_back(VK_NULL_HANDLE);
        check(vkCreateSemaphore(d.device, &sem, nullptr, &c.rendered.back()), "vkCreateSemaphore");
    }
}

void checkImGuiVk(VkResult r) {
    if (r < 0) {  // ImGui's backend cannot carry on after a failed call
        std::fprintf(stderr, "error: ImGui Vulkan backend: %s\n", gpu::resultName(r));
        std::abort();
    }
}

void initImGuiVulkan(Presenter& p) {
    gpu::Device& d = *p.d;
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8};
    auto pool = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    pool.maxSets = 8;
    pool.poolSizeCount = 1;
    pool.pPoolSizes = &size;
    check(vkCreateDescriptorPool(d.device, &pool, nullptr, &p.imguiPool), "vkCreateDescriptorPool");
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = d.instance;
    info.PhysicalDevice = d.physical;
    info.Device = d.device;
    info.QueueFamily = d.queueFamily;
    info.Queue = d.queue;
    info.DescriptorPool = p.imguiPool;
    info.MinImageCount = p.chain.minImages;
    info.ImageCount = std::max<std::uint32_t>(std::uint32_t(p.chain.images.size()), p.chain.minImages);
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkImGuiVk;
    if (!ImGui_ImplVulkan_Init(&info, p.overlay)) throw Error("view: ImGui_ImplVulkan_Init failed");
    p.imgui = true;
    gpu::submitOnce(d, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

}  // namespace

/// The instance extensions a surface needs, for every device built from now on.
void requestPresentation() {
    std::uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (names == nullptr) throw Error("view: Vulkan cannot present to this window system");
    gpu::setPresentationExtensions(std::vector<std::string>(names, names + count));
}

void destroyPresenter(Presenter& p) {
    if (p.d == nullptr || p.d->device == VK_NULL_HANDLE) return;
    gpu::Device& d = *p.d;
    vkDeviceWaitIdle(d.device);
    if (p.imgui) ImGui_ImplVulkan_Shutdown();
    p.imgui = false;
    vkDestroyDescriptorPool(d.device, p.imguiPool, nullptr);
    destroyChainViews(d, p.chain);
    vkDestroySwapchainKHR(d.device, p.chain.swapchain, nullptr);
    vkDestroyRenderPass(d.device, p.overlay, nullptr);
    vkDestroySemaphore(d.device, p.acquired, nullptr);
    vkDestroyFence(d.device, p.done, nullptr);
    vkDestroyCommandPool(d.device, p.pool, nullptr);
    vkDestroySurfaceKHR(d.instance, p.surface, nullptr);
    p = Presenter{};
}

Presenter createPresenter(gpu::Device& d, GLFWwindow* window) {
    Presenter p;
    p.d = &d;
    try {
        check(glfwCreateWindowSurface(d.instance, window, nullptr, &p.surface), "glfwCreateWindowSurface");
        VkBool32 supported = VK_FALSE;
        check(vkGetPhysicalDeviceSurfaceSupportKHR(d.physical, d.queueFamily, p.surface, &supported),
              "vkGetPhysicalDeviceSurfaceSupportKHR");
        if (supported == VK_FALSE) throw Error("view: the device's queue cannot present to this window");
        p.surfaceFormat = chooseFormat(d, p.surface);
        p.presentMode = choosePresentMode(d, p.surface);
        p.overlay = createOverlayPass(d, p.surfaceFormat.format);
        createSwapchain(p, window);
        auto pool = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = d.queueFamily;
        check(vkCreateCommandPool(d.device, &pool, nullptr, &p.pool), "vkCreateCommandPool");
        auto alloc = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        alloc.commandPool = p.pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        check(vkAllocateCommandBuffers(d.device, &alloc, &p.cmd), "vkAllocateCommandBuffers");
        auto fence = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        fence.flags = VK_FENCE_CREATE_SIGNALED_BIT;
        check(vkCreateFence(d.device, &fence, nullptr, &p.done), "vkCreateFence");
        auto sem = vkStruct<VkSemaphoreCreateInfo>(VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO);
        check(vkCreateSemaphore(d.device, &sem, nullptr, &p.acquired), "vkCreateSemaphore");
        initImGuiVulkan(p);
    } catch (...) {
        destroyPresenter(p);
        throw;
    }
    return p;
}

/// The largest rectangle of the frame's aspect centred in the window.
VkOffset3D fitted(std::uint32_t fw, std::uint32_t fh, VkExtent2D win, bool end) {
    const double scale = std::min(double(win.width) / fw, double(win.height) / fh);
    const auto w = std::int32_t(std::lround(fw * scale)), h = std::int32_t(std::lround(fh * scale));
    const std::int32_t x = (std::int32_t(win.width) - w) / 2, y = (std::int32_t(win.height) - h) / 2;
    return end ? VkOffset3D{x + w, y + h, 1} : VkOffset3D{x, y, 0};
}

/// After recordFrame: the frame blitted (scaled, letterboxed) into swapchain
/// image `index`, then ImGui's draw data over it; leaves it PRESENT_SRC.
void recordPresent(Presenter& p, const render::RenderTarget& target, std::uint32_t index) {
    const Swapchain& c = p.chain;
    VkImage image = c.images[index];
    // From UNDEFINED: the whole image is rewritten. The stage is the one the
    // acquire semaphore is waited at, so the two chain.
    render::imageBarrier(p.cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_ACCESS_TRANSFER_WRITE_BIT);
    VkClearColorValue black{};
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(p.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
    // The blit writes over part of what the clear wrote (the bars stay).
    render::imageBarrier(p.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_ACCESS_TRANSFER_WRITE_BIT);
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {std::int32_t(target.width), std::int32_t(target.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[0] = fitted(target.width, target.height, c.extent, false);
    blit.dstOffsets[1] = fitted(target.width, target.height, c.extent, true);
    if (blit.dstOffsets[1].x > blit.dstOffsets[0].x && blit.dstOffsets[1].y > blit.dstOffsets[0].y) {
        // vkCmdBlitImage converts RGBA sRGB to the swapchain's format.
        vkCmdBlitImage(p.cmd, target.colour.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    }
    render::imageBarrier(p.cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    auto begin = vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    begin.renderPass = p.overlay;
    begin.framebuffer = c.framebuffers[index];
    begin.renderArea = {{0, 0}, c.extent};
    vkCmdBeginRenderPass(p.cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), p.cmd);
    vkCmdEndRenderPass(p.cmd);
}

void recreateSwapchain(Presenter& p, GLFWwindow* window) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    while ((w == 0 || h == 0) && glfwWindowShouldClose(window) == GLFW_FALSE) {  // minimised: wait
        glfwWaitEvents();
        glfwGetFramebufferSize(window, &w, &h);
    }
    check(vkDeviceWaitIdle(p.d->device), "vkDeviceWaitIdle");
    createSwapchain(p, window);
}

}  // namespace spindrift::app
