// Buffers, memory and staging copies.
#include "gpu/vulkan_buffer.h"

#include <spindrift/errors.h>

#include <spindrift/effects.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace spindrift::gpu {
namespace {

VkDeviceSize totalBytes(std::span<const Transfer> transfers) {
    VkDeviceSize total = 0;
    for (const Transfer& t : transfers) {
        if (t.bytes > t.buffer->size) {
            throw Error(fmt::format("gpu transfer of {} bytes into a buffer of {} bytes", t.bytes, t.buffer->size));
        }
        total += t.bytes;
    }
    return total;
}

// Execution and memory dependency between two pipeline stages for all buffers
// of the submission (a global VkMemoryBarrier, Vulkan spec 7.7.1).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
    auto barrier = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

// Memory for one resource, of a type that has `flags`.
VkDeviceMemory allocateMemory(Device& d, const VkMemoryRequirements& req, VkMemoryPropertyFlags flags) {
    auto alloc = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = findMemoryType(d, req.memoryTypeBits, flags);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(d.device, &alloc, nullptr, &memory), "vkAllocateMemory");
    return memory;
}

VkImageSubresourceRange wholeImage(const ImageShape& shape) {
    return {shape.aspect, 0, shape.levels, 0, shape.layers()};
}

// Layout transition of the whole image with its execution and memory dependency.
void transition(VkCommandBuffer cmd, VkImage image, const ImageShape& shape, VkImageLayout from, VkImageLayout to,
                VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                VkAccessFlags dstAccess) {
    imageBarrier(cmd, image, wholeImage(shape), from, to, srcStage, srcAccess, dstStage, dstAccess);
}

// UNDEFINED -> TRANSFER_DST_OPTIMAL, `fill` records the transfer, then
// TRANSFER_DST_OPTIMAL -> SHADER_READ_ONLY_OPTIMAL for compute and fragment
// shaders (the renderer samples sprite and background images).
template <class F>
void fillImage(Device& d, Image& image, const ImageShape& shape, F&& fill) {
    submitOnce(d, [&](VkCommandBuffer cmd) {
        transition(cmd, image.image, shape, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        fill(cmd);
        transition(cmd, image.image, shape, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_SHADER_READ_BIT);
    });
}

}  // namespace

bool linearFilterable(const Device& d, VkFormat format) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(d.physical, format, &props);
    const VkFormatFeatureFlags needed = VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                        VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
                                        VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    return (props.optimalTilingFeatures & needed) == needed;
}

Image createSampledImage(Device& d, const ImageShape& shape) {
    Image img;
    const bool cube = shape.viewType == VK_IMAGE_VIEW_TYPE_CUBE;
    const bool volume = shape.viewType == VK_IMAGE_VIEW_TYPE_3D;
    auto info = vkStruct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    info.flags = cube ? VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT : 0;
    info.imageType = volume ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    info.format = shape.format;
    info.extent = {shape.width, shape.height, volume ? shape.depth : 1u};
    info.mipLevels = shape.levels;
    info.arrayLayers = shape.layers();
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = shape.usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(vkCreateImage(d.device, &info, nullptr, &img.image), "vkCreateImage");
    try {
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(d.device, img.image, &req);
        img.memory = allocateMemory(d, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        check(vkBindImageMemory(d.device, img.image, img.memory, 0), "vkBindImageMemory");
        auto view = vkStruct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        view.image = img.image;
        view.viewType = shape.viewType;
        view.format = shape.format;
        view.subresourceRange = wholeImage(shape);
        check(vkCreateImageView(d.device, &view, nullptr, &img.view), "vkCreateImageView");
    } catch (...) {
        destroyImage(d, img);
        throw;
    }
    return img;
}

void uploadImage(Device& d, Image& image, const ImageShape& shape, const void* texels, VkDeviceSize bytes) {
    Buffer staging = createBuffer(d, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    try {
        std::memcpy(staging.mapped, texels, bytes);
        fillImage(d, image, shape, [&](VkCommandBuffer cmd) {
            // One region a mip level, all layers at once; the texel size
            // follows from the bytes of level 0's layers and the rest.
            const std::uint32_t depth = shape.viewType == VK_IMAGE_VIEW_TYPE_3D ? shape.depth : 1u;
            VkDeviceSize texels = 0;
            for (std::uint32_t level = 0; level < shape.levels; ++level) {
                texels += VkDeviceSize{std::max(shape.width >> level, 1u)} * std::max(shape.height >> level, 1u) *
                          std::max(depth >> level, 1u) * shape.layers();
            }
            const VkDeviceSize texelBytes = bytes / texels;
            VkDeviceSize offset = 0;
            for (std::uint32_t level = 0; level < shape.levels; ++level) {
                VkBufferImageCopy region{};
                region.bufferOffset = offset;
                region.bufferRowLength = 0;  // tightly packed
                region.bufferImageHeight = 0;
                region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, shape.layers()};
                region.imageOffset = {0, 0, 0};
                region.imageExtent = {std::max(shape.width >> level, 1u), std::max(shape.height >> level, 1u),
                                      std::max(depth >> level, 1u)};
                vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                                       &region);
                offset += VkDeviceSize{region.imageExtent.width} * region.imageExtent.height *
                          region.imageExtent.depth * shape.layers() * texelBytes;
            }
        });
    } catch (...) {
        destroyBuffer(d, staging);
        throw;
    }
    destroyBuffer(d, staging);
    d.bytesUploaded += bytes;
}

void clearImage(Device& d, Image& image, const ImageShape& shape) {
    fillImage(d, image, shape, [&](VkCommandBuffer cmd) {
        VkClearColorValue zero{};
        VkImageSubresourceRange range = wholeImage(shape);
        vkCmdClearColorImage(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
    });
}

void destroyImage(Device& d, Image& image) {
    if (image.view != VK_NULL_HANDLE) {
        vkDestroyImageView(d.device, image.view, nullptr);
    }
    if (image.image != VK_NULL_HANDLE) {
        vkDestroyImage(d.device, image.image, nullptr);
    }
    if (image.memory != VK_NULL_HANDLE) {
        vkFreeMemory(d.device, image.memory, nullptr);
    }
    image = Image{};
}

Buffer createBuffer(Device& d, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags memoryFlags) {
    Buffer b;
    b.size = size;
    auto info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(d.device, &info, nullptr, &b.buffer), "vkCreateBuffer");
    try {
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(d.device, b.buffer, &req);
        b.memory = allocateMemory(d, req, memoryFlags);
        check(vkBindBufferMemory(d.device, b.buffer, b.memory, 0), "vkBindBufferMemory");
        if ((memoryFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) != 0) {
            check(vkMapMemory(d.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
        }
    } catch (...) {
        destroyBuffer(d, b);
        throw;
    }
    return b;
}

Buffer createStorageBuffer(Device& d, VkDeviceSize size) {
    return createBuffer(d, size,
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                            VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
}

Buffer createHostStorageBuffer(Device& d, VkDeviceSize size) {
    return createBuffer(d, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
}

void requireBufferBytes(const Buffer* b, VkDeviceSize bytes, const char* pass, const char* what) {
    if (b == nullptr || b->buffer == VK_NULL_HANDLE || b->size < bytes) {
        throw Error(fmt::format("{}: the {} buffer holds {} bytes, {} needed", pass, what,
                                b != nullptr ? b->size : VkDeviceSize{0}, bytes));
    }
}

void recreateStorageBuffer(Device& d, Buffer& b, VkDeviceSize bytes) {
    destroyBuffer(d, b);
    b = createStorageBuffer(d, bytes < 16 ? VkDeviceSize{16} : bytes);
}

void destroyBuffer(Device& d, Buffer& b) {
    // Unmapping is implicit in vkFreeMemory (Vulkan spec, vkFreeMemory).
    if (b.buffer != VK_NULL_HANDLE) {
        vkDestroyBuffer(d.device, b.buffer, nullptr);
    }
    if (b.memory != VK_NULL_HANDLE) {
        vkFreeMemory(d.device, b.memory, nullptr);
    }
    b = Buffer{};
}

void uploadGrowing(Device& d, Buffer& b, const void* data, VkDeviceSize bytes) {
    if (b.buffer == VK_NULL_HANDLE || b.size < std::max<VkDeviceSize>(bytes, 16u)) {
        recreateStorageBuffer(d, b, bytes);
    }
    if (bytes > 0) {
        const Transfer t{&b, const_cast<void*>(data), bytes};
        upload(d, std::span(&t, 1));
    }
}

void upload(Device& d, std::span<const Transfer> transfers) {
    VkDeviceSize total = totalBytes(transfers);
    if (total == 0) {
        return;
    }
    Buffer staging = createBuffer(d, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    try {
        VkDeviceSize offset = 0;
        for (const Transfer& t : transfers) {
            std::memcpy(static_cast<char*>(staging.mapped) + offset, t.host, t.bytes);
            offset += t.bytes;
        }
        // Host writes before vkQueueSubmit are visible to the device without a
        // barrier (Vulkan spec 7.9, "Host Write Ordering Guarantee").
        submitOnce(d, [&](VkCommandBuffer cmd) {
            VkDeviceSize at = 0;
            for (const Transfer& t : transfers) {
                if (t.bytes > 0) {
                    VkBufferCopy region{at, t.offset, t.bytes};
                    vkCmdCopyBuffer(cmd, staging.buffer, t.buffer->buffer, 1, &region);
                }
                at += t.bytes;
            }
            memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        });
    } catch (...) {
        destroyBuffer(d, staging);
        throw;
    }
    destroyBuffer(d, staging);
    d.bytesUploaded += total;
}

void download(Device& d, std::span<const Transfer> transfers) {
    VkDeviceSize total = totalBytes(transfers);
    if (total == 0) {
        return;
    }
    Buffer staging = createBuffer(d, total, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    try {
        submitOnce(d, [&](VkCommandBuffer cmd) {
            memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
            VkDeviceSize at = 0;
            for (const Transfer& t : transfers) {
                if (t.bytes > 0) {
                    VkBufferCopy region{t.offset, at, t.bytes};
                    vkCmdCopyBuffer(cmd, t.buffer->buffer, staging.buffer, 1, &region);
                }
                at += t.bytes;
            }
            // Device writes must be made available to the host before the fence
            // wait makes them visible (Vulkan spec 7.9, host access).
            memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        });
        VkDeviceSize offset = 0;
        for (const Transfer& t : transfers) {
            std::memcpy(t.host, static_cast<const char*>(staging.mapped) + offset, t.bytes);
            offset += t.bytes;
        }
    } catch (...) {
        destroyBuffer(d, staging);
        throw;
    }
    destroyBuffer(d, staging);
    d.bytesDownloaded += total;
}

VkSampler createSampler(Device& d, VkFilter filter, VkSamplerAddressMode address, bool mipmaps) {
    auto info = vkStruct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    info.magFilter = filter;
    info.minFilter = filter;
    info.mipmapMode = mipmaps ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = address;
    info.addressModeV = address;
    info.addressModeW = address;
    info.minLod = 0.0f;
    info.maxLod = mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
    info.unnormalizedCoordinates = VK_FALSE;
    VkSampler sampler = VK_NULL_HANDLE;
    check(vkCreateSampler(d.device, &info, nullptr, &sampler), "vkCreateSampler");
    return sampler;
}

VkSampler createLinearSampler(Device& d) {
    return createSampler(d, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                  VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
    auto b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = range;
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace spindrift::gpu
