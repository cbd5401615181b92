// The rules of a FireDef's fields, named once: validateFireDef checks them,
// the scene loader words its type errors with them (src/core/field_rules.h).
#pragma once

#include "core/field_rules.h"

namespace spindrift::fire_rules {

/// At creation; 0 is a fire that is out.
inline constexpr FieldRule kStrength = FieldRule::number(Bounds{0.0, 1.0, true, false});
inline constexpr FieldRule kDousePerStrike = FieldRule::number(Bounds::nonNegative());
inline constexpr FieldRule kSteamPerStrike = FieldRule::number(Bounds::nonNegative());

}  // namespace spindrift::fire_rules
