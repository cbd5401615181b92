// The Vulkan renderer behind include/spindrift/render.h. Internal so the
// viewer (apps/spindrift) can record a frame into its own command buffer and
// present it.
#pragma once

#include <spindrift/render.h>

#include <memory>

namespace spindrift::render {

struct Renderer {
    WorldId world;
    RenderDef def;
    RenderStats stats;
    double lastTime = -1.0;  // world time of the previous frame; < 0: none yet
};

std::unique_ptr<Renderer> createRenderer(WorldId world, const RenderDef& def);
void destroyRenderer(Renderer& r);
Frame renderFrame(Renderer& r);

}  // namespace spindrift::render
