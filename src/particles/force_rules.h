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

}  // namespace spindrift::force_rules
