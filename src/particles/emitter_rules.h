// The rules of an EmitterDef's fields, named once: validateEmitterDef checks
// them (so createEmitter and the scene loader, which words its type errors
// with them too; src/core/field_rules.h). Rules a scene file states in its
// own units or conventions (degrees, "leave duration out for forever") stay in
// src/scene/parse_emitter.cpp (docs/design.md, "Validation").
#pragma once

#include "core/field_rules.h"

#include <spindrift/effects.h>

#include <glm/gtc/constants.hpp>

namespace spindrift::emitter_rules {

inline constexpr FieldRule kCapacity = FieldRule::whole(Bounds::between(1, kEmitterMaxCapacity));
inline constexpr FieldRule kRate = FieldRule::number(Bounds::nonNegative());      ///< particles/s
inline constexpr FieldRule kLifetime = FieldRule::number(Bounds::positive());     ///< s, each end
inline constexpr FieldRule kSize = FieldRule::number(Bounds::nonNegative());      ///< m, each end
inline constexpr FieldRule kMass = FieldRule::number(Bounds::positive());         ///< kg
inline constexpr FieldRule kLifeLoss = FieldRule::number(Bounds::unit());         ///< per hit
inline constexpr FieldRule kBurstTime = FieldRule::number(Bounds::nonNegative()); ///< s

// Checked by the API only: a scene file reads these in its own terms and is
// stricter (src/scene/parse_emitter.cpp), so the API rule never fires for it.
/// m/s; the scene file asks for >= 0 (docs/design.md, "Validation").
inline constexpr FieldRule kSpeed = FieldRule::number(Bounds::any());
/// rad, rad/s: a file gives degrees and checks them as degrees.
inline constexpr FieldRule kRotation = FieldRule::number(Bounds::any());
inline constexpr FieldRule kAngularVelocity = FieldRule::number(Bounds::any());
/// rad: the half-angle of a cone of directions; a file gives [0, 180] degrees.
/// The float pi (just above the real one) is the top: 180 degrees converted
/// in float arithmetic is that value.
inline constexpr FieldRule kSpread = FieldRule::number(Bounds::between(0.0, static_cast<double>(glm::pi<float>())));
/// m; a file asks for > 0 where the shape has a radius.
inline constexpr FieldRule kShapeRadius = FieldRule::number(Bounds::nonNegative());
/// A file asks for at least 1 and at most `capacity`.
inline constexpr FieldRule kBurstCount = FieldRule::whole(Bounds::between(0, kEmitterMaxBurstCount));

}  // namespace spindrift::emitter_rules
