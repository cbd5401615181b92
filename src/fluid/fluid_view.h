// Read-only access to one fluid's last step for code outside the solver (the
// renderer's splats, src/render/fluid_splats.cpp): what the neighbour search
// and constraint setup already know (slide 56: "we have a lot more information
// than just particle position"), and the fluid's obstacles as path tests.
// A new file rather than edits to fluid_world.cpp, which others change often.
#pragma once

#include "fluid/fluid_state.h"

#include <spindrift/bodies.h>

#include <span>

namespace spindrift::fluid {

/// One fluid's particles in grid order, and the neighbour lists of its last
/// constraint setup: particle i's neighbours are neighbourList(i)[k] for
/// k < count[i]. Before the first step there are no lists (count is
/// empty); a particle added since the last step (i >= count.size()) has none.
template <int D>
struct FluidView {
    std::span<const Vec<D>> position;    // m
    std::span<const Vec<D>> velocity;    // m/s
    std::span<const float> density;      // rho / rho0 at the last setup
    std::span<const std::uint32_t> id;   // creation serial
    std::span<const std::vector<Neighbour<D>>> neighbours;  // per chunk (NeighbourChunks)
    std::span<const std::uint32_t> count;
    std::span<const std::uint32_t> first;      // offset in the chunk's list
    std::span<const std::uint32_t> listChunk;  // the array of `neighbours` that holds it
    const Neighbour<D>* neighbourList(std::size_t i) const { return neighbours[listChunk[i]].data() + first[i]; }
};

template <int D>
FluidView<D> viewFluid(const FluidState& f);

/// True when the straight path x0 -> x1 of a point meets one of the fluid's
/// obstacles: a plane, sphere or box among the world's `colliders` (the
/// solver's own path tests from src/kernels/collide.glsl), one of the
/// fluid's polygons (end point inside, as integratePositions tests them), or,
/// for a 2D fluid, a shape of one of the `bodies` at its pose now
/// (pathMeetsBodyShape). In 2D pass z = 0.
bool pathMeetsObstacle(std::span<const kernels::ColliderParams> colliders, const FluidState& f,
                       std::span<const BodySnapshot> bodies, glm::vec3 x0, glm::vec3 x1);

/// True when the path x0 -> x1 (m, the body plane) meets a body shape: it
/// crosses one of its segments (a polygon's sides, an edge, a chain's links),
/// ends inside a polygon, or comes within a circle's radius of its centre.
/// Crossing, not only ending inside, so a fast point cannot pass through a
/// thin shape between two frames.
bool pathMeetsBodyShape(const BodyShapeView& shape, glm::vec2 x0, glm::vec2 x1);

}  // namespace spindrift::fluid
