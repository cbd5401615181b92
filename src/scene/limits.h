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
/// Noise evaluations a generated field may cost (curl noise, hills): samples
/// x octaves (x 3 potentials for 3D curl noise). Fields are generated while
/// the scene is read, so this bounds what `validate` spends on them: about
/// half a second in an optimised build (~130 ns an evaluation).
inline constexpr std::uint64_t kMaxNoiseEvaluations = 1u << 22;
inline constexpr std::int64_t kMaxThreads = 1024;
inline constexpr std::int64_t kMaxSteps = 100'000'000;

// What a scene's text may ask of the TOML parser (src/scene/toml_prescan.h),
// checked before toml++ sees it.
inline constexpr std::size_t kMaxSceneBytes = 16u << 20;     ///< a scene's text
inline constexpr std::size_t kMaxSceneLineBytes = 1u << 20;  ///< one line of it
inline constexpr int kMaxKeyParts = 32;     ///< parts of a dotted key or table header
inline constexpr int kMaxTomlNesting = 32;  ///< arrays, inline tables, table headers

/// A data file (`file`, `image`, `texture`): room for the largest flow field
/// (kMaxFlowSamples lines of three numbers) as text.
inline constexpr std::size_t kMaxDataFileBytes = 256u << 20;

}  // namespace spindrift::scene
