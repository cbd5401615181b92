// Back-to-front sort on the device (src/gpu/shaders/back_to_front_sort.comp):
// view-depth keys of a positions buffer that stays on the device, radix-sorted
// into an index buffer on the device (for the renderer), in exactly the order
// of the CPU's sortBackToFront. Nothing is read back unless asked for.
//
// Dead slots: the sort runs over every slot and, when given the slots' ages,
// puts the dead ones (age < 0, as readParticles skips them) after the live
// ones, and counts the live ones on the device. Sorting every slot rather than
// a spawn emitter's alive list keeps ties in slot order: the alive list is
// filled with atomics, so its order changes from run to run, and a stable sort
// of it would break ties differently each time.
//
// "Exactly" assumes the device rounds float add and multiply to nearest and
// keeps subnormals, infinities and NaNs, as lavapipe (and the CPU) do. Vulkan
// lets a device round toward zero or flush subnormals unless it reports
// shaderRoundingModeRTEFloat32 / shaderDenormPreserveFloat32 (Vulkan 1.2
// spec, "Precision and Operation of SPIR-V Instructions"); there, depths can
// differ in the last bit and near-equal particles swap.
#pragma once

#include "gpu/vulkan_buffer.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace spindrift::gpu {

struct GpuWorld;

/// Pipelines and scratch of the sort, for one Device. Scratch grows on
/// demand and never shrinks: two (key, value) buffer pairs of the largest
/// count sorted so far, the per-tile digit counts and a header (live count).
struct GpuSort {
    Device* device = nullptr;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkPipeline keysPipeline = VK_NULL_HANDLE;
    VkPipeline countPipeline = VK_NULL_HANDLE;
    VkPipeline scanPipeline = VK_NULL_HANDLE;
    VkPipeline scatterPipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    /// sets[p]: keys[p], values[p] are the current pairs, the others the next.
    VkDescriptorSet sets[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};
    Buffer keys[2], values[2];
    Buffer tileCounts;  // [digit][tile]
    Buffer header;      // uint liveCount, 3 pads
    std::uint32_t capacity = 0;  // pairs each scratch buffer holds

    GpuSort() = default;
    GpuSort(const GpuSort&) = delete;
    GpuSort& operator=(const GpuSort&) = delete;
    ~GpuSort();
};

/// Creates the four pipelines (compiled by the driver now, not at the first sort).
std::unique_ptr<GpuSort> createGpuSort(Device& d);

/// What to sort: `count` positions (tightly packed float xyz) and, optionally,
/// their ages (float; age < 0 is a dead slot).
struct SortInput {
    const Buffer* positions = nullptr;
    const Buffer* ages = nullptr;  // null: every slot is live
    std::uint32_t count = 0;
    glm::vec3 eye{0.0f};
    glm::vec3 forward{0.0f, 0.0f, 1.0f};  // unit length: normalizeViewDirection
};

/// Records the sort into `cmd`: afterwards sortedIndices(s) holds the
/// `count` indices, the live ones first, farthest first (ties in index order,
/// NaN depths last), then the dead ones in index order, and liveCount(s) the
/// number of live ones. Waits for earlier compute and transfer writes (the
/// positions); its results are visible to later compute and transfer
/// commands. Grows the scratch and rewrites the descriptor sets, so no other
/// sort of `s` may be pending or recorded in the same command buffer. Throws
/// Error for a count above what one dispatch can tile or buffers too small.
void recordSortBackToFront(GpuSort& s, VkCommandBuffer cmd, const SortInput& input);

/// The radix passes alone, for (key, value) pairs another pass writes (the
/// fluid's grid, src/gpu/gpu_fluid_grid.cpp): grows the scratch to `count`
/// pairs and binds `input` where the keys pass would read positions and ages
/// (the radix passes read neither). The caller's pass then writes keys[0] and
/// values[0]. Same rules as recordSortBackToFront: no other sort of `s` may
/// be pending. Throws Error for a count above what one dispatch can tile.
void bindRadixSort(GpuSort& s, std::uint32_t count, const Buffer& input);
/// Records the stable LSD radix passes (count, scan, scatter per 4-bit digit)
/// over the low `keyBits` bits of the `count` pairs in keys[0], values[0]
/// (keys must be below 2^keyBits); waits for earlier compute writes. The
/// sorted pairs are then in pair radixResultPair(count, keyBits). Used by
/// recordSortBackToFront with every bit.
void recordRadixPasses(GpuSort& s, VkCommandBuffer cmd, std::uint32_t count, std::uint32_t keyBits);
/// The pair (0 or 1) recordRadixPasses leaves its result in: one pass per
/// digit, each writing the other pair.
int radixResultPair(std::uint32_t count, std::uint32_t keyBits);

/// The sorted indices (uint32, valid for the last recorded count).
const Buffer& sortedIndices(const GpuSort& s);
/// The live count (one uint32 at offset 0).
const Buffer& liveCount(const GpuSort& s);

/// Read-back helpers (tests, sortEmitterBackToFront): wait for the device and
/// copy the live count or the first `count` sorted indices.
std::uint32_t readLiveCount(GpuSort& s);
std::vector<std::uint32_t> readSortedIndices(GpuSort& s, std::uint32_t count);

/// Sorts every slot of state-preserving emitter `index` of `w` on the device
/// and reads back the live slots, farthest first. `forward` is unit length.
std::vector<std::uint32_t> sortEmitterSlots(GpuWorld& w, std::size_t index, glm::vec3 eye, glm::vec3 forward);

}  // namespace spindrift::gpu
