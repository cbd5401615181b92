// The rules of a ForceDef's fields, named once: validateForceDef checks them
// (so createForce and the scene loader, which words its type errors with them
// too; src/core/field_rules.h). What only a file says (a repulsor is an
// attractor with its strength negated, so a file's attractor and repulsor
// strengths are >= 0) stays in src/scene/parse_force.cpp.
#pragma once

#include "core/field_rules.h"

namespace spindrift::force_rules {

inline constexpr FieldRule kStrength = FieldRule::number(Bounds::any());
/// Damping, undamping and wind: a rate (1/s); a negative one would blow up.
inline constexpr FieldRule kRate = FieldRule::number(Bounds::nonNegative());
inline constexpr FieldRule kRadius = FieldRule::number(Bounds::positive());       ///< m
inline constexpr FieldRule kFalloff = FieldRule::number(Bounds::any());           ///< exponent
inline constexpr FieldRule kRange = FieldRule::number(Bounds::nonNegative());     ///< m; 0: unlimited
inline constexpr FieldRule kTargetSpeed = FieldRule::number(Bounds::nonNegative());  ///< m/s
/// Pa s; 0 is no drag at all (harmless, so allowed).
inline constexpr FieldRule kViscosity = FieldRule::number(Bounds::nonNegative());
/// Curl noise: the rms speed (m/s) of the noise velocity.
inline constexpr FieldRule kNoiseStrength = FieldRule::number(Bounds::nonNegative());
/// Curl noise: noise cells per metre (1/m).
inline constexpr FieldRule kFrequency = FieldRule::number(Bounds::positive());
/// Curl noise: noise slices per second (1/s); 0 is a static field.
inline constexpr FieldRule kSpeed = FieldRule::number(Bounds::nonNegative());
/// Curl noise: each octave costs a full noise evaluation per particle and
/// force stage, and past 4 the finest layer is under 1/16 of the first's size:
/// detail below a sprite.
inline constexpr FieldRule kOctaves = FieldRule::whole(Bounds::between(1.0, 4.0));
/// Curl noise: any 32-bit seed.
inline constexpr FieldRule kSeed = FieldRule::whole(Bounds::between(0.0, 4294967295.0));

}  // namespace spindrift::force_rules
