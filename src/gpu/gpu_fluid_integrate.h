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

#include <glm/glm.hpp>

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

/// The particles' sleep in particle order, as the integration reads it.
struct FluidSleepInputs {
    const Buffer* anchors = nullptr;  // float[dimension n] (m)
    const Buffer* stills = nullptr;   // float[n] (s)
};

struct GpuFluidIntegrate {
    Device* device = nullptr;
    ComputePasses passes;  // fluid_integrate.comp, one pass, one set
    Buffer anchors, stills;  // grid order, out
    Buffer stats;            // FluidIntegrateStats
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

/// The last integration's statistics and sleep, read back (tests): waits.
struct FluidIntegrateReadback {
    float maxSpeed = 0.0f;      // m/s
    float pressedDepth = 0.0f;  // m
    std::uint32_t nonFinite = 0;
    std::vector<float> anchors, stills;  // grid order
};
FluidIntegrateReadback readFluidIntegrate(GpuFluidIntegrate& g);

}  // namespace spindrift::gpu
