// PLACEHOLDER until the Vulkan renderer lands (issue 5, in progress): fills
// the frame with the background on the CPU so the CLI and scene work can
// proceed against the real API.
#include "render/renderer.h"

#include <algorithm>
#include <cmath>

namespace spindrift::render {

std::unique_ptr<Renderer> createRenderer(WorldId world, const RenderDef& def) {
    auto r = std::make_unique<Renderer>();
    r->world = world;
    r->def = def;
    return r;
}

void destroyRenderer(Renderer&) {}

Frame renderFrame(Renderer& r) {
    Frame f;
    f.width = r.def.width;
    f.height = r.def.height;
    f.rgba.resize(std::size_t{f.width} * f.height * 4);
    for (std::uint32_t y = 0; y < f.height; ++y) {
        const float t = f.height > 1 ? 1.0f - float(y) / float(f.height - 1) : 0.5f;
        const glm::vec3 c = r.def.background.kind == BackgroundKind::Gradient
                                ? glm::mix(r.def.background.bottom, r.def.background.top, t)
                                : r.def.background.colour;
        for (std::uint32_t x = 0; x < f.width; ++x) {
            std::uint8_t* p = &f.rgba[(std::size_t{y} * f.width + x) * 4];
            for (int i = 0; i < 3; ++i) {
                const float s = std::pow(std::clamp(c[i], 0.0f, 1.0f), 1.0f / 2.2f);
                p[i] = static_cast<std::uint8_t>(std::lround(s * 255.0f));
            }
            p[3] = 255;
        }
    }
    return f;
}

}  // namespace spindrift::render
