// The CPU backend's world: parameters in kernel layout, sampled fields, the
// emitters' particle arrays, and the worker pool.
#pragma once

#include "core/parallel.h"
#include "effects/emitter_state.h"
#include "effects/fields.h"

#include <spindrift/world.h>

#include <memory>
#include <vector>

namespace spindrift {

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
    double time = 0.0;
    std::uint64_t stepIndex = 0;
};

World& worldFromId(WorldId id);
EmitterState& emitterFromId(World& world, EmitterId id);

/// Advances one emitter by dt; adds its births, deaths and hits to `stats`.
void stepEmitter(World& world, EmitterState& emitter, float dt, StepStats& stats);

}  // namespace spindrift
