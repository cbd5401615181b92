// Builders for fluid tests: tanks of plane walls, blocks, and per-run metrics.
#pragma once

#include <spindrift/world.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace spindrift::test {

/// A world owned by the test, destroyed at scope end.
struct FluidWorld {
    explicit FluidWorld(std::uint32_t threads = 1) {
        WorldDef def;
        def.threads = threads;
        id = createWorld(def);
    }
    ~FluidWorld() { destroyWorld(id); }
    FluidWorld(const FluidWorld&) = delete;
    FluidWorld& operator=(const FluidWorld&) = delete;
    WorldId id;
};

inline ColliderDef wall(glm::vec3 point, glm::vec3 normal) {
    ColliderDef c;
    c.kind = ColliderKind::Plane;
    c.position = point;
    c.normal = normal;
    return c;
}

/// Plane walls on every side of [lo, hi] (4 in 2D, 6 in 3D), normals inward.
inline void closedBox(WorldId world, glm::vec3 lo, glm::vec3 hi, std::uint32_t dimension) {
    createCollider(world, wall(lo, {1, 0, 0}));
    createCollider(world, wall(hi, {-1, 0, 0}));
    createCollider(world, wall(lo, {0, 1, 0}));
    createCollider(world, wall(hi, {0, -1, 0}));
    if (dimension == 3) {
        createCollider(world, wall(lo, {0, 0, 1}));
        createCollider(world, wall(hi, {0, 0, -1}));
    }
}

inline glm::dvec3 momentum(const FluidSnapshot& s) {
    glm::dvec3 sum(0.0);
    for (const glm::vec3& v : s.velocity) sum += glm::dvec3(v);
    return sum;
}

inline float maxSpeed(const FluidSnapshot& s) {
    float m = 0.0f;
    for (const glm::vec3& v : s.velocity) m = std::max(m, glm::length(v));
    return m;
}

}  // namespace spindrift::test
