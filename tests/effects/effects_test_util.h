// Small builders for physics tests: a world with one emitter that fires a
// single particle (or a few) from a point at t = 0, so closed forms apply.
#pragma once

#include <spindrift/world.h>

#include <vector>

namespace spindrift::test {

struct OneShot {
    glm::vec3 start{0.0f};
    glm::vec3 velocity{0.0f};
    std::uint32_t count = 1;
    float lifetime = 1000.0f;
    float mass = 1.0f;
    float size = 0.1f;
    Integrator integrator = Integrator::SemiImplicitEuler;
};

inline EmitterDef oneShotEmitter(const OneShot& o) {
    EmitterDef e;
    e.name = "probe";
    e.lifecycle = Lifecycle::Spawn;
    e.capacity = o.count;
    e.rate = 0.0f;
    e.bursts = {{0.0f, o.count}};
    e.shape.kind = SpawnShapeKind::Point;
    e.shape.center = o.start;
    float speed = glm::length(o.velocity);
    e.shape.direction = speed > 0.0f ? o.velocity / speed : glm::vec3(0.0f, 1.0f, 0.0f);
    e.speed = {speed, speed};
    e.lifetime = {o.lifetime, o.lifetime};
    e.size = {o.size, o.size};
    e.mass = o.mass;
    e.integrator = o.integrator;
    return e;
}

/// A world owned by the test, destroyed at scope end.
struct ScopedWorld {
    explicit ScopedWorld(std::uint32_t threads = 1, std::uint32_t seed = 7, Backend backend = Backend::Cpu,
                         std::uint32_t framesInFlight = 1, std::uint32_t eventCapacity = WorldDef{}.eventCapacity) {
        WorldDef def;
        def.eventCapacity = eventCapacity;
        def.backend = backend;
        def.threads = threads;
        def.seed = seed;
        def.framesInFlight = framesInFlight;
        id = createWorld(def);
    }
    ~ScopedWorld() { destroyWorld(id); }
    ScopedWorld(const ScopedWorld&) = delete;
    ScopedWorld& operator=(const ScopedWorld&) = delete;
    WorldId id;
};

inline ForceDef gravity(glm::vec3 g) {
    ForceDef f;
    f.kind = ForceKind::Gravity;
    f.vector = g;
    return f;
}

inline ColliderDef groundPlane(float resilience, float friction = 0.0f) {
    ColliderDef c;
    c.kind = ColliderKind::Plane;
    c.position = glm::vec3(0.0f);
    c.normal = glm::vec3(0.0f, 1.0f, 0.0f);
    c.resilience = resilience;
    c.friction = friction;
    return c;
}

/// Steps `steps` times and returns the single probe particle's state.
inline ParticleSnapshot run(WorldId world, EmitterId emitter, float dt, int steps) {
    for (int i = 0; i < steps; ++i) {
        stepWorld(world, dt);
    }
    return readParticles(world, emitter);
}

}  // namespace spindrift::test
