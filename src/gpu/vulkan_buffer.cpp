// Buffers, memory and staging copies.
#include "gpu/vulkan_buffer.h"

#include <spindrift/effects.h>

#include <fmt/format.h>

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

}  // namespace

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
        auto alloc = vkStruct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = findMemoryType(d, req.memoryTypeBits, memoryFlags);
        check(vkAllocateMemory(d.device, &alloc, nullptr, &b.memory), "vkAllocateMemory");
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
                    VkBufferCopy region{at, 0, t.bytes};
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
                    VkBufferCopy region{0, at, t.bytes};
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

}  // namespace spindrift::gpu
