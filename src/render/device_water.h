// A device fluid's look built from the device's own buffers (issue 16): the
// 2D surface's kernels, the 3D screen-space liquid's spheres or Sprinkle's
// splats written into the renderer's splat instances by a compute pass
// (shaders/fluid_water.comp, the rules of src/kernels/fluid_look.glsl that
// the host's instances use),
// and only the particles that throw a splash this frame read back (48 bytes
// each), so a frame reads no particle arrays back.
#pragma once

#include "gpu/vulkan_pipeline.h"
#include "kernels/render_layout.glsl"

#include <cstdint>
#include <vector>

namespace spindrift {
struct DeviceFluidBuffers;
}

namespace spindrift::render {

/// The pass's pipeline and its own buffers, made at first use.
struct DeviceWater {
    gpu::ComputePasses passes;  // passes.pipelines.empty(): not made yet
    gpu::Buffer planes;         // host-visible: a point and a unit normal per wall plane
    gpu::Buffer splashes;       // the throwers' count and list (FluidSplashThrower)
};

/// One fluid's instances: where they go and how they look.
struct DeviceWaterJob {
    std::uint32_t first = 0;    // the first instance written in `instances`
    std::uint32_t style = kernels::SD_FLUID_WATER_SURFACE;
    bool stretch = false;       // kernels stretched along the velocity
    float radius = 0.0f;        // m, a kernel's or sphere's
    std::vector<glm::vec4> planes;  // wall planes: a point, then the unit normal, each (surface style)
    bool splashes = false;      // list the splash throwers
    std::uint32_t frame = 0;    // the splash RNG's counter
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float chance = 0.0f;        // a thrower's probability this frame
    // The splat style (SD_FLUID_WATER_SPLATS):
    kernels::SplatSteps steps{};
    float invH2 = 0.0f;              // the fluid's 1 / h^2 (1/m^2)
    gpu::Buffer* shown = nullptr;    // the fluid's shown orientations by serial, grown to `serials`
    std::uint32_t serials = 0;       // the fluid's serials so far (FluidState::nextSerial)
};

/// The particles that threw a splash, in particle order; `complete` is
/// false when there were more than SD_FLUID_SPLASH_ROOM (then `throwers`
/// is empty and the caller reads the particles back instead).
struct SplashThrowers {
    std::vector<kernels::FluidSplashThrower> throwers;
    bool complete = true;
};

/// Instances a job writes: the particles, then a slot per particle and plane.
std::uint32_t deviceWaterInstances(std::uint32_t particles, std::size_t planes);

/// Writes the instances of `fluid` into `instances` (which must hold
/// job.first + deviceWaterInstances(...) of them) and returns the splash
/// throwers. One submission, waited for.
SplashThrowers buildDeviceWater(gpu::Device& d, DeviceWater& w, const DeviceFluidBuffers& fluid,
                                gpu::Buffer& instances, const DeviceWaterJob& job);

void destroyDeviceWater(gpu::Device& d, DeviceWater& w);

}  // namespace spindrift::render
