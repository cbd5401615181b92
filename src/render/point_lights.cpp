// Point lights, per frame (point_lights.h).
#include "render/point_lights.h"

#include "core/field_rules.h"
#include "world/world.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace spindrift::render {
namespace {

static_assert(kRenderMaxLights == kernels::SD_MAX_LIGHTS);

const EmitterDef* emitterOf(const World& world, const LightDef& light) {
    if (light.emitter.index == 0) return nullptr;
    return &world.emitters[light.emitter.index - 1]->def;
}

// In [1 - depth, 1]: two incommensurate sines of the world time, a fixed
// function of it so that a frame is reproducible; `phase` keeps two lights
// from flickering together.
float flickerAt(float depth, double time, float phase) {
    const double wave = 0.5 + 0.25 * std::sin(11.3 * time + phase) + 0.25 * std::sin(17.9 * time + 2.3 * phase);
    return static_cast<float>(1.0 - depth * wave);
}

}  // namespace

PointLights capturePointLights(const World& world, const std::vector<LightDef>& lights) {
    PointLights captured;
    for (const LightDef& light : lights) {
        if (light.emitter.index > world.emitters.size()) {
            throw Error(fmt::format("{}: emitter id {} does not exist in this world", objectLabel("light", light.name),
                                    light.emitter.index));
        }
        const EmitterDef* e = emitterOf(world, light);
        captured.baseRates.push_back(e != nullptr ? e->rate : 0.0f);
    }
    return captured;
}

void writeLights(const PointLights& captured, const RenderDef& def, const World& world, double time,
                 kernels::FrameUniforms& u) {
    u.ambient = glm::vec4(def.ambient, static_cast<float>(def.lights.size()));
    u.sunColour = glm::vec4(def.sunColour, 0.0f);
    for (std::size_t i = 0; i < def.lights.size(); ++i) {
        const LightDef& light = def.lights[i];
        glm::vec3 position = light.position;
        float scale = flickerAt(light.flicker, time, 1.7f * static_cast<float>(i));
        if (const EmitterDef* e = emitterOf(world, light)) {
            position += e->shape.center;
            // An emitter made with rate 0 (steam, fed by strikes) lights at its
            // colour while it emits at all.
            const float base = captured.baseRates[i];
            scale *= base > 0.0f ? std::clamp(e->rate / base, 0.0f, 1.0f) : (e->rate > 0.0f ? 1.0f : 0.0f);
        }
        u.lightPosition[i] = glm::vec4(position, light.radius);
        u.lightColour[i] = glm::vec4(light.colour * scale, 0.0f);
    }
}

}  // namespace spindrift::render
