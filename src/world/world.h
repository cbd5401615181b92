// The hub: struct World, everything one world owns (parameters in kernel
// layout, sampled fields, emitters, fluids, bodies, fires, the worker pool and
// the Vulkan backend's state), and the lookups by public id. Only src/world,
// src/render and the programs above include it; nothing below does
// (cmake/check_includes.cmake), so each part below sees only what it is handed.
#pragma once

#include "core/parallel.h"
#include "particles/emitter_state.h"
#include "particles/event_queue.h"
#include "particles/fields.h"
#include "world/device_fluid.h"
#include "world/fires.h"

#include <spindrift/world.h>

#include <memory>
#include <vector>

namespace spindrift {

namespace gpu {
struct GpuWorld;
}
namespace fluid {
struct FluidState;
}
namespace coupling {
struct BodyWorld;
}

// The world owns its backends' state through these; they are defined in
// world.cpp, the one file that sees every part complete, so this header
// does not pull Vulkan or Box2D into everything that includes it.
struct GpuWorldDeleter {
    void operator()(gpu::GpuWorld* w) const;
};
struct FluidStateDeleter {
    void operator()(fluid::FluidState* f) const;
};
struct BodyWorldDeleter {
    void operator()(coupling::BodyWorld* b) const;
};

struct World {
    explicit World(const WorldDef& d) : def(d), pool(d.threads) {}

    WorldDef def;
    WorkerPool pool;
    std::vector<FlowFieldDef> flowDefs;
    std::vector<ForceDef> forceDefs;
    std::vector<kernels::ForceParams> forces;
    std::vector<ColliderDef> colliderDefs;
    std::vector<kernels::ColliderParams> colliders;
    FieldSet fields;
    std::vector<std::unique_ptr<EmitterState>> emitters;
    EventQueue events;
    /// Fires on bodies, updated after each step from its fluid strikes.
    std::vector<FireState> fires;
    double time = 0.0;
    std::uint64_t stepIndex = 0;
    /// Set when the world runs on Vulkan: then the particle data lives on the
    /// device and EmitterState::particles stays empty.
    std::unique_ptr<gpu::GpuWorld, GpuWorldDeleter> gpu;
    /// Constraint fluids (src/fluid), stepped after the emitters.
    std::vector<std::unique_ptr<fluid::FluidState, FluidStateDeleter>> fluids;
    /// Per fluid, its state on the device when it is solved there
    /// (FluidBackend; null: on the CPU). After `gpu`, so destroyed before it.
    std::vector<DeviceFluidPtr> deviceFluids;
    /// Rigid bodies (src/coupling), made with the first body; stepped after
    /// the fluids, which exchange impulses with them.
    std::unique_ptr<coupling::BodyWorld, BodyWorldDeleter> bodies;
};

World& worldFromId(WorldId id);
EmitterState& emitterFromId(World& world, EmitterId id);

/// The fluid `fluid` of `world` with its particle arrays current (a fluid
/// on the device is read back first); throws Error for an unknown id.
const fluid::FluidState& fluidStateFromId(const World& world, FluidId fluid);
/// The same fluid's settings and state without its particles: a fluid on
/// the device is not read back (its arrays may be out of date).
const fluid::FluidState& fluidSettingsFromId(const World& world, FluidId fluid);
/// The fluid's state on the device, or null where the CPU solves it.
DeviceFluid* deviceFluidFromId(const World& world, FluidId fluid);

/// Advances every fluid by dt; appends one FluidStepStats per fluid to `stats`
/// (fluid_api.cpp).
void stepFluids(World& world, float dt, StepStats& stats);
/// After the bodies' step: particles Box2D's step left inside a body move
/// with it (fluid::carryOutOfMovedBodies).
void settleFluids(World& world);

}  // namespace spindrift
