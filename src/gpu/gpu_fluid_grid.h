// The constraint fluid's grid on the device (issue 16, first slice): the
// CPU's buildGrid (src/fluid/grid.cpp) for a positions buffer that stays on
// the device. Keys by fluid.glsl's fluidGridKey, the back-to-front sort's
// stable radix passes over as many bits as the largest key needs, then
// keyStart (src/gpu/shaders/fluid_grid.comp). The order and keyStart are the
// CPU's, element for element, on a device that rounds float subtract and
// multiply to nearest as lavapipe does (gpu_sort.h has the caveat).
//
// Where the grid lies (origin, cells) is the host's choice, from placeGrid
// (src/fluid/fluid_state.h): it needs the particles' box and median.
#pragma once

#include "gpu/gpu_sort.h"
#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_pipeline.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace spindrift::gpu {

/// Where the grid lies, as fluid::Grid<D> holds it (the caller, above both
/// src/fluid and src/gpu, converts: origin, 1.0f / h, cells).
struct FluidGridParams {
    std::uint32_t dimension = 2;
    glm::vec3 origin{0.0f};       // m, corner of sub-cell 0 (z 0 in 2D)
    float invH = 1.0f;            // 1/m: 1.0f / h, as buildGrid computes it
    glm::ivec3 cells{1, 1, 1};    // cells 2h wide per axis (z 1 in 2D)
};

/// Pipelines and scratch of the grid, for one Device. Scratch grows on demand
/// and never shrinks.
struct GpuFluidGrid {
    Device* device = nullptr;
    /// Its own sort: the radix passes and (key, value) pairs (the grid's keys
    /// pass writes pair 0), apart from the world's back-to-front sort.
    std::unique_ptr<GpuSort> sort;
    ComputePasses passes;  // fluid_grid.comp's two (keys, starts), one set
    Buffer keyStart;                   // uint[keyTotal + 1]
    std::uint32_t keyStartCapacity = 0;  // entries keyStart holds
    // Of the last recorded grid.
    std::uint32_t count = 0;
    std::uint32_t keyTotal = 0;
    std::uint32_t dimension = 2;
    glm::ivec3 cells{1, 1, 1};
    int sortedPair = 0;  // the sort's pair that holds the grid order

    GpuFluidGrid() = default;
    GpuFluidGrid(const GpuFluidGrid&) = delete;
    GpuFluidGrid& operator=(const GpuFluidGrid&) = delete;
    ~GpuFluidGrid();
};

/// Creates the pipelines (the grid's two and the sort's four).
std::unique_ptr<GpuFluidGrid> createGpuFluidGrid(Device& d);

/// Records the grid of `count` particles at `positions` (count x dimension
/// floats, tightly packed, m) into `cmd`: afterwards gridOrder(g) holds, for
/// each place in grid order, the particle's index, and gridKeyStart(g) the
/// first place of each key (keyTotal + 1 entries, the last = count). Waits for
/// earlier compute and transfer writes; its results are visible to later
/// compute and transfer commands. Grows the scratch and rewrites the
/// descriptor sets, so no other grid of `g` may be pending or recorded in the
/// same command buffer. Throws Error for buffers too small or a grid or count
/// too large for one dispatch.
void recordFluidGrid(VkCommandBuffer cmd, GpuFluidGrid& g, const Buffer& positions, std::uint32_t count,
                     const FluidGridParams& params);

/// Grid order -> particle index (uint32, `count` valid of the last grid).
const Buffer& gridOrder(const GpuFluidGrid& g);
/// keyStart (uint32, keyTotal + 1 valid of the last grid).
const Buffer& gridKeyStart(const GpuFluidGrid& g);

/// Read-back helpers (tests): wait for the device and copy the last grid's.
std::vector<std::uint32_t> readGridOrder(GpuFluidGrid& g);
std::vector<std::uint32_t> readGridKeyStart(GpuFluidGrid& g);

}  // namespace spindrift::gpu
