// The constraint fluid's integration on the device (issue 16, fifth slice):
// the CPU's integratePositions (src/fluid/collide.cpp) for a fluid without
// rigid bodies, src/gpu/shaders/fluid_integrate.comp. After the solve, it
// moves the setup's grid-order positions and velocities in place, carries
// each particle's sleep (anchor and time still, read in particle order and
// written in grid order), and reduces the statistics the substep rule reads.
// On a device that rounds to nearest the results are the CPU's bit for bit.
//
// Not yet here: bodies (pushOutOfBodies), and removing the particles whose
// numbers became NaN or infinite (counted and marked; the CPU removes them).
#pragma once

#include "gpu/gpu_fluid_contacts.h"
#include "gpu/gpu_fluid_grid.h"
#include "gpu/gpu_fluid_setup.h"
#include "gpu/gpu_fluid_solve.h"
#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/layout.glsl"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace spindrift::gpu {

/// The integration's settings, as fluid::FluidState holds them.
struct FluidIntegrateParams {
    glm::vec3 gravity{0.0f, -9.81f, 0.0f};  // m/s^2 (its direction gives the depth)
    float dt = 1.0f / 60.0f;                // s, of the substep
    float sleepSpeed = 0.05f;               // m/s (0: never sleeps)
    float sleepTime = 0.5f;                 // s
    float spacing = 0.02f;                  // m
    bool split = true;                      // FluidDef::splitImpulse
};

/// What the integration carries from particle order into grid order: the
/// particles' sleep and, optionally, their creation serials.
struct FluidSleepInputs {
    const Buffer* anchors = nullptr;  // float[dimension n] (m)
    const Buffer* stills = nullptr;   // float[n] (s)
    const Buffer* ids = nullptr;      // uint[n]; null: not carried
};

struct GpuFluidIntegrate {
    Device* device = nullptr;
    ComputePasses passes;  // fluid_integrate.comp, one pass, one set
    Buffer anchors, stills;  // grid order, out
    Buffer ids;              // grid order, out (FluidSleepInputs::ids)
    Buffer stats;            // FluidIntegrateStats
    Buffer partials;         // float per workgroup: its compression sum
    std::uint32_t capacity = 0;
    std::uint32_t count = 0;
    std::uint32_t dimension = 2;

    GpuFluidIntegrate() = default;
    GpuFluidIntegrate(const GpuFluidIntegrate&) = delete;
    GpuFluidIntegrate& operator=(const GpuFluidIntegrate&) = delete;
    ~GpuFluidIntegrate();
};

std::unique_ptr<GpuFluidIntegrate> createGpuFluidIntegrate(Device& d);

/// Records the integration of the particles of `setup`'s last setup, solved
/// by `solve`, against `contacts`' surfaces. Throws Error for sleep buffers
/// too small.
void recordFluidIntegrate(VkCommandBuffer cmd, GpuFluidIntegrate& g, const GpuFluidGrid& grid, GpuFluidSetup& setup,
                          GpuFluidSolve& solve, GpuFluidContacts& contacts, const FluidSleepInputs& sleep,
                          const FluidIntegrateParams& params);

/// The substep's statistics, read back in one transfer (a few hundred
/// bytes): waits for the device. Of the setup (its lists, and the density
/// and closing speeds the constraints were built from) and of the move
/// (speed, depth, box).
struct FluidSubstepReport {
    std::uint32_t listEntries = 0;         // the lists' entries (more than their capacity: some not written)
    std::uint32_t neighbourOverflows = 0;  // neighbours left out (FluidStepStats::neighbourOverflows)
    float maxSpeed = 0.0f;      // m/s, after the move
    float pressedDepth = 0.0f;  // m along gravity, of the particles under pressure
    std::uint32_t nonFinite = 0;
    /// Box of the finite particles after the move (m; z 0 in 2D); lo > hi
    /// when there are none.
    glm::vec3 boxLow{3.0e38f}, boxHigh{-3.0e38f};
    float maxDensityError = 0.0f;   // largest rho / rho0 - 1 at the setup
    float densityErrorSum = 0.0f;   // sum of max(rho / rho0 - 1, 0)
    std::uint32_t neighbours = 0;   // list entries of all particles
    std::array<std::uint32_t, kernels::SD_FLUID_APPROACH_BINS> approach{};  // by fastest closing speed
};
FluidSubstepReport readFluidSubstepReport(GpuFluidSetup& setup, GpuFluidIntegrate& g);

/// The float an order key (fluid.glsl, fluidOrderKey) stands for.
float fromOrderKey(std::uint32_t key);

/// The last integration's statistics and sleep, read back (tests): waits.
struct FluidIntegrateReadback {
    float maxSpeed = 0.0f;      // m/s
    float pressedDepth = 0.0f;  // m
    std::uint32_t nonFinite = 0;
    std::vector<float> anchors, stills;  // grid order
};
FluidIntegrateReadback readFluidIntegrate(GpuFluidSetup& setup, GpuFluidIntegrate& g);

}  // namespace spindrift::gpu
