// The constraint fluid's solve on the device: pipelines, scratch and the
// recorded passes of fluid_solve.comp.
#include "gpu/gpu_fluid_solve.h"

#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/fluid.glsl"
#include "kernels/layout.glsl"

#include <spindrift/errors.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <span>

namespace spindrift::gpu {
namespace {

// Bindings, passes and push constants of fluid_solve.comp: src/kernels/layout.glsl.
constexpr std::uint32_t kBindings = kernels::SD_FLUID_SOLVE_BINDINGS;
constexpr std::uint32_t kWorkgroup = kernels::SD_FLUID_SOLVE_WORKGROUP;
using kernels::FluidSolvePush;

void reserveParticles(GpuFluidSolve& s, std::uint32_t count) {
    if (count <= s.capacity && s.motion.buffer != VK_NULL_HANDLE) {
        return;
    }
    const std::uint32_t n = std::max(count, std::max(2 * s.capacity, kWorkgroup));
    recreateStorageBuffer(*s.device, s.motion, VkDeviceSize{n} * 6 * 4);  // room for 3D
    recreateStorageBuffer(*s.device, s.pseudoImpulse, VkDeviceSize{n} * 4);
    s.capacity = n;
}

void writeSet(GpuFluidSolve& s, const GpuFluidGrid& grid, GpuFluidSetup& setup, const Buffer& wall) {
    std::array<const Buffer*, kBindings> buffers{};
    buffers[kernels::SD_FLUID_SOLVE_BINDING_KEY_START] = &gridKeyStart(grid);
    buffers[kernels::SD_FLUID_SOLVE_BINDING_FIRST] = &setup.first;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_COUNTS] = &setup.counts;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_X] = &setup.x;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_LIST_INDEX] = &setup.listIndex;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_CONSTRAINTS] = &setup.constraints;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_WARM] = &setup.warm;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_WALL] = &wall;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_V] = &setup.v;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_P] = &setup.p;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_PSEUDO_IMPULSE] = &s.pseudoImpulse;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_MOTION] = &s.motion;
    buffers[kernels::SD_FLUID_SOLVE_BINDING_HEADER] = &setup.header;
    writeStorageSet(*s.device, s.passes.sets[0], buffers);
}

/// Cells of colour `colour` (parities x | y << 1 | z << 2): those with
/// the colour's parity along every axis.
std::uint64_t cellsOfColour(glm::ivec3 cells, std::uint32_t colour) {
    std::uint64_t total = 1;
    for (int a = 0; a < 3; ++a) {
        const auto parity = static_cast<std::int64_t>((colour >> a) & 1u);
        total *= static_cast<std::uint64_t>((cells[a] - parity + 1) / 2);
    }
    return total;
}

}  // namespace

GpuFluidSolve::~GpuFluidSolve() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    destroyBuffer(*device, motion);
    destroyBuffer(*device, pseudoImpulse);
    destroyComputePasses(*device, passes);
}

std::unique_ptr<GpuFluidSolve> createGpuFluidSolve(Device& d) {
    auto s = std::make_unique<GpuFluidSolve>();  // destroys what was made if a step throws
    s->device = &d;
    createComputePasses(d, kBindings, sizeof(FluidSolvePush), 1, std::span(shaders::kFluidSolve, shaders::kFluidSolveWords),
                        4, "fluid_solve", s->passes);
    reserveParticles(*s, 1);
    return s;
}

void recordFluidSolve(VkCommandBuffer cmd, GpuFluidSolve& s, const GpuFluidGrid& grid, GpuFluidSetup& setup,
                      const Buffer& wall, const FluidSolveParams& params, GpuFluidContacts* contacts) {
    const std::uint32_t n = setup.count;
    const std::uint32_t dimension = setup.dimension;
    if (n != grid.count) {
        throw Error(fmt::format("gpu fluid solve: the setup holds {} particles, the grid {}", n, grid.count));
    }
    requireBufferBytes(&wall, VkDeviceSize{n} * 16, "gpu fluid solve", "wall");
    const std::uint32_t groups = workgroupsFor(*s.device, n, kWorkgroup, "gpu fluid solve", "particles");
    reserveParticles(s, n);
    s.count = n;
    s.dimension = dimension;
    writeSet(s, grid, setup, wall);

    const glm::ivec3 cells = grid.cells;
    FluidSolvePush push{};
    push.cells = glm::ivec4(cells, static_cast<int>(dimension));
    push.count = n;
    push.split = params.split ? 1u : 0u;
    push.warmFraction = params.warmFraction;
    push.allowanceSlop = kernels::fluidAllowanceSlop(params.restDensity, params.baumgarte, params.h, params.dt);
    push.invH2 = 1.0f / (params.h * params.h);  // as the setup's push: the same bits of g

    computeToCompute(cmd);  // the setup's results
    if (n == 0) {
        return;
    }
    const auto pass = [&](std::uint32_t which, std::uint32_t colour, std::uint32_t passGroups) {
        push.colour = colour;
        dispatchCompute(cmd, s.passes.pipelines[which], s.passes.pipelineLayout, s.passes.sets[0], &push, sizeof(push),
                        passGroups);
        computeToCompute(cmd);
    };
    // One colour's cells: one invocation each.
    const auto colourPasses = [&](std::uint32_t which) {
        for (std::uint32_t colour = 0; colour < (1u << dimension); ++colour) {
            const std::uint64_t colourCells = cellsOfColour(cells, colour);
            if (colourCells == 0) continue;
            pass(which, colour, workgroupsFor(*s.device, colourCells, kWorkgroup, "gpu fluid solve", "cells"));
        }
    };
    pass(kernels::SD_FLUID_SOLVE_PASS_START, 0u, groups);
    colourPasses(kernels::SD_FLUID_SOLVE_PASS_WARM);  // does nothing when the warm start was gathered
    if (contacts != nullptr) recordFluidContactsSolve(cmd, *contacts, s.motion, true);
    for (std::uint32_t it = 0; it < params.iterations; ++it) {
        colourPasses(kernels::SD_FLUID_SOLVE_PASS_SWEEP);
        if (contacts != nullptr) recordFluidContactsSolve(cmd, *contacts, s.motion, false);
    }
    pass(kernels::SD_FLUID_SOLVE_PASS_FINISH, 0u, groups);
    // The results for whoever reads them next: a compute pass or a copy.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

FluidSolveReadback readFluidSolve(GpuFluidSolve& s, GpuFluidSetup& setup) {
    Device& d = *s.device;
    FluidSolveReadback r;
    r.velocity = downloadArray<float>(d, setup.v, std::size_t{s.count} * s.dimension);
    r.motion = downloadArray<float>(d, s.motion, std::size_t{s.count} * 2 * s.dimension);
    r.pressure = downloadArray<float>(d, setup.p, s.count);
    r.pseudoImpulse = downloadArray<float>(d, s.pseudoImpulse, s.count);
    return r;
}

}  // namespace spindrift::gpu
