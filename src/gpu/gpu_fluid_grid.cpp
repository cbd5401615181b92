// The constraint fluid's grid on the device: pipelines, scratch and the
// recorded passes of fluid_grid.comp around the back-to-front sort's radix
// passes (gpu_sort.cpp).
#include "gpu/gpu_fluid_grid.h"

#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/layout.glsl"

#include <spindrift/errors.h>

#include <fmt/format.h>

#include <array>
#include <bit>
#include <span>
#include <utility>

namespace spindrift::gpu {
namespace {

// Bindings, passes and push constants of fluid_grid.comp: src/kernels/layout.glsl.
constexpr std::uint32_t kBindings = kernels::SD_FLUID_GRID_BINDINGS;
constexpr std::uint32_t kWorkgroup = kernels::SD_FLUID_GRID_WORKGROUP;
using kernels::FluidGridPush;

// keyStart for `entries` entries. Only between submissions: the old buffer
// must be idle.
void reserveKeyStart(GpuFluidGrid& g, std::uint32_t entries) {
    if (entries <= g.keyStartCapacity) {
        return;
    }
    destroyBuffer(*g.device, g.keyStart);
    g.keyStartCapacity = 0;
    g.keyStart = createStorageBuffer(*g.device, VkDeviceSize{entries} * 4);
    g.keyStartCapacity = entries;
}

void writeSet(GpuFluidGrid& g, const Buffer& positions) {
    std::array<const Buffer*, kBindings> buffers{};
    buffers[kernels::SD_FLUID_GRID_BINDING_POSITIONS] = &positions;
    buffers[kernels::SD_FLUID_GRID_BINDING_KEYS] = &g.sort->keys[0];
    buffers[kernels::SD_FLUID_GRID_BINDING_VALUES] = &g.sort->values[0];
    buffers[kernels::SD_FLUID_GRID_BINDING_SORTED_KEYS] = &g.sort->keys[g.sortedPair];
    buffers[kernels::SD_FLUID_GRID_BINDING_KEY_START] = &g.keyStart;
    writeStorageSet(*g.device, g.passes.sets[0], buffers);
}

void dispatch(const GpuFluidGrid& g, VkCommandBuffer cmd, VkPipeline pipeline, const FluidGridPush& push,
              std::uint32_t groups) {
    dispatchCompute(cmd, pipeline, g.passes.pipelineLayout, g.passes.sets[0], &push, sizeof(push), groups);
}

std::uint32_t groupsFor(const GpuFluidGrid& g, std::uint64_t items, const char* what) {
    return workgroupsFor(*g.device, items, kWorkgroup, "gpu fluid grid", what);
}

}  // namespace


GpuFluidGrid::~GpuFluidGrid() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    Device& d = *device;
    destroyBuffer(d, keyStart);
    destroyComputePasses(d, passes);
}

std::unique_ptr<GpuFluidGrid> createGpuFluidGrid(Device& d) {
    auto g = std::make_unique<GpuFluidGrid>();  // destroys what was made if a step throws
    g->device = &d;
    g->sort = createGpuSort(d);
    createComputePasses(d, kBindings, sizeof(FluidGridPush), 1, std::span(shaders::kFluidGrid, shaders::kFluidGridWords),
                        2, "fluid_grid", g->passes);
    reserveKeyStart(*g, 1);
    return g;
}

void recordFluidGrid(VkCommandBuffer cmd, GpuFluidGrid& g, const Buffer& positions, std::uint32_t count,
                     const FluidGridParams& params) {
    const std::uint32_t dimension = params.dimension;
    if (dimension != 2 && dimension != 3) {
        throw Error(fmt::format("gpu fluid grid: dimension {} (2 or 3)", dimension));
    }
    std::uint64_t keyTotal = std::uint64_t{1} << dimension;  // quadrants per cell
    for (std::uint32_t a = 0; a < 3; ++a) {
        if (params.cells[a] < 1 || (a == 2 && dimension == 2 && params.cells[a] != 1)) {
            throw Error(fmt::format("gpu fluid grid: {} cells along axis {}", params.cells[a], a));
        }
        keyTotal *= static_cast<std::uint64_t>(params.cells[a]);
        if (keyTotal >= 0xFFFFFFFFu) {  // keyStart's keyTotal + 1 entries are counted in a uint
            throw Error("gpu fluid grid: too many cells for 32-bit keys");
        }
    }
    requireBufferBytes(&positions, VkDeviceSize{count} * dimension * 4, "gpu fluid grid", "positions");
    const std::uint32_t keyGroups = groupsFor(g, count, "particles");
    const std::uint32_t startGroups = groupsFor(g, keyTotal + 1, "keys");
    // Keys are below keyTotal: the radix passes need only the bits of keyTotal - 1.
    const auto keyBits = static_cast<std::uint32_t>(std::bit_width(keyTotal - 1));

    bindRadixSort(*g.sort, count, positions);
    reserveKeyStart(g, static_cast<std::uint32_t>(keyTotal + 1));
    g.count = count;
    g.keyTotal = static_cast<std::uint32_t>(keyTotal);
    g.dimension = dimension;
    g.cells = params.cells;
    // The set is written before the passes are recorded (it may not change
    // once bound), so it names the pair they will leave the order in.
    g.sortedPair = radixResultPair(count, keyBits);
    writeSet(g, positions);

    FluidGridPush push{glm::vec4(params.origin, params.invH), glm::ivec4(params.cells, 0), count, dimension,
                       g.keyTotal, 0u};
    // The positions' writers (a step's pass, an upload) before the keys pass.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    if (count > 0) {
        dispatch(g, cmd, g.passes.pipelines[kernels::SD_FLUID_GRID_PASS_KEYS], push, keyGroups);
    }
    recordRadixPasses(*g.sort, cmd, count, keyBits);  // waits for the keys
    computeToCompute(cmd);
    dispatch(g, cmd, g.passes.pipelines[kernels::SD_FLUID_GRID_PASS_STARTS], push, startGroups);
    // The order and keyStart for whoever reads them next: a compute pass or a copy.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

const Buffer& gridOrder(const GpuFluidGrid& g) { return g.sort->values[g.sortedPair]; }
const Buffer& gridKeyStart(const GpuFluidGrid& g) { return g.keyStart; }

std::vector<std::uint32_t> readGridOrder(GpuFluidGrid& g) {
    return downloadArray<std::uint32_t>(*g.device, g.sort->values[g.sortedPair], g.count);
}

std::vector<std::uint32_t> readGridKeyStart(GpuFluidGrid& g) {
    return downloadArray<std::uint32_t>(*g.device, g.keyStart, std::size_t{g.keyTotal} + 1);
}

}  // namespace spindrift::gpu
