// Storage buffers of the GPU backend. Particle data lives in device-local
// memory and moves only through staging buffers, which are counted per device
// (Device::bytesUploaded / bytesDownloaded): a step must move nothing.
#pragma once

#include "gpu/vulkan_device.h"

#include <span>

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

/// One copy between host memory and a device buffer, at offset 0.
struct Transfer {
    Buffer* buffer;
    void* host;
    VkDeviceSize bytes;
};

/// Copies every host range into its buffer through one staging buffer and one
/// submission; makes them visible to compute shaders. Counts the bytes.
void upload(Device& d, std::span<const Transfer> transfers);
/// Waits for earlier compute writes, copies every buffer into its host range
/// through one staging buffer and one submission. Counts the bytes.
void download(Device& d, std::span<const Transfer> transfers);

}  // namespace spindrift::gpu
