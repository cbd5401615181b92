// The rules of a FluidDef's fields, named once: validateFluidDef checks them
// (so createFluid, setFluidSolver and the scene loader, which words its type
// errors with them too) and the viewer's panel takes its slider ranges from
// the same limits (include/spindrift/fluid.h).
#pragma once

#include "core/field_rules.h"

#include <spindrift/fluid.h>

namespace spindrift::fluid::rules {

inline constexpr FieldRule kDimension = FieldRule::whole(Bounds::between(2, 3));
inline constexpr FieldRule kSpacing = FieldRule::number(Bounds::positive());  ///< m
/// h (m); 0 is the default, otherwise more than the spacing (checked apart).
inline constexpr FieldRule kSmoothing = FieldRule::number(Bounds::nonNegative());
inline constexpr FieldRule kIterations = FieldRule::whole(Bounds::between(kFluidMinIterations, kFluidMaxIterations));
inline constexpr FieldRule kRelaxation = FieldRule::number(Bounds::between(kFluidMinRelaxation, kFluidMaxRelaxation));
inline constexpr FieldRule kBaumgarte = FieldRule::number(Bounds::between(kFluidMinBaumgarte, 1.0));
inline constexpr FieldRule kWarmStart = FieldRule::number(Bounds::unit());
inline constexpr FieldRule kMaxNeighbours = FieldRule::whole(Bounds::between(0, kFluidMaxNeighbours));
inline constexpr FieldRule kSubsteps = FieldRule::whole(Bounds::between(0, kFluidMaxSubsteps));
inline constexpr FieldRule kSleepSpeed = FieldRule::number(Bounds::nonNegative());  ///< m/s
inline constexpr FieldRule kSleepTime = FieldRule::number(Bounds::nonNegative());   ///< s
inline constexpr FieldRule kFriction = FieldRule::number(Bounds::nonNegative());
inline constexpr FieldRule kDensity = FieldRule::number(Bounds::positive());
inline constexpr FieldRule kCapacity = FieldRule::whole(Bounds::between(0, kFluidMaxCapacity));
inline constexpr FieldRule kRestDensity = FieldRule::number(Bounds::nonNegative());

// Jets.
inline constexpr FieldRule kJetSpeed = FieldRule::number(Bounds::positive());      ///< m/s
inline constexpr FieldRule kJetRate = FieldRule::number(Bounds::nonNegative());    ///< particles/s
inline constexpr FieldRule kJetRadius = FieldRule::number(Bounds::nonNegative());  ///< m
inline constexpr FieldRule kJetStart = FieldRule::number(Bounds::nonNegative());   ///< s
inline constexpr FieldRule kJetDuration = FieldRule::number(Bounds::any());        ///< s; < 0: forever

}  // namespace spindrift::fluid::rules
