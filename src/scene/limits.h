// Limits of what a scene may ask for, checked before anything is built.
#pragma once

#include "kernels/layout.glsl"

#include <spindrift/effects.h>

#include <cstddef>
#include <cstdint>

namespace spindrift::scene {

/// Emitters select colliders and forces with 32-bit masks on the GPU
/// (src/kernels/layout.glsl).
inline constexpr std::size_t kMaxColliders = kernels::SD_MAX_COLLIDERS;
inline constexpr std::size_t kMaxForces = kernels::SD_MAX_FORCES;
/// The API's limits (include/spindrift/effects.h), for the data files' headers.
inline constexpr std::int64_t kMaxFlowAxis = kFlowFieldMaxAxis;        ///< samples along one axis
inline constexpr std::int64_t kMaxFlowSamples = kFlowFieldMaxSamples;  ///< 48 MiB of vec3
inline constexpr std::int64_t kMaxTerrainAxis = kTerrainMaxAxis;
inline constexpr std::int64_t kMaxCubeResolution = kCubeMapMaxResolution;  ///< texels per face edge
inline constexpr std::int64_t kMaxThreads = 1024;
inline constexpr std::int64_t kMaxSteps = 100'000'000;

}  // namespace spindrift::scene
