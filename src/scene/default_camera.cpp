// The default camera (default_camera.h). The 3D default (CameraDef: eye at
// (0, 2, 10) looking at the origin) shows a 2D tank of a few metres as a small
// box off centre beside a wall seen edge on; a user who left [camera] out of
// a 2D fluid scene wants to see the water.
#include "scene/default_camera.h"

#include "particles/params.h"

#include <algorithm>
#include <cmath>

namespace spindrift::scene {
namespace {

/// Box (m) in the x-y plane.
struct Frame {
    glm::vec2 lo{3.0e38f};
    glm::vec2 hi{-3.0e38f};
    void add(glm::vec2 p, glm::vec2 reach = glm::vec2(0.0f)) {
        lo = glm::min(lo, p - reach);
        hi = glm::max(hi, p + reach);
    }
    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y); }
};

/// Largest distance (m) from a body's origin to any point of its shapes.
float bodyReach(const BodyDef& body) {
    float reach = 0.0f;
    for (const BodyShapeDef& s : body.shapes) {
        const float offset = glm::length(s.offset);
        switch (s.kind) {
            case BodyShapeKind::Box: reach = std::max(reach, offset + glm::length(s.halfExtents)); break;
            case BodyShapeKind::Circle: reach = std::max(reach, offset + s.radius); break;
            case BodyShapeKind::Polygon:
            case BodyShapeKind::Edge:
            case BodyShapeKind::Chain:
                for (const glm::vec2& v : s.vertices) reach = std::max(reach, glm::length(v));
                break;
        }
    }
    return reach;
}

/// Half extents (m) along x and y of a box collider's bounding box: each of
/// the box's axes (the kernels' frame, params.cpp) times its half extent.
glm::vec2 boxReach(const ColliderDef& c) {
    const kernels::ColliderParams p = makeColliderParams(c, 0);
    const glm::vec3 axes[3] = {glm::vec3(p.axisX), glm::vec3(p.axisY), glm::vec3(p.axisZ)};
    glm::vec2 reach(0.0f);
    for (int k = 0; k < 3; ++k) reach += glm::abs(glm::vec2(axes[k])) * c.halfExtents[k];
    return reach;
}

/// What the scene holds: fluid blocks, jets' nozzles, bodies (their shapes'
/// bounding circles), box and sphere colliders.
Frame contentFrame(const SceneDef& scene) {
    Frame f;
    for (const FluidDef& fluid : scene.fluids) {
        for (const FluidBlockDef& b : fluid.blocks) {
            f.add(glm::vec2(b.min));
            f.add(glm::vec2(b.max));
        }
        for (const FluidJetDef& j : fluid.jets) f.add(glm::vec2(j.position));
    }
    for (const BodyDef& b : scene.bodies) f.add(b.position, glm::vec2(bodyReach(b)));
    for (const ColliderDef& c : scene.colliders) {
        if (c.kind == ColliderKind::Box) f.add(glm::vec2(c.position), boxReach(c));
        if (c.kind == ColliderKind::Sphere) f.add(glm::vec2(c.position), glm::vec2(c.radius));
    }
    return f;
}

/// The content's box grown to the walls that contain it: a plane whose normal
/// lies along x or y and which stands within the content's own size of it (a
/// tank's floor and sides; not a floor kilometres below).
Frame withWalls(const SceneDef& scene, Frame f) {
    const glm::vec2 size = f.hi - f.lo;
    const float near = std::max(size.x, size.y);
    Frame walled = f;
    for (const ColliderDef& c : scene.colliders) {
        if (c.kind != ColliderKind::Plane) continue;
        const glm::vec3 n = glm::normalize(c.normal);
        for (int a = 0; a < 2; ++a) {
            if (std::abs(n[a]) < 0.999f) continue;
            const float at = c.position[a];
            // A wall facing +a bounds the content from below along a.
            if (n[a] > 0.0f && at <= f.lo[a] && f.lo[a] - at <= near) walled.lo[a] = std::min(walled.lo[a], at);
            if (n[a] < 0.0f && at >= f.hi[a] && at - f.hi[a] <= near) walled.hi[a] = std::max(walled.hi[a], at);
        }
    }
    return walled;
}

}  // namespace

CameraDef defaultCamera(const SceneDef& scene) {
    CameraDef camera;
    if (scene.fluids.empty()) return camera;
    for (const FluidDef& fluid : scene.fluids) {
        if (fluid.dimension != 2) return camera;
    }
    Frame f = contentFrame(scene);
    if (f.empty()) return camera;
    f = withWalls(scene, f);
    // A margin of 5 % of the larger side all round, and at least 0.1 m, so
    // that walls and the water at them are inside the picture.
    const glm::vec2 size = f.hi - f.lo;
    const float margin = std::max(0.05f * std::max(size.x, size.y), 0.1f);
    const float width = size.x + 2.0f * margin;
    const float height = size.y + 2.0f * margin;
    const float aspect = static_cast<float>(scene.render.width) / static_cast<float>(scene.render.height);
    const glm::vec2 centre = 0.5f * (f.lo + f.hi);
    camera.orthographic = true;
    camera.orthoHeight = std::max(height, width / aspect);
    camera.target = glm::vec3(centre, 0.0f);
    camera.eye = glm::vec3(centre, 10.0f);
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    return camera;
}

}  // namespace spindrift::scene
