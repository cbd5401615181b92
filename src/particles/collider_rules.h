// The rules of a ColliderDef's fields, named once: validateColliderDef checks
// them (so createCollider and the scene loader, which words its type errors
// with them too; src/core/field_rules.h). A generator's parameters (hills,
// shapes of a cube map, an image's height scale) never reach the Def and are
// checked by src/scene/parse_collider.cpp.
#pragma once

#include "core/field_rules.h"

#include <spindrift/effects.h>

namespace spindrift::collider_rules {

inline constexpr FieldRule kFriction = FieldRule::number(Bounds::unit());
inline constexpr FieldRule kResilience = FieldRule::number(Bounds::unit());
inline constexpr FieldRule kRestSpeed = FieldRule::number(Bounds::nonNegative());  ///< m/s
inline constexpr FieldRule kRadius = FieldRule::number(Bounds::positive());        ///< m, sphere
inline constexpr FieldRule kHalfExtent = FieldRule::number(Bounds::positive());    ///< m, box, each
inline constexpr FieldRule kTerrainSize = FieldRule::number(Bounds::positive());   ///< m, x and z
inline constexpr FieldRule kTerrainAxis = FieldRule::whole(Bounds::between(2, kTerrainMaxAxis));
inline constexpr FieldRule kCubeResolution = FieldRule::whole(Bounds::between(2, kCubeMapMaxResolution));
inline constexpr FieldRule kCubeDepth = FieldRule::number(Bounds::nonNegative());  ///< m

}  // namespace spindrift::collider_rules
