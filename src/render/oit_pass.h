// Weighted blended order-independent transparency (McGuire and Bavoil 2013,
// "Weighted Blended Order-Independent Transparency", JCGT 2(2)) for emitters
// with SpriteBlend::WeightedOit: an accumulation pass after pass A sums the
// sprites' weighted colours and multiplies their revealage, with no sort;
// the composite in pass B lays the result over the frame.
#pragma once

#include "render/renderer.h"

namespace spindrift::render {

/// Sums and weights targets, pass, pipelines and descriptor set, when some
/// emitter uses OIT (after createSpriteEmitters); otherwise nothing.
void createOit(Renderer& r);
void destroyOit(Renderer& r);
/// The accumulation pass: outside any render pass, after pass A.
void recordOitAccumulation(Renderer& r, VkCommandBuffer cmd);
/// The composite: inside pass B, with the frame's viewport.
void recordOitComposite(Renderer& r, VkCommandBuffer cmd);

}  // namespace spindrift::render
