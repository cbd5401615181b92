// Compute pipelines and barriers shared by the GPU passes (effect update,
// back-to-front sort): plain free functions in the zeux/niagara style.
#pragma once

#include "gpu/vulkan_device.h"

#include <cstdint>
#include <span>

namespace spindrift::gpu {

/// A compute pipeline of the embedded SPIR-V `code` (entry point "main"),
/// with specialization constant i (constant_id = i) set to constants[i].
/// Throws Error naming `name` and the failing call.
VkPipeline createComputePipeline(Device& d, VkPipelineLayout layout, std::span<const std::uint32_t> code,
                                 std::span<const std::uint32_t> constants, const char* name);

/// Execution and memory dependency between commands (a global VkMemoryBarrier).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

/// Compute writes made visible to the next compute dispatch's reads and writes.
void computeToCompute(VkCommandBuffer cmd);

}  // namespace spindrift::gpu
