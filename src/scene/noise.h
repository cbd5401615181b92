// Deterministic gradient noise (Perlin-style) with its analytic gradient, used
// to generate flow fields and terrain. Pure functions of position and seed: the
// same scene gives the same data on every machine.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace spindrift::scene {

/// Noise value and its gradient with respect to the sample position.
struct NoiseSample {
    float value = 0.0f;  ///< roughly in [-1, 1]
    glm::vec3 gradient{0.0f};
};

/// Gradient noise with one lattice cell per unit; C2-smooth (quintic fade), so
/// its analytic gradient is exact and continuous.
NoiseSample gradientNoise(glm::vec3 p, std::uint32_t seed);

/// Sum of `octaves` layers, each at twice the frequency and half the amplitude
/// of the one before, normalised so the amplitudes add up to 1.
NoiseSample fractalNoise(glm::vec3 p, std::uint32_t seed, std::uint32_t octaves);

}  // namespace spindrift::scene
