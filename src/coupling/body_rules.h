// The rules of a BodyDef's and a JointDef's fields, named once:
// validateBodyDef and validateJointDef check them (so createBody, createJoint
// and the scene loader, which words its type errors with them too;
// src/core/field_rules.h).
#pragma once

#include "core/field_rules.h"

#include <spindrift/bodies.h>

#include <box2d/b2_common.h>

namespace spindrift::body_rules {

/// Box2D welds polygon corners closer than half its linear slop and asserts
/// on chain points closer than the slop: the smallest size and gap (m).
inline constexpr double kMinGap = b2_linearSlop;

/// m: positions, vertices and offsets, each coordinate.
inline constexpr FieldRule kCoordinate = FieldRule::number(Bounds::between(-kBodyMaxLength, kBodyMaxLength));
inline constexpr FieldRule kAngle = FieldRule::number(Bounds::any());  ///< rad
inline constexpr FieldRule kAngularVelocity = FieldRule::number(Bounds::between(-kBodyMaxSpeed, kBodyMaxSpeed));
/// kg/m^2, of a dynamic body (the others' is unused).
inline constexpr FieldRule kDensity = FieldRule::number(Bounds{0.0, kBodyMaxDensity, true, false});
inline constexpr FieldRule kFriction = FieldRule::number(Bounds::nonNegative());
inline constexpr FieldRule kRestitution = FieldRule::number(Bounds::unit());
/// m: a box's half extents, a circle's radius.
inline constexpr FieldRule kSize = FieldRule::number(Bounds::between(kMinGap, kBodyMaxLength));
/// Corners of a polygon; points of a chain.
inline constexpr FieldRule kPolygonCorners = FieldRule::whole(Bounds::between(3, b2_maxPolygonVertices));
inline constexpr FieldRule kChainPoints = FieldRule::whole(Bounds::between(2, kBodyMaxChainPoints));

// Joints.
/// A motor's most torque (N m) or force (N).
inline constexpr FieldRule kMaxMotor = FieldRule::number(Bounds::positive());

}  // namespace spindrift::body_rules
