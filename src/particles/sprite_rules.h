// The rules of an emitter's SpriteDef (how the renderer draws it), named
// once: validateSpriteDef checks them for createEmitter and the scene loader
// (src/core/field_rules.h), named as a scene file spells the keys.
#pragma once

#include "core/field_rules.h"

#include <spindrift/effects.h>

namespace spindrift::sprite_rules {

/// Frames a side of a sprite sheet: 64 x 64 frames of even 4 x 4 texels fill
/// a 256 x 256 image; more is a sheet no artist paints.
inline constexpr std::uint32_t kMaxSheetSide = 64;
inline constexpr FieldRule kSheetSide = FieldRule::whole(Bounds::between(1, kMaxSheetSide));
/// 0: all rows x columns; else at most rows x columns (checked against them).
inline constexpr FieldRule kFrames = FieldRule::whole(Bounds::between(0, kMaxSheetSide * kMaxSheetSide));
/// frames/s; 0 plays the sheet once over the life.
inline constexpr FieldRule kFps = FieldRule::number(Bounds::nonNegative());
/// s: velocity stretch.
inline constexpr FieldRule kStretch = FieldRule::number(Bounds::nonNegative());
/// m: the depth fade of soft particles; 0 is off.
inline constexpr FieldRule kSoftDistance = FieldRule::number(Bounds::nonNegative());

/// Throws FieldError ("sprite.flipbook.rows", ...) for a bad field.
void validateSpriteDef(const FieldCheck& check, const SpriteDef& sprite);

}  // namespace spindrift::sprite_rules
