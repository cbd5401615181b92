// Compute pipelines and barriers shared by the GPU passes (effect update,
// back-to-front sort): plain free functions in the zeux/niagara style.
#pragma once

#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_device.h"

#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

namespace spindrift::gpu {

/// A compute pipeline of the embedded SPIR-V `code` (entry point "main"),
/// with specialization constant i (constant_id = i) set to constants[i].
/// Throws Error naming `name` and the failing call.
VkPipeline createComputePipeline(Device& d, VkPipelineLayout layout, std::span<const std::uint32_t> code,
                                 std::span<const std::uint32_t> constants, const char* name);

/// What compute passes that bind storage buffers 0..bindings-1 in set 0 and
/// push `pushBytes` of constants share: the set layout, the pipeline layout,
/// and a pool of `sets.size()` descriptor sets, allocated into `sets`.
/// Throws Error naming `name` and the failing call.
struct StorageLayouts {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
};
StorageLayouts createStorageLayouts(Device& d, std::uint32_t bindings, std::uint32_t pushBytes,
                                    std::span<VkDescriptorSet> sets, const char* name);

/// Destroys what one set of compute passes owns, each handle possibly null:
/// its pipelines, the descriptor pool (which frees its sets), the pipeline
/// layout and the set layout.
void destroyComputePasses(Device& d, std::initializer_list<VkPipeline> pipelines, VkDescriptorPool pool,
                          VkPipelineLayout pipelineLayout, VkDescriptorSetLayout setLayout);

/// The passes of one compute shader whose specialization constant 0 picks
/// the pass, binding storage buffers 0..bindings-1 of set 0: pipelines[p]
/// runs pass p; `sets` descriptor sets from their own pool.
struct ComputePasses {
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> sets;
    std::vector<VkPipeline> pipelines;
};
/// Throws Error naming `name`; whatever it made is in `out` (destroy it with
/// destroyComputePasses).
void createComputePasses(Device& d, std::uint32_t bindings, std::uint32_t pushBytes, std::uint32_t sets,
                         std::span<const std::uint32_t> code, std::uint32_t passes, const char* name,
                         ComputePasses& out);
void destroyComputePasses(Device& d, ComputePasses& passes);

/// Execution and memory dependency between commands (a global VkMemoryBarrier).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

/// Compute writes made visible to the next compute dispatch's reads and writes.
void computeToCompute(VkCommandBuffer cmd);

/// Points storage binding i of `set` at the whole of buffers[i].
void writeStorageSet(Device& d, VkDescriptorSet set, std::span<const Buffer* const> buffers);

/// Binds `pipeline` and `set`, pushes `pushBytes` of `push` and dispatches
/// `groups` workgroups along x.
void dispatchCompute(VkCommandBuffer cmd, VkPipeline pipeline, VkPipelineLayout layout, VkDescriptorSet set,
                     const void* push, std::uint32_t pushBytes, std::uint32_t groups);

/// Workgroups of `workgroup` invocations for `items` items. Throws Error
/// naming `pass` and `what` beyond what one dispatch holds on `d`.
std::uint32_t workgroupsFor(const Device& d, std::uint64_t items, std::uint32_t workgroup, const char* pass,
                            const char* what);

}  // namespace spindrift::gpu
