// The camera a scene gets when it has no [camera] table.
#pragma once

#include <spindrift/scene.h>

namespace spindrift::scene {

/// A scene whose fluids are all 2D (and at least one) is seen square-on: an
/// orthographic view along -z that frames its fluid blocks, jets, bodies and
/// box and sphere colliders, and the axis-aligned walls close to them, at the
/// frame's aspect ratio. Any other scene keeps CameraDef's defaults.
CameraDef defaultCamera(const SceneDef& scene);

}  // namespace spindrift::scene
