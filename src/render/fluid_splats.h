// PLACEHOLDER (replaced by the fluid splat work on branch `splats`): raw
// splats from readFluid, in the agreed instance layout.
#pragma once

#include <spindrift/render.h>

#include <glm/glm.hpp>

#include <vector>

namespace spindrift::render {

struct SplatInstance {
    glm::vec4 centre;  // xyz position (m), w radius (m)
    glm::vec4 axis;    // xyz unit major axis, w stretch >= 1
    glm::vec4 shade;   // x brightness, y edge factor, z kind (0 water, 1 splash, 2 bubble), w density ratio
};
static_assert(sizeof(SplatInstance) == 48);

struct FluidSplatState {};

void updateFluidSplats(FluidSplatState& state, WorldId world, FluidId fluid, const FluidRenderDef& settings,
                       float dt, std::vector<SplatInstance>& out);

}  // namespace spindrift::render
