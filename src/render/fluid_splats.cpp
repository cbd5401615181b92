// PLACEHOLDER (replaced by the fluid splat work on branch `splats`).
#include "render/fluid_splats.h"

#include <spindrift/fluid.h>

namespace spindrift::render {

void updateFluidSplats(FluidSplatState&, WorldId world, FluidId fluid, const FluidRenderDef& settings, float,
                       std::vector<SplatInstance>& out) {
    FluidSnapshot s = readFluid(world, fluid);
    const float radius = 0.5f * fluidDef(world, fluid).spacing * settings.radiusScale;
    out.clear();
    for (std::size_t i = 0; i < s.count(); ++i) {
        out.push_back({glm::vec4(s.position[i], radius), glm::vec4(1, 0, 0, 1), glm::vec4(1, 0, 0, s.density[i])});
    }
}

}  // namespace spindrift::render
