// Effect emitters drawn as sprites (sprites.vert / sprites.frag).
#pragma once

#include "render/renderer.h"

namespace spindrift::render {

/// One SpriteEmitter per emitter of the world, with its descriptor set.
void createSpriteEmitters(Renderer& r);
void destroySpriteEmitters(Renderer& r);
/// Per frame: uploads a CPU world's particles, the stateless runs, and sorts
/// alpha-blended emitters back to front on the device.
void prepareSprites(Renderer& r);
/// Draws every emitter: additive ones first (order-free), then alpha ones.
void recordSprites(Renderer& r, VkCommandBuffer cmd);

}  // namespace spindrift::render
