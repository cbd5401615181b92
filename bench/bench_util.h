// Small pieces shared by the benchmark programs.
#pragma once

#include <spindrift/effects.h>

namespace spindrift::bench {

/// A plane collider through `point` with unit `normal` (the walls of a tank).
inline ColliderDef wall(glm::vec3 point, glm::vec3 normal) {
    ColliderDef c;
    c.kind = ColliderKind::Plane;
    c.position = point;
    c.normal = normal;
    return c;
}

}  // namespace spindrift::bench
