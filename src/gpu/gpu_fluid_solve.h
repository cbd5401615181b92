// The constraint fluid's solve on the device (issue 16, third slice): the
// CPU's solveConstraints (src/fluid/solver.cpp) in its Parallel order, on the
// lists and constraints of the device's setup (gpu_fluid_setup.h): the warm
// start, then each iteration one dispatch per colour of cells
// (src/gpu/shaders/fluid_solve.comp). On a device that rounds to nearest the
// velocities and pressures are the CPU's bit for bit, given the same setup.
//
// Not yet here (issue 16's next slices): the contacts with bodies between the
// sweeps, and the Sequential order.
#pragma once

#include "gpu/gpu_fluid_contacts.h"
#include "gpu/gpu_fluid_grid.h"
#include "gpu/gpu_fluid_setup.h"
#include "gpu/vulkan_buffer.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace spindrift::gpu {

/// The solve's settings, as fluid::FluidState holds them.
struct FluidSolveParams {
    std::uint32_t iterations = 4;  // FluidDef::iterations
    bool split = true;             // FluidDef::splitImpulse
    float warmFraction = 0.0f;     // Constraints::warmFraction
    float restDensity = 1.0f;      // kernel-sum units
    float baumgarte = 0.0f;
    float h = 1.0f;                // m
    float dt = 1.0f / 60.0f;       // s, of the substep
};

/// Pipelines and scratch of the solve, for one Device. Scratch grows on
/// demand and never shrinks.
struct GpuFluidSolve {
    Device* device = nullptr;
    ComputePasses passes;  // fluid_solve.comp's four, one set
    Buffer motion;         // per particle (grid order): velocity, pseudo velocity (m/s)
    Buffer pseudoImpulse;  // per particle: accumulated pseudo impulse (m/s)
    std::uint32_t capacity = 0;
    // Of the last recorded solve.
    std::uint32_t count = 0;
    std::uint32_t dimension = 2;

    GpuFluidSolve() = default;
    GpuFluidSolve(const GpuFluidSolve&) = delete;
    GpuFluidSolve& operator=(const GpuFluidSolve&) = delete;
    ~GpuFluidSolve();
};

/// Creates the four pipelines.
std::unique_ptr<GpuFluidSolve> createGpuFluidSolve(Device& d);

/// Records the solve of the particles of `setup`'s last recorded setup (on
/// `grid`'s last grid) into `cmd`: the velocities in setup.v become the
/// solved ones, the pressures in setup.p the accumulated impulses. `wall` is
/// the setup's input of the colliders' share. Waits for earlier compute
/// writes; its results are visible to later compute and transfer commands.
/// Rewrites the descriptor set: no other solve of `s` may be pending.
/// With `contacts` (its find recorded before the setup's constraints), the
/// contacts are solved after the warm start and after every sweep, as the
/// CPU's solveConstraints does (slide 51).
void recordFluidSolve(VkCommandBuffer cmd, GpuFluidSolve& s, const GpuFluidGrid& grid, GpuFluidSetup& setup,
                      const Buffer& wall, const FluidSolveParams& params, GpuFluidContacts* contacts = nullptr);

/// The last solve's results, read back (tests): waits for the device.
struct FluidSolveReadback {
    std::vector<float> velocity;       // dimension per particle (m/s), grid order
    std::vector<float> motion;         // 2 dimension per particle: velocity, pseudo velocity
    std::vector<float> pressure;       // m/s
    std::vector<float> pseudoImpulse;  // m/s
};
FluidSolveReadback readFluidSolve(GpuFluidSolve& s, GpuFluidSetup& setup);

}  // namespace spindrift::gpu
