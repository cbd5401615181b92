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
// substepsOfStep, the same function the CPU's step calls).
//
// Rigid bodies are placed by the host each substep (a few hundred bytes a
// shape) and met on the device; the contacts with bodies the fluid moves
// are solved in the CPU's order by one invocation, and the bodies'
// velocities and impulses come back (48 bytes a body) for their end poses
// and Box2D; the carry after Box2D's step runs on the device too.
//
// The renderer draws the liquid from the device's buffers
// (deviceFluidBuffers; src/render/device_water.h); every other host reader
// gets the particles read back (src/world/fluid_api.cpp). Not yet here: the
// Sequential solver order (an Error at creation), the jets' births computed
// on the device (the host emits them from the jets' state alone and uploads
// them).
#pragma once

#include <spindrift/fluid.h>

#include <memory>
#include <span>

namespace spindrift {

namespace gpu {
struct Buffer;
struct Device;
struct GpuFluidContacts;
}
namespace fluid {
struct FluidState;
struct Births;
struct FluidBodyStep;
}
namespace kernels {
struct ColliderParams;
}

struct DeviceFluid;
struct DeviceFluidDeleter {
    void operator()(DeviceFluid* g) const;
};
using DeviceFluidPtr = std::unique_ptr<DeviceFluid, DeviceFluidDeleter>;

/// Uploads `f`'s particles (its arrays as they are: creation, or the CPU's
/// last step) to `d`, which must outlive the result. Throws Error for what
/// the device fluid does not run: the Sequential solver.
DeviceFluidPtr createDeviceFluid(gpu::Device& d, const fluid::FluidState& f);

/// One step of `f` on the device, as fluid::stepFluidBorn takes it on the
/// CPU (the jets' births appended first, appendDeviceBirths), with the
/// bodies of f.bodies (gathered by the caller; static and kinematic ones
/// only: the device does not move bodies yet), whose strikes it adds to
/// their impacts: the automatic substeps from the same
/// rule, the world's fluid colliders (planes, spheres, boxes; at most 32 with
/// the fluid's polygons) and `f`'s polygons. `f`'s particle arrays are not
/// touched (readDeviceFluid fills them); its counters and statistics are.
/// Particles whose numbers stop being finite are removed (counted in
/// FluidStepStats::nonFinite). Pass times are not measured (0).
FluidStepStats stepDeviceFluid(DeviceFluid& g, fluid::FluidState& f,
                               std::span<const kernels::ColliderParams> colliders, FluidId id, float dt);

/// The jets' births of this step (fluid::emitStepJets, which reads no
/// particle) appended to the device's particles: 36 bytes a birth in 2D, 48
/// in 3D, up; nothing down.
void appendDeviceBirths(DeviceFluid& g, const fluid::Births& births);

/// The contacts' passes of `g` (tests read what their last substep left).
gpu::GpuFluidContacts& deviceFluidContacts(DeviceFluid& g);

/// After Box2D's step: the particles inside the shapes of bodies the fluid
/// moves carried with them, on the device (fluid::carryOutOfMovedBodies's
/// rule; `moved`: the bodies at Box2D's poses, gathered from
/// f.bodiesAtEnd). The shapes and moves go up, the particles' box comes
/// back (24 bytes).
void carryDeviceFluid(DeviceFluid& g, const fluid::FluidState& f, fluid::FluidBodyStep& moved);

/// How many particles the device holds now.
std::size_t deviceFluidCount(const DeviceFluid& g);

/// Where the device's particles are now, from the last substep's report
/// (or the last upload and births): whether bodies are near is asked of it
/// without reading the particles back.
struct DeviceFluidExtent {
    std::size_t count = 0;
    glm::vec3 low{0.0f}, high{0.0f};  // m, the particles' box
    float fastest = 0.0f;             // m/s, the largest speed
};
DeviceFluidExtent deviceFluidExtent(const DeviceFluid& g);

/// `f`'s particles uploaded again, in place of the device's (after an edit
/// on the host: a block added, particles removed or poured).
void uploadDeviceFluid(DeviceFluid& g, const fluid::FluidState& f);

/// Whether `f`'s arrays hold the device's particles (false after a step,
/// until readDeviceFluid; true after uploads and appends of them).
bool deviceFluidOnHost(const DeviceFluid& g);

/// The device's particle buffers as a reader on the same device takes them
/// (the renderer, issue 16), valid until the next step or edit: positions
/// and velocities (`dimension` floats a particle), the last setup's
/// constraints (rho / rho0 in z; null when no setup ran since the last
/// upload or births) with its lists, and serials, `count` particles in the
/// device's order.
struct DeviceFluidBuffers {
    const gpu::Buffer* x = nullptr;
    const gpu::Buffer* v = nullptr;
    const gpu::Buffer* constraints = nullptr;
    const gpu::Buffer* ids = nullptr;
    // The last setup's lists (null with its constraints): neighbours a
    // particle, its first entry, each entry's neighbour (particle order).
    const gpu::Buffer* counts = nullptr;
    const gpu::Buffer* first = nullptr;
    const gpu::Buffer* list = nullptr;
    std::uint32_t count = 0;
    std::uint32_t dimension = 2;
};
DeviceFluidBuffers deviceFluidBuffers(const DeviceFluid& g);
/// The device's particles into `f`'s arrays (positions, velocities,
/// pressures, densities of the last setup, serials, sleep), in the device's
/// order (the last grid order, as the CPU's). Waits for the device.
void readDeviceFluid(DeviceFluid& g, fluid::FluidState& f);

}  // namespace spindrift
