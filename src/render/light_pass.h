// Light after the frame is drawn (issue 15, item 2; docs/rendering.md,
// "Light"): the float frame's bloom (what is brighter than 1, reduced to a
// quarter of the frame's side, blurred down a chain of smaller levels and
// added back up them) and the tone map that writes the 8-bit sRGB image.
#pragma once

#include "render/renderer.h"

namespace spindrift::render {

/// Bloom's levels and passes (only when RenderDef::bloom > 0), the tone map's
/// pipeline and the descriptor sets of both. After createDescriptors (it uses
/// the frame's set layout and the placeholder image).
void createLight(Renderer& r);
void destroyLight(Renderer& r);
/// After the frame's last render pass, with the float target in
/// TRANSFER_SRC_OPTIMAL: bloom, then the tone map; leaves the sRGB image in
/// TRANSFER_SRC_OPTIMAL.
void recordLight(Renderer& r, VkCommandBuffer cmd);

}  // namespace spindrift::render
