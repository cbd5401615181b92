// Builders for coupling tests: a world, a tank of static boxes, crates, and
// the depth of a point inside a body's polygon.
#pragma once

#include <spindrift/world.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace spindrift::test {

/// Box2D rounds every polygon by its polygon radius (1 cm) and lets rounded
/// shapes overlap by its linear slop (5 mm) at rest, so two bodies' polygons
/// rest 2 x 1 cm - 5 mm = 1.5 cm apart (m). The fluid sees the exact shapes.
constexpr float kBodyGap = 0.015f;

/// A world owned by the test, destroyed at scope end.
struct BodyTestWorld {
    explicit BodyTestWorld(std::uint32_t threads = 1, glm::vec2 bodyGravity = {0.0f, -9.81f}) {
        WorldDef def;
        def.threads = threads;
        def.bodyGravity = bodyGravity;
        id = createWorld(def);
    }
    ~BodyTestWorld() { destroyWorld(id); }
    BodyTestWorld(const BodyTestWorld&) = delete;
    BodyTestWorld& operator=(const BodyTestWorld&) = delete;
    WorldId id;
};

/// An open tank [0, width] x [0, height] of static boxes 0.1 m thick (floor
/// and two walls), which both the water and the bodies feel.
inline BodyId staticTank(WorldId world, float width, float height) {
    BodyDef def;
    def.name = "tank";
    def.type = BodyType::Static;
    def.shapes.push_back(boxShape({0.5f * width + 0.1f, 0.05f}, {0.5f * width, -0.05f}));
    def.shapes.push_back(boxShape({0.05f, 0.5f * height}, {-0.05f, 0.5f * height}));
    def.shapes.push_back(boxShape({0.05f, 0.5f * height}, {width + 0.05f, 0.5f * height}));
    return createBody(world, def);
}

inline BodyDef crate(const char* name, glm::vec2 centre, glm::vec2 halfExtents, float density) {
    BodyDef def;
    def.name = name;
    def.type = BodyType::Dynamic;
    def.position = centre;
    def.density = density;
    def.shapes.push_back(boxShape(halfExtents));
    return def;
}

/// A 2D fluid at `spacing` with one block.
inline FluidDef waterBlock(float spacing, glm::vec2 lo, glm::vec2 hi, glm::vec2 velocity = glm::vec2(0.0f)) {
    FluidDef def;
    def.name = "water";
    def.dimension = 2;
    def.spacing = spacing;
    FluidBlockDef b;
    b.min = glm::vec3(lo, 0.0f);
    b.max = glm::vec3(hi, 0.0f);
    b.velocity = glm::vec3(velocity, 0.0f);
    def.blocks.push_back(b);
    return def;
}

/// How deep (m) x lies inside a convex counter-clockwise polygon; <= 0 outside.
inline float depthInside(const std::vector<glm::vec2>& polygon, glm::vec2 x) {
    float depth = 3.0e38f;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::vec2 a = polygon[i];
        const glm::vec2 b = polygon[(i + 1) % polygon.size()];
        const glm::vec2 edge = glm::normalize(b - a);
        const glm::vec2 inward(-edge.y, edge.x);
        depth = std::min(depth, glm::dot(x - a, inward));
    }
    return depth;
}

inline BodySnapshot findBody(WorldId world, BodyId id) {
    for (BodySnapshot& b : readBodies(world)) {
        if (b.id.index == id.index) return b;
    }
    return {};
}

}  // namespace spindrift::test
