// Read-only access to a fluid for the renderer (see fluid_view.h).
#include "fluid/fluid_view.h"

#include "particles/cpu_kernels.h"

#include <algorithm>

namespace spindrift::fluid {

namespace {

// Const twins of FluidState::particles<D>() and neighbours<D>().
template <int D>
const Particles<D>& particlesOf(const FluidState& f) {
    if constexpr (D == 2) return f.p2; else return f.p3;
}

template <int D>
const NeighbourChunks<D>& neighboursOf(const FluidState& f) {
    if constexpr (D == 2) return f.n2; else return f.n3;
}

float cross2(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

// Whether the segments p0-p1 and a-b share a point (touching counts): each
// one's end points lie on both sides of, or on, the other's line.
bool segmentsMeet(glm::vec2 p0, glm::vec2 p1, glm::vec2 a, glm::vec2 b) {
    const glm::vec2 path = p1 - p0, edge = b - a;
    const float s0 = cross2(edge, p0 - a), s1 = cross2(edge, p1 - a);
    const float t0 = cross2(path, a - p0), t1 = cross2(path, b - p0);
    if ((s0 > 0.0f && s1 > 0.0f) || (s0 < 0.0f && s1 < 0.0f)) return false;
    if ((t0 > 0.0f && t1 > 0.0f) || (t0 < 0.0f && t1 < 0.0f)) return false;
    if (s0 == 0.0f && s1 == 0.0f) {  // on one line: overlap along it
        const float len2 = glm::dot(edge, edge);
        if (len2 == 0.0f) return p0 == a || p1 == a;
        const float u0 = glm::dot(p0 - a, edge) / len2, u1 = glm::dot(p1 - a, edge) / len2;
        return std::max(u0, u1) >= 0.0f && std::min(u0, u1) <= 1.0f;
    }
    return true;
}

// Distance (m) from c to the segment p0-p1.
float segmentDistance(glm::vec2 p0, glm::vec2 p1, glm::vec2 c) {
    const glm::vec2 path = p1 - p0;
    const float len2 = glm::dot(path, path);
    const float t = len2 > 0.0f ? std::clamp(glm::dot(c - p0, path) / len2, 0.0f, 1.0f) : 0.0f;
    return glm::distance(p0 + path * t, c);
}

}  // namespace

bool pathMeetsBodyShape(const BodyShapeView& shape, glm::vec2 x0, glm::vec2 x1) {
    if (shape.kind == BodyShapeView::Kind::Circle) return segmentDistance(x0, x1, shape.centre) <= shape.radius;
    const std::vector<glm::vec2>& v = shape.vertices;
    const bool closed = shape.kind == BodyShapeView::Kind::Polygon || shape.loop;
    const std::size_t links = v.size() < 2 ? 0 : (closed && v.size() > 2 ? v.size() : v.size() - 1);
    for (std::size_t k = 0; k < links; ++k) {
        if (segmentsMeet(x0, x1, v[k], v[(k + 1) % v.size()])) return true;
    }
    if (shape.kind != BodyShapeView::Kind::Polygon || v.size() < 3) return false;
    // Counter-clockwise and convex (Box2D's polygons): inside is left of every side.
    for (std::size_t k = 0; k < v.size(); ++k) {
        if (cross2(v[(k + 1) % v.size()] - v[k], x1 - v[k]) < 0.0f) return false;
    }
    return true;
}

template <int D>
FluidView<D> viewFluid(const FluidState& f) {
    const Particles<D>& p = particlesOf<D>(f);
    const NeighbourChunks<D>& lists = neighboursOf<D>(f);
    FluidView<D> v;
    v.position = p.position;
    v.velocity = p.velocity;
    v.density = p.density;
    v.id = p.id;
    v.neighbours = lists;
    v.count = f.constraints.count;
    v.first = f.constraints.first;
    v.listChunk = f.constraints.listChunk;
    return v;
}

template FluidView<2> viewFluid<2>(const FluidState&);
template FluidView<3> viewFluid<3>(const FluidState&);

bool pathMeetsObstacle(std::span<const kernels::ColliderParams> colliders, const FluidState& f,
                       std::span<const BodySnapshot> bodies, glm::vec3 x0, glm::vec3 x1) {
    for (const kernels::ColliderParams& c : colliders) {
        kernels::Hit hit = kernels::noHit();
        if (c.kind == kernels::SD_COLLIDER_PLANE) hit = kernels::intersectPlane(c, x0, x1);
        else if (c.kind == kernels::SD_COLLIDER_SPHERE) hit = kernels::intersectSphere(c, x0, x1);
        else if (c.kind == kernels::SD_COLLIDER_BOX) hit = kernels::intersectBox(c, x0, x1);
        if (hit.hit != 0u) return true;
    }
    for (const kernels::FluidPolygon& poly : f.polygons) {
        if (kernels::fluidPolygonSurface(poly, x1).distance < 0.0f) return true;
    }
    if (f.def.dimension != 2) return false;  // bodies are 2D (Box2D)
    for (const BodySnapshot& body : bodies) {
        for (const BodyShapeView& shape : body.shapes) {
            if (pathMeetsBodyShape(shape, glm::vec2(x0), glm::vec2(x1))) return true;
        }
    }
    return false;
}

}  // namespace spindrift::fluid
