// The constraint fluid's setup on the device (issue 16, second slice): the
// CPU's setupConstraints (src/fluid/neighbours.cpp) for particles that stay
// on the device, after the grid (gpu_fluid_grid.h). The particles are
// gathered into the grid's order, each one's neighbours within h found in the
// CPU's order, the counts' prefix sum gives each list its place in one
// compact array, and the lists, density, bias, effective mass, gathered warm
// start and fastest closing speed are written (src/gpu/shaders/
// fluid_setup.comp). The lists are the CPU's entry for entry; the sums are
// added in another order (tests/gpu/gpu_fluid_setup_test.cpp states by how
// much they may differ).
//
// Not yet here (issue 16's next slices): the colliders' share is an input
// (the `wall` buffer), found by the CPU's contacts; the step's statistics are
// per particle, not yet reduced on the device.
#pragma once

#include "gpu/gpu_fluid_grid.h"
#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/fluid.glsl"
#include "kernels/layout.glsl"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace spindrift::gpu {

/// The fluid's constants of one setup, as fluid::FluidState holds them (the
/// caller, above both src/fluid and src/gpu, converts).
struct FluidSetupParams {
    std::uint32_t readLimit = 1;      // FluidState::subCellReadLimit
    std::uint32_t cap = 0xFFFFFFFFu;  // FluidState::maxNeighbours
    float h = 1.0f;                   // m
    float restDensity = 1.0f;         // kernel-sum units
    float baumgarte = 0.0f;
    float relaxation = 1.0f;          // FluidDef::relaxation
    float dt = 1.0f / 60.0f;          // s, of the substep
    float warmFraction = 0.0f;        // Constraints::warmFraction
    float warmCap = kernels::SD_FLUID_NO_WARM_CAP;  // m/s, fluid::WarmStart::cap: the gather caps the pressures
    /// The closing speeds too (constraint w), as the CPU's setup counts them
    /// in a step's first substep only; 0 in w otherwise.
    bool countClosing = true;
    /// m/s added to every velocity in the gather: gravity x dt, computed as
    /// the CPU's step does (z 0 in 2D).
    glm::vec3 velocityChange{0.0f};
};

/// What the setup reads, in particle order (the grid's input order), except
/// `wall`, which is in grid order: `count` particles.
struct FluidSetupInputs {
    const Buffer* positions = nullptr;   // float[dimension count] (m)
    const Buffer* velocities = nullptr;  // float[dimension count] (m/s)
    const Buffer* pressures = nullptr;   // float[count] (m/s), the last accumulated impulses
    const Buffer* wall = nullptr;        // vec4[count]: the colliders' density, xyz their g sum
    std::uint32_t count = 0;
};

/// Pipelines, outputs and scratch of the setup, for one Device. Buffers grow
/// on demand and never shrink.
struct GpuFluidSetup {
    Device* device = nullptr;
    ComputePasses passes;  // fluid_setup.comp's four, one set
    // Per particle, grid order.
    Buffer x, v, p;        // positions, velocities, pressures
    Buffer counts, first;  // neighbours stored; first list entry
    Buffer constraints;    // vec4: bias (m/s), 1 / A, rho / rho0, fastest closing speed (m/s)
    Buffer warm;           // vec4: xyz the gathered warm start (m/s)
    Buffer tiles;          // per workgroup of the count pass
    Buffer header;         // FluidSetupHeader: entries, overflows
    // The lists: the neighbour (grid order) of each entry; its g = w dir the
    // solve computes again from the positions (fluid.glsl, fluidPairG).
    Buffer listIndex;
    std::uint32_t capacity = 0;      // particles the per-particle buffers hold
    std::uint32_t listCapacity = 0;  // entries the lists hold
    // Of the last recorded setup.
    std::uint32_t count = 0;
    std::uint32_t dimension = 2;
    std::uint32_t groups = 0;  // workgroups of the per-particle passes

    GpuFluidSetup() = default;
    GpuFluidSetup(const GpuFluidSetup&) = delete;
    GpuFluidSetup& operator=(const GpuFluidSetup&) = delete;
    ~GpuFluidSetup();
};

/// Creates the four pipelines.
std::unique_ptr<GpuFluidSetup> createGpuFluidSetup(Device& d);

/// Grows the lists to hold `entries` entries. Only between submissions.
void reserveFluidLists(GpuFluidSetup& s, std::uint32_t entries);

/// Records the setup of the particles of `in`, whose grid `grid` holds (its
/// last recorded grid, of the same positions and count; the dimension and
/// cells are the grid's), into `cmd`. The
/// lists hold at least count x 64 entries (2D) or count x 256 (3D) unless
/// reserved larger; entries past the capacity are counted, not written
/// (readFluidSubstepReport). Waits for earlier compute and transfer writes; its
/// results are visible to later compute and transfer commands. Rewrites the
/// descriptor set, so no other setup of `s` may be pending or recorded in the
/// same command buffer. Throws Error for a count that does not match the
/// grid, or buffers too small.
void recordFluidSetup(VkCommandBuffer cmd, GpuFluidSetup& s, const GpuFluidGrid& grid, const FluidSetupInputs& in,
                      const FluidSetupParams& params);

/// recordFluidSetup in two halves, for a pass between them that reads the
/// gathered particles and writes `wall` (the contacts' find pass,
/// gpu_fluid_contacts.h): the gather into grid order (it binds `in`, wall
/// included), then the constraints (passes count, tiles and setup).
void recordFluidGather(VkCommandBuffer cmd, GpuFluidSetup& s, const GpuFluidGrid& grid, const FluidSetupInputs& in,
                       const FluidSetupParams& params);
void recordFluidConstraints(VkCommandBuffer cmd, GpuFluidSetup& s, const GpuFluidGrid& grid,
                            const FluidSetupParams& params);

/// The last setup's results, read back (tests): waits for the device.
struct FluidSetupReadback {
    std::uint32_t entries = 0;    // list entries needed (more than listCapacity: some not written)
    std::uint32_t overflows = 0;  // neighbours left out (FluidStepStats::neighbourOverflows)
    std::vector<float> x, v, p;   // grid order
    std::vector<std::uint32_t> counts, first;
    std::vector<glm::vec4> constraints, warm;
    std::vector<std::uint32_t> listIndex;
};
FluidSetupReadback readFluidSetup(GpuFluidSetup& s);

}  // namespace spindrift::gpu
