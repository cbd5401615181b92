#include "scene/noise.h"

#include <cmath>

namespace spindrift::scene {

namespace {

// Integer hash (PCG output permutation); good avalanche for lattice hashing.
std::uint32_t hash(std::uint32_t v) {
    const std::uint32_t state = v * 747796405u + 2891336453u;
    const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

std::uint32_t latticeHash(glm::ivec3 c, std::uint32_t seed) {
    std::uint32_t h = hash(seed ^ 0x9E3779B9u);
    h = hash(h ^ static_cast<std::uint32_t>(c.x));
    h = hash(h ^ static_cast<std::uint32_t>(c.y));
    return hash(h ^ static_cast<std::uint32_t>(c.z));
}

// One of the 12 cube-edge directions (Perlin 2002): no axis is favoured.
glm::vec3 latticeGradient(glm::ivec3 c, std::uint32_t seed) {
    static const glm::vec3 kDirections[12] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                              {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                              {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
    return kDirections[latticeHash(c, seed) % 12u];
}

// Quintic fade 6t^5 - 15t^4 + 10t^3 and its derivative: zero first and second
// derivatives at the lattice, so the noise is C2 across cells.
float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
float fadeDerivative(float t) { return 30.0f * t * t * (t * (t - 2.0f) + 1.0f); }

}  // namespace

NoiseSample gradientNoise(glm::vec3 p, std::uint32_t seed) {
    // Beyond 2^24 cells a float has no fraction left; clamping far below
    // INT_MAX keeps the cell index conversion defined for any finite input.
    p = glm::clamp(p, glm::vec3(-1e9f), glm::vec3(1e9f));
    const glm::vec3 cell = glm::floor(p);
    const glm::vec3 f = p - cell;
    const glm::ivec3 base(cell);
    const glm::vec3 w(fade(f.x), fade(f.y), fade(f.z));
    const glm::vec3 dw(fadeDerivative(f.x), fadeDerivative(f.y), fadeDerivative(f.z));
    NoiseSample out;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 c((corner >> 0) & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        const glm::vec3 g = latticeGradient(base + c, seed);
        const float n = glm::dot(g, f - glm::vec3(c));
        // Trilinear weight of this corner and its partial derivatives.
        const glm::vec3 k(c.x ? w.x : 1.0f - w.x, c.y ? w.y : 1.0f - w.y, c.z ? w.z : 1.0f - w.z);
        const glm::vec3 dk(c.x ? dw.x : -dw.x, c.y ? dw.y : -dw.y, c.z ? dw.z : -dw.z);
        const float weight = k.x * k.y * k.z;
        const glm::vec3 dWeight(dk.x * k.y * k.z, k.x * dk.y * k.z, k.x * k.y * dk.z);
        out.value += weight * n;
        out.gradient += dWeight * n + weight * g;
    }
    return out;
}

NoiseSample fractalNoise(glm::vec3 p, std::uint32_t seed, std::uint32_t octaves) {
    NoiseSample sum;
    float amplitude = 1.0f;
    float frequency = 1.0f;
    float total = 0.0f;
    for (std::uint32_t o = 0; o < octaves; ++o) {
        const NoiseSample s = gradientNoise(p * frequency, seed + 101u * o);
        sum.value += amplitude * s.value;
        sum.gradient += (amplitude * frequency) * s.gradient;
        total += amplitude;
        amplitude *= 0.5f;
        frequency *= 2.0f;
    }
    sum.value /= total;
    sum.gradient /= total;
    return sum;
}

}  // namespace spindrift::scene
