// The carry after Box2D's step on the device (issue 16): the CPU's
// carryOutOfMovedBodies (src/fluid/body_contacts.cpp) for particles that
// stay on the device, src/gpu/shaders/fluid_carry.comp. Box2D moved the
// bodies the fluid moves on from where the fluid's copies ended its step; a
// particle inside one of their shapes goes with it. The host uploads the
// shapes at Box2D's poses and each body's move (a few hundred bytes a
// shape) and reads back the particles' box (24 bytes), not the particles.
#pragma once

#include "gpu/gpu_fluid_contacts.h"
#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/carry_layout.glsl"
#include "kernels/fluid.glsl"

#include <glm/glm.hpp>

#include <memory>
#include <span>

namespace spindrift::gpu {

struct GpuFluidCarry {
    Device* device = nullptr;
    ComputePasses passes;  // fluid_carry.comp, one pass, one set
    Buffer shapes, boxes, bodies, box;

    GpuFluidCarry() = default;
    GpuFluidCarry(const GpuFluidCarry&) = delete;
    GpuFluidCarry& operator=(const GpuFluidCarry&) = delete;
    ~GpuFluidCarry();
};

std::unique_ptr<GpuFluidCarry> createGpuFluidCarry(Device& d);

/// What the carry reads: the shapes at Box2D's poses (pad0 1: the body is
/// still), each shape's bounds, each body's move.
struct FluidCarryInputs {
    std::span<const kernels::FluidBodyShape> shapes;
    std::span<const glm::vec4> boxes;  // lo.xy, hi.xy (m)
    std::span<const kernels::FluidBodyCarry> bodies;
};

/// Carries the `count` 2D particles of `x` (particle order), against the
/// fluid's colliders and polygons in `surfaces`; returns their box after it
/// (low.xy, high.xy; lo > hi when none is finite). Submits and waits.
glm::vec4 carryOnDevice(GpuFluidCarry& c, const GpuFluidContacts& surfaces, Buffer& x, std::uint32_t count,
                        const FluidCarryInputs& inputs);

}  // namespace spindrift::gpu
