// The hub: world lifetime, object creation (Box2D v3 style: Def structs in,
// small ids out; ids index 1-based arrays in creation order) and stepWorld, a
// named list of stages (docs/design.md, "A step of the world").
#include "world/world.h"

#include "core/field_rules.h"
#include "coupling/body_world.h"
#include "effects/emitter_step.h"
#include "fluid/fluid_state.h"
#include "gpu/gpu_world.h"
#include "kernels/trail.glsl"
#include "particles/params.h"
#include "particles/slots.h"

#include <fmt/format.h>

#include <chrono>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <mutex>
#include <optional>
#include <utility>

namespace spindrift {
namespace {

struct WorldSlot {
    std::unique_ptr<World> world;
    std::uint32_t generation = 0;
};

std::mutex gWorldsMutex;
std::vector<WorldSlot> gWorlds;

void initialiseSlots(EmitterState& s) {
    const std::uint32_t n = s.def.capacity;
    s.particles.resize(n);
    ParticleArrays& p = s.particles;
    p.trail.assign(std::size_t{n} * s.def.trail.points, glm::vec3(0.0f));
    if (s.def.lifecycle == Lifecycle::Recycle) {
        // Slot i is first born at i / n of a mean lifetime: an even stream from
        // the start, as the GPU particle talk's fixed slots.
        float meanLife = 0.5f * (s.def.lifetime.min + s.def.lifetime.max);
        for (std::uint32_t i = 0; i < n; ++i) {
            // Strictly negative, also for slot 0: unborn until the first step.
            p.age[i] = -meanLife * (static_cast<float>(i) / static_cast<float>(n)) - FLT_MIN;
            p.birth[i] = i;
        }
    } else {
        std::fill(p.age.begin(), p.age.end(), kernels::SD_DEAD_AGE);
        s.freeSlots.resize(n);
        for (std::uint32_t i = 0; i < n; ++i) {
            s.freeSlots[i] = n - 1 - i;  // slot 0 at the back: used first
        }
    }
}

std::uint32_t maskOf(const auto& ids, std::size_t total, const char* what, const std::string& emitter) {
    if (ids.empty()) {
        return total >= 32 ? 0xFFFFFFFFu : ((1u << total) - 1u);
    }
    std::uint32_t mask = 0;
    for (auto id : ids) {
        if (id.index == 0 || id.index > total) {
            throw Error(fmt::format("emitter '{}': {} id {} does not exist in this world", emitter, what, id.index));
        }
        mask |= 1u << (id.index - 1);
    }
    return mask;
}

}  // namespace

void GpuWorldDeleter::operator()(gpu::GpuWorld* w) const {
    if (w != nullptr) {
        gpu::destroyGpuWorld(*w);
        delete w;
    }
}

void FluidStateDeleter::operator()(fluid::FluidState* f) const { delete f; }

void BodyWorldDeleter::operator()(coupling::BodyWorld* b) const { delete b; }

void ParticleArrays::resize(std::size_t n) {
    position.resize(n);
    velocity.resize(n);
    age.resize(n);
    lifetime.resize(n, 1.0f);
    rotation.resize(n);
    angularVelocity.resize(n);
    birth.resize(n);
}

World& worldFromId(WorldId id) {
    std::lock_guard lock(gWorldsMutex);
    if (id.index == 0 || id.index > gWorlds.size() || !gWorlds[id.index - 1].world ||
        gWorlds[id.index - 1].generation != id.generation) {
        throw Error(fmt::format("world id {}:{} is not a live world", id.index, id.generation));
    }
    return *gWorlds[id.index - 1].world;
}

EmitterState& emitterFromId(World& world, EmitterId id) {
    if (id.index == 0 || id.index > world.emitters.size()) {
        throw Error(fmt::format("emitter id {} does not exist in this world", id.index));
    }
    return *world.emitters[id.index - 1];
}

WorldId createWorld(const WorldDef& def) {
    if (!(std::abs(def.bodyGravity.x) <= kMaxBodyGravity && std::abs(def.bodyGravity.y) <= kMaxBodyGravity)) {
        throw Error(fmt::format("WorldDef::bodyGravity must be finite, each component within {} m/s^2",
                                kMaxBodyGravity));
    }
    if (def.framesInFlight < 1 || def.framesInFlight > gpu::kMaxFramesInFlight) {
        throw Error(fmt::format("WorldDef::framesInFlight must be 1 to {}, got {}", gpu::kMaxFramesInFlight,
                                def.framesInFlight));
    }
    auto world = std::make_unique<World>(def);
    world->events.capacity = def.eventCapacity;
    // Auto takes a real GPU: discrete or integrated, never lavapipe, which
    // runs the shaders on the CPU cores slower than the CPU backend
    // (docs/performance.md).
    const bool vulkan = def.backend == Backend::Vulkan ||
                        (def.backend == Backend::Auto && gpu::hardwareGpuAvailable());
    if (vulkan) {
        world->gpu.reset(gpu::createGpuWorld(def.framesInFlight, def.eventCapacity).release());
    }
    std::lock_guard lock(gWorldsMutex);
    for (std::size_t i = 0; i < gWorlds.size(); ++i) {
        if (!gWorlds[i].world) {
            gWorlds[i].world = std::move(world);
            return {static_cast<std::uint32_t>(i + 1), ++gWorlds[i].generation};
        }
    }
    gWorlds.push_back({std::move(world), 1});
    return {static_cast<std::uint32_t>(gWorlds.size()), 1};
}

void destroyWorld(WorldId id) {
    worldFromId(id);  // validates
    std::lock_guard lock(gWorldsMutex);
    gWorlds[id.index - 1].world.reset();
}

FlowFieldId createFlowField(WorldId id, const FlowFieldDef& def) {
    World& w = worldFromId(id);
    validateFlowFieldDef(def);
    FlowGrid grid{def.nx, def.ny, def.nz, def.velocities};
    if (w.gpu) {
        gpu::addFlowField(*w.gpu, grid, def.name);
    }
    w.flowDefs.push_back(def);
    w.fields.flows.push_back(std::move(grid));
    return {static_cast<std::uint32_t>(w.flowDefs.size())};
}

ForceId createForce(WorldId id, const ForceDef& def) {
    World& w = worldFromId(id);
    if (w.forces.size() >= kMaxForces) {
        throw Error(fmt::format("force '{}': a world holds at most {} forces", def.name, kMaxForces));
    }
    const FlowFieldDef* flow = nullptr;
    std::uint32_t flowIndex = 0;
    if (def.kind == ForceKind::FlowField) {
        if (def.flowField.index == 0 || def.flowField.index > w.flowDefs.size()) {
            throw Error(fmt::format("force '{}': flow field id {} does not exist", def.name, def.flowField.index));
        }
        flowIndex = def.flowField.index - 1;
        flow = &w.flowDefs[flowIndex];
    }
    w.forces.push_back(makeForceParams(def, flow, flowIndex));
    w.forceDefs.push_back(def);
    if (w.gpu) {
        gpu::uploadForces(*w.gpu, w.forces);
    }
    return {static_cast<std::uint32_t>(w.forces.size())};
}

ColliderId createCollider(WorldId id, const ColliderDef& def) {
    World& w = worldFromId(id);
    if (w.colliders.size() >= kMaxColliders) {
        throw Error(fmt::format("collider '{}': a world holds at most {} colliders", def.name, kMaxColliders));
    }
    std::uint32_t dataIndex = 0;
    kernels::ColliderParams params;
    if (def.kind == ColliderKind::Terrain) {
        params = makeColliderParams(def, static_cast<std::uint32_t>(w.fields.heights.size()));
        HeightMap map{def.terrainNx, def.terrainNz, def.heights};
        if (w.gpu) {
            gpu::addHeightMap(*w.gpu, map, def.name);
        }
        w.fields.heights.push_back(std::move(map));
    } else if (def.kind == ColliderKind::CubeMap) {
        params = makeColliderParams(def, static_cast<std::uint32_t>(w.fields.cubes.size()));
        DepthCubeMap cube = makeDepthCubeMap(def.cubeResolution, def.cubeDepths);
        if (w.gpu) {
            gpu::addCubeMap(*w.gpu, cube, def.name);
        }
        w.fields.cubes.push_back(std::move(cube));
    } else {
        params = makeColliderParams(def, dataIndex);
    }
    w.colliders.push_back(params);
    w.colliderDefs.push_back(def);
    if (w.gpu) {
        gpu::uploadColliders(*w.gpu, w.colliders);
    }
    return {static_cast<std::uint32_t>(w.colliders.size())};
}

namespace {

// Where an emitter riding a body is now: its mount (shape centre and
// direction in the body's frame) turned and moved by the body's pose, and
// the share of the body's velocity at that centre every birth inherits
// (m/s; v + omega x r about the centre of mass).
struct Carried {
    EmitterDef def;
    glm::vec2 velocity{0.0f};
};

Carried carriedBy(const fluid::JetMount& body, const EmitterState& e) {
    const float c = std::cos(body.angle), s = std::sin(body.angle);
    auto turn = [&](glm::vec2 v) { return glm::vec2(c * v.x - s * v.y, s * v.x + c * v.y); };
    Carried out{e.def, glm::vec2(0.0f)};
    const glm::vec2 centre = body.origin + turn(glm::vec2(e.mountCentre));
    out.def.shape.center = glm::vec3(centre, e.mountCentre.z);
    out.def.shape.direction = glm::vec3(turn(glm::vec2(e.mountDirection)), e.mountDirection.z);
    const glm::vec2 r = centre - body.centre;
    out.velocity = (body.velocity + body.angularVelocity * glm::vec2(-r.y, r.x)) * e.def.inheritVelocity;
    return out;
}

}  // namespace

EmitterId createEmitter(WorldId id, const EmitterDef& def) {
    World& w = worldFromId(id);
    auto state = std::make_unique<EmitterState>();
    state->def = def;
    auto index = static_cast<std::uint32_t>(w.emitters.size());
    std::uint32_t forceMask = maskOf(def.forces, w.forces.size(), "force", def.name);
    std::uint32_t colliderMask = maskOf(def.collision.colliders, w.colliders.size(), "collider", def.name);
    glm::vec2 carried(0.0f);
    if (def.body.index != 0) {
        validateEmitterDef(def);  // a stateless emitter on a body is refused at its key first
        if (!w.bodies) {
            throw Error(fmt::format("emitter '{}' rides body id {}, but the world has no bodies", def.name,
                                    def.body.index));
        }
        coupling::bodyFromId(*w.bodies, def.body);  // throws for a body the world does not have
        state->mountCentre = def.shape.center;
        state->mountDirection = def.shape.direction;
        const Carried placed = carriedBy(coupling::jetMount(w.bodies.get(), def.body), *state);
        state->def = placed.def;
        carried = placed.velocity;
    }
    if (def.spawnOn.enabled()) {
        validateEmitterDef(def);  // its own rules first (lifecycle, count), at their keys
        const std::uint32_t parent = def.spawnOn.parent.index;
        if (parent > w.emitters.size()) {
            throw FieldError(objectLabel("emitter", def.name), "spawn_on.parent",
                             fmt::format("expected an emitter created before this one (ids 1 to {}), got {}",
                                         w.emitters.size(), parent));
        }
        if (w.emitters[parent - 1]->def.stateless) {
            throw FieldError(objectLabel("emitter", def.name), "spawn_on.parent",
                             fmt::format("emitter '{}' is stateless: a closed form has no particle events to "
                                         "follow; expected a state-preserving emitter",
                                         w.emitters[parent - 1]->def.name));
        }
    }
    state->params = makeEmitterParams(state->def, w.def.seed, index, forceMask, colliderMask);
    state->params.carriedVelocityX = carried.x;
    state->params.carriedVelocityY = carried.y;
    if (!def.stateless) {
        initialiseSlots(*state);
    }
    if (def.spawnOn.enabled()) {
        // The parent keeps this kind's requests from now on (on the device,
        // in a buffer the child's passes bind).
        EmitterState& parent = *w.emitters[def.spawnOn.parent.index - 1];
        const auto kind = static_cast<std::uint32_t>(def.spawnOn.event);
        parent.requestKinds |= 1u << kind;
        if (w.gpu) {
            gpu::followEvents(*w.gpu, def.spawnOn.parent.index - 1, kind);
        }
    }
    if (w.gpu) {
        // The same initial slots as the CPU backend, uploaded once; the device
        // holds them from now on.
        gpu::addEmitter(*w.gpu, *state);
        state->particles = ParticleArrays{};
    }
    w.emitters.push_back(std::move(state));
    return {index + 1};
}

namespace {

// Stats with one zero hit count per collider, for the steps' counts to add to.
StepStats emptyStats(const World& w) {
    StepStats stats;
    stats.colliderHits.resize(w.colliders.size());
    for (std::size_t i = 0; i < w.colliders.size(); ++i) {
        stats.colliderHits[i].collider = {static_cast<std::uint32_t>(i + 1)};
    }
    return stats;
}

// Alive (after the counted steps) and the collision total.
void addTotals(const World& w, StepStats& stats) {
    for (const auto& emitter : w.emitters) {
        stats.alive += emitter->alive;
    }
    for (const ColliderStepStats& c : stats.colliderHits) {
        stats.collisions += c.hits;
    }
}

}  // namespace

namespace {

// Re-derives the kernel parameters from `def` (validating it) before
// anything changes; the masks stay those computed at creation.
// carried: the velocity share births inherit from the body the emitter rides
// (m/s; carryEmitters); unset keeps the last one.
void changeEmitter(World& w, EmitterId id, const EmitterDef& def, std::optional<glm::vec2> carried = std::nullopt) {
    EmitterState& e = emitterFromId(w, id);
    if (e.def.stateless) {
        throw Error(fmt::format("emitter '{}' is stateless: its closed form covers all time and cannot change "
                                "during a run",
                                e.def.name));
    }
    const std::uint32_t index = id.index - 1;
    kernels::EmitterParams params =
        makeEmitterParams(def, w.def.seed, index, e.params.forceMask, e.params.colliderMask);
    // Set by the body an emitter rides on, not by its def (carryEmitters).
    params.carriedVelocityX = carried ? carried->x : e.params.carriedVelocityX;
    params.carriedVelocityY = carried ? carried->y : e.params.carriedVelocityY;
    // The device copy is rewritten (after waiting for the steps in flight)
    // only when the kernel parameters change: a rate lives in the host's
    // birth schedule, and fires set rates and positions every step.
    // EmitterParams is 4-byte fields without padding (std430, checked in
    // src/kernels/types.glsl), so bytes compare as values.
    if (w.gpu && std::memcmp(&params, &e.params, sizeof(params)) != 0) {
        gpu::setEmitterParams(*w.gpu, index, params);
    }
    e.def = def;
    e.params = params;
}

}  // namespace

void setEmitterRate(WorldId id, EmitterId emitter, float rate) {
    World& w = worldFromId(id);
    EmitterDef def = emitterFromId(w, emitter).def;
    def.rate = rate;
    changeEmitter(w, emitter, def);
}

void setEmitterSpeed(WorldId id, EmitterId emitter, FloatRange speed) {
    World& w = worldFromId(id);
    EmitterDef def = emitterFromId(w, emitter).def;
    def.speed = speed;
    changeEmitter(w, emitter, def);
}

void setEmitterPosition(WorldId id, EmitterId emitter, glm::vec3 centre) {
    World& w = worldFromId(id);
    EmitterState& e = emitterFromId(w, emitter);
    if (e.def.body.index != 0) {
        if (!std::isfinite(centre.x) || !std::isfinite(centre.y) || !std::isfinite(centre.z)) {
            throw Error(fmt::format("setEmitterPosition: emitter '{}': the centre must be finite", e.def.name));
        }
        e.mountCentre = centre;  // in the body's frame; placed at the next step
        return;
    }
    EmitterDef def = e.def;
    def.shape.center = centre;
    changeEmitter(w, emitter, def);
}

namespace {

// Stage "carry": emitters riding bodies follow them (EmitterDef::body), placed
// from the bodies' poses and velocities at the start of the step. A destroyed
// body leaves its emitters where they were, with nothing more to inherit.
void carryEmitters(World& w) {
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        EmitterState& e = *w.emitters[i];
        if (e.def.body.index == 0) continue;
        const fluid::JetMount body = coupling::jetMount(w.bodies.get(), e.def.body);
        const Carried placed = body.active ? carriedBy(body, e) : Carried{e.def, glm::vec2(0.0f)};
        changeEmitter(w, EmitterId{static_cast<std::uint32_t>(i + 1)}, placed.def, placed.velocity);
    }
}

// Stage "emitters": every state-preserving emitter's step, on the device
// (one submission) or on the CPU backend, emitter by emitter.
void stepEmitters(World& w, float dt, StepStats& stats) {
    for (const std::unique_ptr<EmitterState>& e : w.emitters) {
        e->trailHead = kernels::nextTrailHead(e->trailHead, e->def.trail.points);
    }
    if (w.gpu) {
        gpu::stepEmitters(*w.gpu, w.emitters, w.time, dt, w.stepIndex, stats, w.events);
        return;
    }
    const kernels::KernelContext ctx{w.forces.data(), static_cast<std::uint32_t>(w.forces.size()),
                                     w.colliders.data(), static_cast<std::uint32_t>(w.colliders.size()),
                                     &w.fields, static_cast<float>(w.time)};
    StepEvents events{w.events.capacity, {}, 0};
    for (std::uint32_t i = 0; i < w.emitters.size(); ++i) {
        EmitterState& e = *w.emitters[i];
        if (!e.def.stateless) {
            // A sub-emitter's parent was created, and so is stepped, before it.
            const EmitterState* parent =
                e.def.spawnOn.enabled() ? w.emitters[e.def.spawnOn.parent.index - 1].get() : nullptr;
            stepEmitter(w.pool, ctx, e, i, w.stepIndex, w.time, dt, parent, stats, events);
        }
    }
    w.events.addStep(w.stepIndex, events.records, events.dropped);
    stats.countedSteps = 1;
    stats.lastCountedStep = w.stepIndex;
}

}  // namespace

StepStats stepWorld(WorldId id, float dt) {
    World& w = worldFromId(id);
    if (!(dt >= static_cast<float>(kMinStep) && dt <= static_cast<float>(kMaxStep))) {
        throw Error(fmt::format("stepWorld: dt must be {} to {} s, got {}", kMinStep, kMaxStep, dt));
    }
    auto start = std::chrono::steady_clock::now();
    StepStats stats = emptyStats(w);
    stats.step = w.stepIndex;
    w.events.beginStep();

    // 1. Emitters: births, forces, integration, collisions, deaths, events.
    carryEmitters(w);
    stepEmitters(w, dt, stats);

    // 2. Body gravity: dynamic bodies get this step's gravity before the
    // fluids, which exchange impulses with them during their solve, so the
    // water's pressure answers this step's weight.
    if (w.bodies) coupling::beginBodyStep(*w.bodies, dt);

    // 3. Fluids: each constraint fluid's step (src/fluid), bodies reached
    // through coupling's link; strikes on bodies become collision events.
    stepFluids(w, dt, stats);

    // 4. Bodies: Box2D steps them once by dt with what the water left them.
    if (w.bodies) {
        const auto bodiesStart = std::chrono::steady_clock::now();
        stats.frozenBodies = coupling::stepBodies(*w.bodies, dt);
        stats.bodiesMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - bodiesStart).count();
        // The fluids solved against copies of the bodies that see joints
        // but not the bodies' contacts with each other or Box2D's position
        // correction, so Box2D may leave a body where its copy did not go:
        // a particle left inside moves with the body back to the side it
        // was on.
        settleFluids(w);
    }

    // 5. Fires: this step's strikes douse them; their emitters follow.
    updateFires(w, id, dt);

    addTotals(w, stats);
    w.time += dt;
    w.stepIndex += 1;
    stats.time = w.time;
    stats.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return stats;
}

EventBatch takeEvents(WorldId id) {
    World& w = worldFromId(id);
    return std::exchange(w.events.batch, EventBatch{});
}

StepStats flushWorld(WorldId id) {
    World& w = worldFromId(id);
    StepStats stats = emptyStats(w);
    stats.step = w.stepIndex == 0 ? 0 : w.stepIndex - 1;
    stats.time = w.time;
    if (w.gpu) {
        gpu::collectAll(*w.gpu, w.emitters, stats, w.events);
    }
    addTotals(w, stats);
    return stats;
}

TransferStats transferStats(WorldId id) {
    World& w = worldFromId(id);
    return w.gpu ? gpu::transferStats(*w.gpu) : TransferStats{};
}

double worldTime(WorldId id) { return worldFromId(id).time; }

std::uint32_t emitterCount(WorldId id) { return static_cast<std::uint32_t>(worldFromId(id).emitters.size()); }

std::uint32_t colliderCount(WorldId id) { return static_cast<std::uint32_t>(worldFromId(id).colliders.size()); }

const EmitterDef& emitterDef(WorldId id, EmitterId emitter) {
    World& w = worldFromId(id);
    return emitterFromId(w, emitter).def;
}

ParticleSnapshot readParticles(WorldId id, EmitterId emitterId) {
    World& w = worldFromId(id);
    EmitterState& e = emitterFromId(w, emitterId);
    if (e.def.stateless) {
        return evaluateStateless(e.def, w.def.seed, emitterId.index - 1, static_cast<float>(w.time));
    }
    ParticleSnapshot s;
    ParticleArrays fromDevice;
    if (w.gpu) {
        fromDevice = gpu::readSlots(*w.gpu, emitterId.index - 1, e.params);
    }
    const ParticleArrays& p = w.gpu ? fromDevice : e.particles;
    const std::uint32_t points = e.def.trail.points;
    s.trailPoints = points;
    for (std::uint32_t i = 0; i < e.def.capacity; ++i) {
        if (p.age[i] < 0.0f) {
            continue;
        }
        s.position.push_back(p.position[i]);
        s.velocity.push_back(p.velocity[i]);
        s.age.push_back(p.age[i]);
        s.lifetime.push_back(p.lifetime[i]);
        const kernels::Particle look = loadParticle(p, e.params, i);
        s.size.push_back(look.size);
        s.rotation.push_back(p.rotation[i]);
        s.color.push_back(look.color);
        s.birth.push_back(p.birth[i]);
        s.slot.push_back(i);
        for (std::uint32_t k = 0; k < points; ++k) {
            s.trail.push_back(p.trail[kernels::trailPointIndex(i, k, e.trailHead, points)]);
        }
    }
    return s;
}

}  // namespace spindrift
