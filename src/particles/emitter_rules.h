// The rules of an EmitterDef's fields, named once: validateEmitterDef checks
// them (so createEmitter and the scene loader, which words its type errors
// with them too; src/core/field_rules.h). A file's angles are degrees,
// converted to the API's radians where they enter, and checked here as
// radians. Rules of a file's own conventions ("leave duration out for
// forever", a burst that fits the capacity) stay in
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
/// m/s, each end: a magnitude; the shape's direction gives the way.
inline constexpr FieldRule kSpeed = FieldRule::number(Bounds::nonNegative());
/// rad, rad/s, each end (a file gives degrees).
inline constexpr FieldRule kRotation = FieldRule::number(Bounds::any());
inline constexpr FieldRule kAngularVelocity = FieldRule::number(Bounds::any());
/// rad: the half-angle of a cone of directions (a file gives [0, 180] degrees).
/// The float pi (just above the real one) is the top: 180 degrees converted
/// in float arithmetic is that value.
inline constexpr FieldRule kSpread = FieldRule::number(Bounds::between(0.0, static_cast<double>(glm::pi<float>())));
/// m: a sphere of radius 0 is a point.
inline constexpr FieldRule kSphereRadius = FieldRule::number(Bounds::nonNegative());
/// m: a disk and a cone need a rim (a cone's launch angle grows from 0 on its
/// axis to `spread` at its rim: radius 0 would launch everything along the axis).
inline constexpr FieldRule kRimRadius = FieldRule::number(Bounds::positive());
/// m, each, of a box.
inline constexpr FieldRule kHalfExtent = FieldRule::number(Bounds::nonNegative());
/// s: >= 0 is how long the emitter runs, < 0 forever (a file leaves it out).
inline constexpr FieldRule kDuration = FieldRule::number(Bounds::any());
/// A file asks for at least 1 and at most `capacity`.
inline constexpr FieldRule kBurstCount = FieldRule::whole(Bounds::between(0, kEmitterMaxBurstCount));
/// `color`: linear RGB, each channel (above 1 is brighter than white, for
/// additive light), and an opacity in [0, 1].
inline constexpr FieldRule kColorChannel = FieldRule::number(Bounds::nonNegative());
inline constexpr FieldRule kColorAlpha = FieldRule::number(Bounds::unit());
/// A curve key's time: the particle's normalised age (over-life curves) or
/// speed (over-speed curves).
inline constexpr FieldRule kCurveTime = FieldRule::number(Bounds::unit());
/// A curve key's value: a colour curve's factor per channel (alpha included)
/// or a size curve's factor.
inline constexpr FieldRule kCurveFactor = FieldRule::number(Bounds::nonNegative());
/// Share of a carrying body's velocity a particle is born with.
inline constexpr FieldRule kInheritVelocity = FieldRule::number(Bounds::unit());
/// m/s, each end of the speeds the over-speed curves span.
inline constexpr FieldRule kOverSpeed = FieldRule::number(Bounds::nonNegative());
/// Particles a sub-emitter makes per parent event.
inline constexpr FieldRule kSpawnCount = FieldRule::whole(Bounds::between(1, kMaxSpawnPerEvent));
/// Share of the parent particle's velocity a sub-emitted particle inherits.
inline constexpr FieldRule kSpawnInherit = FieldRule::number(Bounds::unit());
/// Positions a trail keeps: 0 (none) or 2 and more (one point is no ribbon).
inline constexpr FieldRule kTrailPoints = FieldRule::whole(Bounds::between(0, kMaxTrailPoints));
inline constexpr FieldRule kTrailWidth = FieldRule::number(Bounds::positive());  ///< m

}  // namespace spindrift::emitter_rules
