// Generators for the data behind flow fields and terrain colliders.
//
// Flow-field samples sit at the grid's vertices (FlowFieldDef): sample i of n
// along an axis is at min + (max - min) i / (n - 1), the box's centre if n = 1.
// Terrain heights sit at cell centres, as the terrain sampler reads them
// (src/kernels/context_hooks.glsl): height i of n is at origin + size (i + 0.5) / n.
#pragma once

#include <spindrift/effects.h>

#include <cstdint>
#include <vector>

namespace spindrift::scene {

/// World position (m) of sample (i, j, k) of a flow field's grid.
glm::vec3 flowSamplePosition(const FlowFieldDef& field, std::uint32_t i, std::uint32_t j,
                             std::uint32_t k);

struct CurlNoiseParams {
    float frequency = 1.0f;  ///< noise cells per metre (1/m)
    float strength = 1.0f;   ///< root-mean-square speed of the grid (m/s)
    std::uint32_t seed = 1;
    std::uint32_t octaves = 1;
};

/// Curl of a smooth noise vector potential at p (3D), or of a stream function
/// in the xy plane when `planar` (z component 0). Divergence-free by
/// construction; not yet scaled to `strength`.
glm::vec3 curlNoise(glm::vec3 p, const CurlNoiseParams& params, bool planar);

/// Noise evaluations fillCurlNoise makes: samples x octaves, x 3 in 3D (a
/// vector potential); what kMaxNoiseEvaluations bounds.
std::uint64_t curlNoiseEvaluations(const FlowFieldDef& field, std::uint32_t octaves);

/// Fills field.velocities (bounds and resolution already set) with curl noise,
/// scaled so the root-mean-square speed over the grid equals params.strength.
/// A field with nz == 1 is planar.
void fillCurlNoise(FlowFieldDef& field, const CurlNoiseParams& params);

void fillUniform(FlowFieldDef& field, glm::vec3 velocity);

/// Rankine vortex around the line through `center` along unit `axis`: solid
/// rotation inside `coreRadius` (speed grows linearly to `speed` m/s at the
/// core's edge), free vortex outside (speed falls as coreRadius / d).
/// Positive speed turns counter-clockwise seen from the tip of `axis`.
void fillVortex(FlowFieldDef& field, glm::vec3 center, glm::vec3 axis, float speed,
                float coreRadius);

struct HillParams {
    float amplitude = 1.0f;  ///< largest |height| (m)
    float frequency = 0.2f;  ///< noise cells per metre (1/m)
    std::uint32_t seed = 1;
    std::uint32_t octaves = 3;
};

/// Noise evaluations fillHills makes: samples x octaves.
std::uint64_t hillsEvaluations(const ColliderDef& collider, std::uint32_t octaves);

/// Fills collider.heights for its terrain grid (origin, size, resolution set)
/// with fractal noise hills, scaled so the largest |height| is the amplitude.
void fillHills(ColliderDef& collider, const HillParams& params);

}  // namespace spindrift::scene
