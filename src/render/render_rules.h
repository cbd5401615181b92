// The rules of a RenderDef's fields, named once: validateRenderDef and
// validateCameraDef check them (so createRenderer, setRenderCamera,
// setFluidRender and the scene loader, which words its type errors with them
// too; src/core/field_rules.h), and the viewer's sliders take their ranges
// from them.
#pragma once

#include "core/field_rules.h"

#include <spindrift/render.h>

namespace spindrift::render_rules {

/// Pixels a side: the smallest maxImageDimension2D a desktop driver reports is
/// far above what a frame needs; lavapipe allows 16384.
inline constexpr FieldRule kFrameSide = FieldRule::whole(Bounds::between(1, kRenderMaxFrameSide));
/// Pixels a side of a sprite texture or background image: lavapipe's and a
/// typical desktop driver's maxImageDimension2D. The scene loader checks it
/// from the PNG header, before anything is decoded (a 60000 x 60000 PNG of a
/// few kB would decode to 14 GB).
inline constexpr std::uint32_t kMaxImageSide = 16384;
inline constexpr FieldRule kFps = FieldRule::number(Bounds::positive());
inline constexpr FieldRule kSeconds = FieldRule::number(Bounds::positive());  ///< s
/// FluidRenderDef::upTo's n.
inline constexpr FieldRule kFluidSteps = FieldRule::whole(Bounds::between(1, kFluidRenderSteps));
inline constexpr FieldRule kFluidOpacity = FieldRule::number(Bounds{0.0, 1.0, true, false});
inline constexpr FieldRule kFluidRadiusScale = FieldRule::number(Bounds::positive());
/// The liquid surface's field resolution, a fraction of the frame's side
/// (docs/rendering.md).
inline constexpr FieldRule kFluidSurfaceScale = FieldRule::number(Bounds::between(0.125, 1.0));
/// RenderDef::exposure, a multiplier of linear light.
inline constexpr FieldRule kExposure = FieldRule::number(Bounds::positive());
/// RenderDef::bloom; 0 turns it off. Above 10 the glow swamps any frame.
inline constexpr FieldRule kBloom = FieldRule::number(Bounds::between(0.0, 10.0));

/// LightDef::radius (m) and flicker.
inline constexpr FieldRule kLightRadius = FieldRule::number(Bounds::positive());
inline constexpr FieldRule kLightFlicker = FieldRule::number(Bounds::between(0.0, 1.0));

// Camera. Open interval: 0 and 180 degrees make a degenerate projection.
inline constexpr FieldRule kFov = FieldRule::number(Bounds{0.0, 180.0, true, true});  ///< degrees
inline constexpr FieldRule kOrthoHeight = FieldRule::number(Bounds::positive());      ///< m

}  // namespace spindrift::render_rules
