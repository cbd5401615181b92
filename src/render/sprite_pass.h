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
/// Draws the additive emitters (order-free), then the sorted alpha ones.
void recordSprites(Renderer& r, VkCommandBuffer cmd);
/// Draws the emitters of one blend mode, in order, with pipeline `hard`, or
/// `soft` for those with a soft distance (the OIT accumulation draws
/// SpriteBlend::WeightedOit ones with one pipeline for both).
void recordSpriteGroup(Renderer& r, VkCommandBuffer cmd, const Pipeline& hard, const Pipeline& soft,
                       SpriteBlend blend);

}  // namespace spindrift::render
