// The rules of a FlowFieldDef's fields, named once: validateFlowFieldDef
// checks them (so createFlowField and the scene loader; src/core/field_rules.h).
// A generator's parameters (frequency, octaves ...) never reach the Def and
// are checked by src/scene/parse_flow_field.cpp.
#pragma once

#include "core/field_rules.h"

#include <spindrift/effects.h>

namespace spindrift::flow_field_rules {

/// Samples along one axis; nx * ny * nz at most kFlowFieldMaxSamples.
inline constexpr FieldRule kAxis = FieldRule::whole(Bounds::between(1, kFlowFieldMaxAxis));

}  // namespace spindrift::flow_field_rules
