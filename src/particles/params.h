// Translation of the public Def structs into the GPU-visible kernel parameter
// structs, with validation: a bad definition throws spindrift::Error naming the
// object and the field.
#pragma once

#include "particles/fields.h"
#include "kernels/layout.glsl"

#include <spindrift/effects.h>

#include <cstdint>

namespace spindrift {

/// Most forces and colliders a world can hold (src/kernels/layout.glsl): an
/// emitter selects them with a 32-bit mask in its kernel parameters.
inline constexpr std::uint32_t kMaxForces = kernels::SD_MAX_FORCES;
inline constexpr std::uint32_t kMaxColliders = kernels::SD_MAX_COLLIDERS;

// The kernel's form of a curve that validateEmitterDef accepted.
kernels::CurveParams makeCurveParams(const Curve& curve);
/// forceMask and colliderMask select the emitter's forces and colliders.
kernels::EmitterParams makeEmitterParams(const EmitterDef& def, std::uint32_t seed, std::uint32_t emitterIndex,
                                         std::uint32_t forceMask, std::uint32_t colliderMask);
/// flowIndex: where the force's flow field's data lives; `flow` its definition.
kernels::ForceParams makeForceParams(const ForceDef& def, const FlowFieldDef* flow, std::uint32_t flowIndex);
/// dataIndex: where the collider's height map or cube map lives in the FieldSet.
kernels::ColliderParams makeColliderParams(const ColliderDef& def, std::uint32_t dataIndex);

void validateEmitterDef(const EmitterDef& def);
void validateFlowFieldDef(const FlowFieldDef& def);
/// The resolution and bounds only: what a generator needs before it fills
/// the velocities (validateFlowFieldDef checks them too).
void validateFlowFieldGrid(const FlowFieldDef& def);
void validateColliderDef(const ColliderDef& def);
/// A terrain's or cube map's resolution only: what a generator needs before
/// it fills the heights or depths (validateColliderDef checks it too).
void validateColliderGrid(const ColliderDef& def);
void validateForceDef(const ForceDef& def);

}  // namespace spindrift
