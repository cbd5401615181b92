// 3D fluids drawn as one continuous liquid in screen space (issue 15; van der
// Laan, Green and Sainz 2009, "Screen Space Fluid Rendering with Curvature
// Flow", and NVIDIA FleX's fluid renderer): the field passes at reduced
// resolution before the frame's first render pass (sphere depths, summed
// thickness, the depth smoothed) and the composite in pass B. The spheres
// are host work: screenFluidInstances (surface_field.h).
#pragma once

#include "render/renderer.h"

namespace spindrift::render {

/// Per frame, after prepareSplats: whether some fluid is drawn so
/// (r.screen.drawn); its passes and pipelines on first use, its images for
/// this frame's size.
void prepareScreenFluid(Renderer& r);
void destroyScreenFluid(Renderer& r);
/// The field: outside any render pass.
void recordScreenFluidField(Renderer& r, VkCommandBuffer cmd);
/// The composite: inside pass B, with the frame's viewport.
void recordScreenFluidComposite(Renderer& r, VkCommandBuffer cmd);

}  // namespace spindrift::render
