// 2D fluids drawn as one continuous liquid (issue 15): the field passes
// (kernels summed at reduced resolution, blurred across, then down, then the
// depth tint's input; before the frame's first render pass) and the composite (in pass B, before the
// splats). The kernels themselves are host work: surface_field.h.
#pragma once

#include "render/renderer.h"

namespace spindrift::render {

/// The render pass, descriptor layout and pipelines; the field images are
/// made on first use and remade when FluidRenderDef::surfaceScale changes.
void createSurface(Renderer& r);
void destroySurface(Renderer& r);
/// Per frame, after prepareSplats: the field's images for this frame's size
/// and whether anything is drawn as a surface (r.surface.drawn).
void prepareSurface(Renderer& r);
/// The field: outside any render pass.
void recordSurfaceField(Renderer& r, VkCommandBuffer cmd);
/// The composite: inside pass B, with the frame's viewport.
void recordSurfaceComposite(Renderer& r, VkCommandBuffer cmd);

}  // namespace spindrift::render
