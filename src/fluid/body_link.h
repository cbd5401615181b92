// What one fluid step sees of the world around it, handed in by the hub
// (src/world/fluid_api.cpp): the worker pool, the world's colliders, the clock,
// the event queue, and the rigid bodies through BodyLink. The solver never
// reaches for the world itself, so src/fluid includes nothing above it.
#pragma once

#include "core/parallel.h"
#include "fluid/fluid_state.h"
#include "kernels/types.glsl"
#include "particles/event_queue.h"

#include <spindrift/bodies.h>

#include <cstdint>
#include <span>

namespace spindrift::fluid {

struct FluidBodyStep;

/// The rigid bodies as a fluid step reaches them, implemented over Box2D by
/// src/coupling (FluidLink). Called on the step's calling thread only, at the
/// step's boundaries (the jets before the substeps, gather before them,
/// exchange after them), never from the worker threads.
class BodyLink {
public:
    /// Where a jet riding `body` is this step (index 0: fixed in the world; a
    /// destroyed body: inactive).
    virtual JetMount jetMount(BodyId body) = 0;
    /// Gives a jet's body the recoil of the particles it emitted.
    virtual void applyRecoil(BodyId body, const JetMount& mount) = 0;
    /// The proxy of the bodies near `f` this step (grown by what they can
    /// travel in dt), or null when there are none (then the fluid ignores
    /// bodies this step). Valid until exchange().
    virtual FluidBodyStep* gather(const FluidState& f, float dt) = 0;
    /// Hands the impulses the step gave the bodies back to them.
    virtual void exchange(const FluidBodyStep& step) = 0;

protected:
    ~BodyLink() = default;
};

/// The world as one fluid step sees it.
struct StepContext {
    WorkerPool& pool;
    std::span<const kernels::ColliderParams> colliders;  // the world's, in creation order
    double time;                                          // s, at the start of the step
    std::uint64_t stepIndex;                              // of the world's step
    EventQueue& events;                                   // strikes on bodies go here
    BodyLink& bodies;
};

}  // namespace spindrift::fluid
