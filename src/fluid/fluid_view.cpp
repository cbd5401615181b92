// Read-only access to a fluid for the renderer (see fluid_view.h).
#include "fluid/fluid_view.h"

#include "particles/cpu_kernels.h"

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

}  // namespace

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
    return v;
}

template FluidView<2> viewFluid<2>(const FluidState&);
template FluidView<3> viewFluid<3>(const FluidState&);

bool pathMeetsObstacle(std::span<const kernels::ColliderParams> colliders, const FluidState& f, glm::vec3 x0,
                       glm::vec3 x1) {
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
    return false;
}

}  // namespace spindrift::fluid
