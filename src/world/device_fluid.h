// A constraint fluid stepped on the device (issue 16): the step driver above
// both the CPU solver's state (src/fluid) and the device's passes (src/gpu),
// so it lives with the hub. The particles stay on the device from step to
// step; each substep records the grid, the gather (gravity added), the
// contacts' find, the constraints, the solve and the integration of
// src/gpu/gpu_fluid_*.h, then carries the grid-order results back as the next
// substep's input (the CPU's particle order is its last grid order too). The
// host reads back a few hundred bytes a substep (gpu_fluid_integrate.h,
// FluidIntegrateReport): the box that places the next grid, and the
// statistics the substep rule of the next step reads (fluid_step.cpp,
// automaticSubsteps, the same function the CPU's step calls).
//
// Not yet here: jets, rigid bodies, the Sequential solver order (each an
// Error at creation), the renderer reading the device's buffers.
#pragma once

#include "fluid/fluid_state.h"

#include <spindrift/fluid.h>

#include <memory>
#include <span>

namespace spindrift {

namespace gpu {
struct Device;
}

struct DeviceFluid;
struct DeviceFluidDeleter {
    void operator()(DeviceFluid* g) const;
};
using DeviceFluidPtr = std::unique_ptr<DeviceFluid, DeviceFluidDeleter>;

/// Uploads `f`'s particles (its arrays as they are: creation, or the CPU's
/// last step) to `d`, which must outlive the result. Throws Error for what
/// the device fluid does not run yet: jets, the Sequential solver.
DeviceFluidPtr createDeviceFluid(gpu::Device& d, const fluid::FluidState& f);

/// One step of `f` on the device, as fluid::stepFluid takes it on the CPU
/// for a fluid without jets and bodies: the automatic substeps from the same
/// rule, the world's fluid colliders (planes, spheres, boxes; at most 32 with
/// the fluid's polygons) and `f`'s polygons. `f`'s particle arrays are not
/// touched (readDeviceFluid fills them); its counters and statistics are.
/// Particles whose numbers stop being finite are removed (counted in
/// FluidStepStats::nonFinite). Pass times are not measured (0).
FluidStepStats stepDeviceFluid(DeviceFluid& g, fluid::FluidState& f,
                               std::span<const kernels::ColliderParams> colliders, FluidId id, float dt);

/// The device's particles into `f`'s arrays (positions, velocities,
/// pressures, densities of the last setup, serials, sleep), in the device's
/// order (the last grid order, as the CPU's). Waits for the device.
void readDeviceFluid(DeviceFluid& g, fluid::FluidState& f);

}  // namespace spindrift
