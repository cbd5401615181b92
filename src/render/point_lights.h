// Point lights (RenderDef::lights): where each one is and how bright, frame by
// frame, into the frame's uniforms. A light that follows an emitter sits at
// its spawn centre (which rides its body) and scales with its rate, so a
// fire's glow fades as the fire is doused (fires scale their flames' rate).
#pragma once

#include "kernels/render_layout.glsl"

#include <spindrift/render.h>

#include <vector>

namespace spindrift {
struct World;
}

namespace spindrift::render {

struct PointLights {
    std::vector<float> baseRates;  // each light's emitter's rate when the renderer was made (0: fixed light)
};

// Throws Error for a light whose emitter the world does not have.
PointLights capturePointLights(const World& world, const std::vector<LightDef>& lights);
// Writes ambient, sun colour and the lights of this moment into `u`.
void writeLights(const PointLights& captured, const RenderDef& def, const World& world, double time,
                 kernels::FrameUniforms& u);

}  // namespace spindrift::render
