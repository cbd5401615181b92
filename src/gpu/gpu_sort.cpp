// Back-to-front sort on the device: pipelines, scratch and the recorded passes
// of back_to_front_sort.comp (the algorithm and its reasons are there).
#include "gpu/gpu_sort.h"

#include "gpu/gpu_world.h"
#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/layout.glsl"
#include "kernels/sort_key.glsl"

#include <spindrift/effects.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <span>
#include <utility>

namespace spindrift::gpu {
namespace {

// Bindings, passes, flags, the header and the push constants of
// back_to_front_sort.comp: src/kernels/layout.glsl, which the shader includes.
constexpr std::uint32_t kBindings = kernels::SD_SORT_BINDINGS;
constexpr std::uint32_t kFlagAges = kernels::SD_SORT_FLAG_AGES;
constexpr VkDeviceSize kHeaderBytes = sizeof(kernels::TableHeader);
using kernels::SortPush;

// The PASS specialization constant of back_to_front_sort.comp.
enum class SortPass : std::uint32_t {
    Keys = kernels::SD_SORT_PASS_KEYS,
    Count = kernels::SD_SORT_PASS_COUNT,
    Scan = kernels::SD_SORT_PASS_SCAN,
    Scatter = kernels::SD_SORT_PASS_SCATTER,
};
static_assert(kernels::SD_SORT_TILE == kernels::SD_SORT_WORKGROUP * kernels::SD_SORT_ITEMS_PER_THREAD);
static_assert(kernels::SD_SORT_RADIX == 1u << kernels::SD_SORT_DIGIT_BITS);
static_assert(kernels::SD_SORT_PASSES * kernels::SD_SORT_DIGIT_BITS == 32);
// The count and scatter passes give one invocation per digit a row to scan.
static_assert(kernels::SD_SORT_WORKGROUP >= kernels::SD_SORT_RADIX);
// An even number of passes leaves the result in the first buffer pair.
static_assert(kernels::SD_SORT_PASSES % 2 == 0);

void createLayouts(GpuSort& s) {
    const StorageLayouts l = createStorageLayouts(*s.device, kBindings, sizeof(SortPush), s.sets, "sort");
    s.setLayout = l.setLayout;
    s.pipelineLayout = l.pipelineLayout;
    s.pool = l.pool;
}

std::uint32_t tilesFor(std::uint32_t count) {
    return (count + kernels::SD_SORT_TILE - 1) / kernels::SD_SORT_TILE;
}

// Scratch for `count` pairs, in whole tiles (at least one: no buffer may be
// empty). Only between submissions: the old buffers must be idle.
void reserve(GpuSort& s, std::uint32_t count) {
    const std::uint32_t tiles = std::max(tilesFor(count), 1u);
    const std::uint32_t pairs = tiles * kernels::SD_SORT_TILE;
    if (pairs <= s.capacity) {
        return;
    }
    Device& d = *s.device;
    for (Buffer* b : {&s.keys[0], &s.keys[1], &s.values[0], &s.values[1], &s.tileCounts}) {
        destroyBuffer(d, *b);
    }
    s.capacity = 0;
    for (int p = 0; p < 2; ++p) {
        s.keys[p] = createStorageBuffer(d, VkDeviceSize{pairs} * 4);
        s.values[p] = createStorageBuffer(d, VkDeviceSize{pairs} * 4);
    }
    s.tileCounts = createStorageBuffer(d, VkDeviceSize{tiles} * kernels::SD_SORT_RADIX * 4);
    s.capacity = pairs;
}

// Points both sets at the input and the scratch; set p reads pair p and
// writes pair 1 - p. `ages` may be null (not read without FLAG_AGES).
void writeSets(GpuSort& s, const Buffer* positions, const Buffer* ages) {
    if (ages == nullptr) {
        ages = positions;
    }
    std::array<VkDescriptorBufferInfo, 2 * kBindings> infos{};
    std::array<VkWriteDescriptorSet, 2 * kBindings> writes{};
    for (std::uint32_t p = 0; p < 2; ++p) {
        std::array<const Buffer*, kBindings> buffers{};
        buffers[kernels::SD_SORT_BINDING_POSITIONS] = positions;
        buffers[kernels::SD_SORT_BINDING_AGES] = ages;
        buffers[kernels::SD_SORT_BINDING_KEYS] = &s.keys[p];
        buffers[kernels::SD_SORT_BINDING_VALUES] = &s.values[p];
        buffers[kernels::SD_SORT_BINDING_NEXT_KEYS] = &s.keys[1 - p];
        buffers[kernels::SD_SORT_BINDING_NEXT_VALUES] = &s.values[1 - p];
        buffers[kernels::SD_SORT_BINDING_TILE_COUNTS] = &s.tileCounts;
        buffers[kernels::SD_SORT_BINDING_HEADER] = &s.header;
        for (std::uint32_t i = 0; i < kBindings; ++i) {
            const std::uint32_t k = p * kBindings + i;
            infos[k] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
            writes[k] = vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
            writes[k].dstSet = s.sets[p];
            writes[k].dstBinding = i;
            writes[k].descriptorCount = 1;
            writes[k].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            writes[k].pBufferInfo = &infos[k];
        }
    }
    vkUpdateDescriptorSets(s.device->device, 2 * kBindings, writes.data(), 0, nullptr);
}

void dispatch(const GpuSort& s, VkCommandBuffer cmd, VkPipeline pipeline, int set, const SortPush& push,
              std::uint32_t groups) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelineLayout, 0, 1, &s.sets[set], 0, nullptr);
    vkCmdPushConstants(cmd, s.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, groups, 1, 1);
}

// Radix passes (one per digit) that sort `count` keys by their low `keyBits` bits.
std::uint32_t radixPasses(std::uint32_t count, std::uint32_t keyBits) {
    return count == 0 ? 0u : (keyBits + kernels::SD_SORT_DIGIT_BITS - 1) / kernels::SD_SORT_DIGIT_BITS;
}

void requireTiles(const GpuSort& s, std::uint32_t n) {
    const std::uint32_t tiles = tilesFor(n);
    const std::uint32_t maxGroups = s.device->properties.limits.maxComputeWorkGroupCount[0];
    if (tiles > maxGroups) {
        throw Error(fmt::format("gpu sort: {} keys need {} workgroups of {}; this device dispatches at most {}", n,
                                tiles, kernels::SD_SORT_TILE, maxGroups));
    }
}

}  // namespace

GpuSort::~GpuSort() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    Device& d = *device;
    for (Buffer* b : {&header, &tileCounts, &values[1], &values[0], &keys[1], &keys[0]}) {
        destroyBuffer(d, *b);
    }
    destroyComputePasses(d, {scatterPipeline, scanPipeline, countPipeline, keysPipeline}, pool, pipelineLayout,
                         setLayout);
}

std::unique_ptr<GpuSort> createGpuSort(Device& d) {
    auto s = std::make_unique<GpuSort>();  // destroys what was made if a step throws
    s->device = &d;
    createLayouts(*s);
    for (auto [pipeline, pass] : {std::pair{&s->keysPipeline, SortPass::Keys},
                                  std::pair{&s->countPipeline, SortPass::Count},
                                  std::pair{&s->scanPipeline, SortPass::Scan},
                                  std::pair{&s->scatterPipeline, SortPass::Scatter}}) {
        const std::array<std::uint32_t, 1> constants{static_cast<std::uint32_t>(pass)};
        *pipeline = createComputePipeline(d, s->pipelineLayout,
                                          std::span(shaders::kBackToFrontSort, shaders::kBackToFrontSortWords),
                                          constants, "back_to_front_sort");
    }
    s->header = createStorageBuffer(d, kHeaderBytes);
    return s;
}

void recordSortBackToFront(GpuSort& s, VkCommandBuffer cmd, const SortInput& in) {
    const std::uint32_t n = in.count;
    const std::uint32_t tiles = tilesFor(n);
    requireTiles(s, n);
    requireBufferBytes(in.positions, VkDeviceSize{n} * 12, "gpu sort", "positions");
    if (in.ages != nullptr) {
        requireBufferBytes(in.ages, VkDeviceSize{n} * 4, "gpu sort", "ages");
    }
    reserve(s, n);
    writeSets(s, in.positions, in.ages);

    // The positions' writers (an update pass, an upload) before the keys pass;
    // the header is zeroed by a transfer, then counted into by the keys pass.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, s.header.buffer, 0, kHeaderBytes, 0u);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    if (n > 0) {
        SortPush push{glm::vec4(in.eye, 0.0f), glm::vec4(in.forward, 0.0f), n, tiles, 0,
                      in.ages != nullptr ? kFlagAges : 0u};
        dispatch(s, cmd, s.keysPipeline, 0, push, tiles);
        // Every bit of the 32-bit keys; an even number of passes leaves the
        // result in pair 0 (sortedIndices).
        recordRadixPasses(s, cmd, n, kernels::SD_SORT_PASSES * kernels::SD_SORT_DIGIT_BITS);
    }
    // The order and the live count for whoever reads them next: a compute pass
    // (the renderer's, or an indirect dispatch) or a copy.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

void bindRadixSort(GpuSort& s, std::uint32_t count, const Buffer& input) {
    requireTiles(s, count);
    reserve(s, count);
    writeSets(s, &input, nullptr);
}

int radixResultPair(std::uint32_t count, std::uint32_t keyBits) {
    return static_cast<int>(radixPasses(count, keyBits) % 2);
}

void recordRadixPasses(GpuSort& s, VkCommandBuffer cmd, std::uint32_t count, std::uint32_t keyBits) {
    const std::uint32_t passes = radixPasses(count, keyBits);
    SortPush push{glm::vec4(0.0f), glm::vec4(0.0f), count, tilesFor(count), 0, 0u};
    for (std::uint32_t pass = 0; pass < passes; ++pass) {
        const int set = static_cast<int>(pass % 2);
        push.shift = pass * kernels::SD_SORT_DIGIT_BITS;
        computeToCompute(cmd);
        dispatch(s, cmd, s.countPipeline, set, push, push.tiles);
        computeToCompute(cmd);
        dispatch(s, cmd, s.scanPipeline, set, push, 1);
        computeToCompute(cmd);
        dispatch(s, cmd, s.scatterPipeline, set, push, push.tiles);
    }
}

const Buffer& sortedIndices(const GpuSort& s) { return s.values[0]; }
const Buffer& liveCount(const GpuSort& s) { return s.header; }

std::uint32_t readLiveCount(GpuSort& s) {
    std::uint32_t live = 0;
    Transfer t{&s.header, &live, sizeof(live)};
    download(*s.device, std::span(&t, 1));
    return live;
}

std::vector<std::uint32_t> readSortedIndices(GpuSort& s, std::uint32_t count) {
    std::vector<std::uint32_t> order(count);
    if (count > 0) {
        Transfer t{&s.values[0], order.data(), VkDeviceSize{count} * 4};
        download(*s.device, std::span(&t, 1));
    }
    return order;
}

std::vector<std::uint32_t> sortEmitterSlots(GpuWorld& w, std::size_t index, glm::vec3 eye, glm::vec3 forward) {
    GpuEmitter& e = *w.emitters.at(index);
    if (e.capacity == 0) {
        return {};
    }
    if (!w.sort) {
        w.sort = createGpuSort(*w.device);
    }
    GpuSort& s = *w.sort;
    waitForSteps(w);  // the positions of the steps in flight
    SortInput in{&e.positions, &e.ages, e.capacity, eye, forward};
    submitOnce(*w.device, [&](VkCommandBuffer cmd) { recordSortBackToFront(s, cmd, in); });
    return readSortedIndices(s, readLiveCount(s));
}

}  // namespace spindrift::gpu
