// Fluids drawn as Sprinkle-style splats (splats.vert / splats.frag).
#pragma once

#include "render/renderer.h"

namespace spindrift::render {

/// Per frame: every fluid's splat instances (fluid_splats.cpp), advanced by
/// `dt` (s of world time since the previous frame), written to one
/// host-visible buffer that grows as needed.
void prepareSplats(Renderer& r, float dt);
void recordSplats(Renderer& r, VkCommandBuffer cmd);
void destroySplats(Renderer& r);

}  // namespace spindrift::render
