// Storage buffers of the GPU backend. Particle data lives in device-local
// memory and moves only through staging buffers, which are counted per device
// (Device::bytesUploaded / bytesDownloaded): a step must move nothing.
#pragma once

#include "gpu/vulkan_device.h"

#include <cstddef>
#include <span>
#include <vector>

namespace spindrift::gpu {

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // host-visible buffers only
};

/// A buffer with its own memory; host-visible ones stay mapped. size > 0.
Buffer createBuffer(Device& d, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memoryFlags);
/// Device-local storage buffer that can be copied to and from.
Buffer createStorageBuffer(Device& d, VkDeviceSize size);
/// Host-visible, host-coherent storage buffer, mapped (small counters read by the CPU).
Buffer createHostStorageBuffer(Device& d, VkDeviceSize size);
void destroyBuffer(Device& d, Buffer& b);
/// Throws Error, naming `pass` and `what`, unless `b` is a buffer of at
/// least `bytes` (a pass's input checked where it enters).
void requireBufferBytes(const Buffer* b, VkDeviceSize bytes, const char* pass, const char* what);
/// Destroys `b` and creates a device-local storage buffer of at least `bytes`
/// (16 at least) in its place. Only while nothing pending uses `b`.
void recreateStorageBuffer(Device& d, Buffer& b, VkDeviceSize bytes);

/// One copy between host memory and a device buffer, at `offset` bytes into
/// the buffer.
struct Transfer {
    Buffer* buffer;
    void* host;
    VkDeviceSize bytes;
    VkDeviceSize offset = 0;
};

/// Copies every host range into its buffer through one staging buffer and one
/// submission; makes them visible to compute shaders. Counts the bytes.
void upload(Device& d, std::span<const Transfer> transfers);
/// Uploads `bytes` of `data` into storage buffer `b`, made anew when too
/// small (16 bytes at least: an empty list still binds a buffer).
void uploadGrowing(Device& d, Buffer& b, const void* data, VkDeviceSize bytes);
/// A sampled image with its own memory and one view of the whole image.
struct Image {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
};

/// Shape of a sampled image: a 3D image (depth > 1 allowed), a 2D image, or a
/// cube (cube-compatible 2D image of 6 layers, width == height, view CUBE).
struct ImageShape {
    VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D;
    VkFormat format = VK_FORMAT_UNDEFINED;
    std::uint32_t width = 1, height = 1, depth = 1;
    /// The renderer's targets add attachment and transfer-source uses.
    VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    /// Layers of a VK_IMAGE_VIEW_TYPE_2D_ARRAY (a cube has 6, others 1).
    std::uint32_t arrayLayers = 1;
    /// Mip levels, each half the one before (at least 1 texel a side).
    std::uint32_t levels = 1;
    std::uint32_t layers() const {
        return viewType == VK_IMAGE_VIEW_TYPE_CUBE ? 6u
                                                   : (viewType == VK_IMAGE_VIEW_TYPE_2D_ARRAY ? arrayLayers : 1u);
    }
};

/// True when `format` with optimal tiling can be sampled with VK_FILTER_LINEAR
/// and copied into (vkGetPhysicalDeviceFormatProperties).
bool linearFilterable(const Device& d, VkFormat format);
/// A device-local image that can be copied into and sampled, in layout
/// UNDEFINED; fill it with uploadImage or clearImage.
Image createSampledImage(Device& d, const ImageShape& shape);
/// Copies `bytes` of tightly packed texels (mip level, then layer, z, y, x;
/// x fastest) through a staging buffer into the whole image, with the layout transitions
/// UNDEFINED -> TRANSFER_DST_OPTIMAL -> SHADER_READ_ONLY_OPTIMAL and barriers
/// that make the copy visible to compute shaders. Counts the bytes as uploaded.
void uploadImage(Device& d, Image& image, const ImageShape& shape, const void* texels, VkDeviceSize bytes);
/// Fills the whole image with zeros on the device (no transfer from the host)
/// and leaves it in SHADER_READ_ONLY_OPTIMAL: a placeholder.
void clearImage(Device& d, Image& image, const ImageShape& shape);
void destroyImage(Device& d, Image& image);

/// Linear filtering, clamped at the edges (fields, sprites, backgrounds).
/// A sampler of `filter` in both directions and `address` on every axis;
/// with `mipmaps`, linear between mip levels over all of them, else level 0.
VkSampler createSampler(Device& d, VkFilter filter, VkSamplerAddressMode address, bool mipmaps);
/// createSampler(linear, clamp to edge, level 0).
VkSampler createLinearSampler(Device& d);

/// Layout transition of `range` of `image` with its execution and memory dependency.
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                  VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

/// Waits for earlier compute writes, copies every buffer into its host range
/// through one staging buffer and one submission. Counts the bytes.
void download(Device& d, std::span<const Transfer> transfers);

/// The first `count` elements of `b` (download; tests and read-backs).
template <class T>
std::vector<T> downloadArray(Device& d, Buffer& b, std::size_t count) {
    std::vector<T> out(count);
    if (count > 0) {
        const Transfer t{&b, out.data(), VkDeviceSize{count} * sizeof(T)};
        download(d, std::span(&t, 1));
    }
    return out;
}

}  // namespace spindrift::gpu
