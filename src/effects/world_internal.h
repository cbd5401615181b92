// The CPU backend's world: parameters in kernel layout, sampled fields, the
// emitters' particle arrays, and the worker pool.
#pragma once

#include "core/parallel.h"
#include "effects/emitter_state.h"
#include "effects/event_queue.h"
#include "effects/fields.h"
#include "effects/fires.h"

#include <spindrift/world.h>

#include <memory>
#include <vector>

namespace spindrift {

namespace gpu {
struct GpuWorld;
/// Destroys a GPU world (defined in src/gpu, where GpuWorld is complete).
struct GpuWorldDeleter {
    void operator()(GpuWorld* w) const;
};
}  // namespace gpu

namespace fluid {
struct FluidState;
/// Destroys a fluid (defined in src/fluid, where FluidState is complete).
struct FluidStateDeleter {
    void operator()(FluidState* f) const;
};
}  // namespace fluid

namespace coupling {
struct BodyWorld;
/// Destroys the bodies (defined in src/coupling, where BodyWorld is complete).
struct BodyWorldDeleter {
    void operator()(BodyWorld* b) const;
};
}  // namespace coupling

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
    std::unique_ptr<gpu::GpuWorld, gpu::GpuWorldDeleter> gpu;
    /// Constraint fluids (src/fluid), stepped after the emitters.
    std::vector<std::unique_ptr<fluid::FluidState, fluid::FluidStateDeleter>> fluids;
    /// Rigid bodies (src/coupling), made with the first body; stepped after
    /// the fluids, which exchange impulses with them.
    std::unique_ptr<coupling::BodyWorld, coupling::BodyWorldDeleter> bodies;
};

World& worldFromId(WorldId id);
EmitterState& emitterFromId(World& world, EmitterId id);

/// The births a spawn emitter owes in the step [t0, t0 + dt): bursts first, in
/// definition order, then the rate's. Shared by both backends: birth k of the
/// step gets serial nextSerial + k and age ages()[k] (s, at the end of the step).
struct BirthSchedule {
    struct BurstRun {
        std::uint32_t count;
        float age;
    };
    std::vector<BurstRun> bursts;
    std::uint64_t rateCount = 0;
    double t0 = 0.0, t1 = 0.0, dt = 0.0;
    double rate = 0.0;
    double carry = 0.0;  // the rate's carry before this step

    std::uint64_t total() const;
    /// Age of the rate's j-th birth of the step.
    float rateAge(std::uint64_t j) const;
    std::vector<float> ages() const;
};

/// The schedule of emitter `e`'s step from t0; advances its emission carry.
BirthSchedule scheduleBirths(EmitterState& e, double t0, float dt);

/// Advances every fluid by dt; appends one FluidStepStats per fluid to `stats`.
void stepFluids(World& world, float dt, StepStats& stats);

/// A step's events on the CPU backend, in emitter and slot order: at most
/// `capacity` records, the rest counted.
struct StepEvents {
    std::uint32_t capacity = 0;
    std::vector<kernels::EventRecord> records;
    std::uint64_t dropped = 0;
};

/// Advances emitter `index` by dt; adds its births, deaths and hits to
/// `stats` and its events to `events`.
void stepEmitter(World& world, std::uint32_t index, float dt, StepStats& stats, StepEvents& events);

}  // namespace spindrift
