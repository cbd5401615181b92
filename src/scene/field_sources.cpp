#include "scene/field_sources.h"

#include "scene/noise.h"

#include <algorithm>
#include <cmath>

namespace spindrift::scene {

namespace {

// The three potential components use unrelated seeds and offsets so they are
// independent noises rather than shifted copies.
constexpr std::uint32_t kComponentSeed[3] = {0x1234567u, 0x89ABCDEu, 0xF1E2D3Cu};
const glm::vec3 kComponentOffset[3] = {
    {0.0f, 0.0f, 0.0f}, {31.4f, 17.9f, 5.3f}, {-12.7f, 43.1f, 23.9f}};

NoiseSample potential(int component, glm::vec3 q, const CurlNoiseParams& params) {
    return fractalNoise(q + kComponentOffset[component], params.seed ^ kComponentSeed[component],
                        params.octaves);
}

float vertex(float lo, float hi, std::uint32_t i, std::uint32_t n) {
    if (n == 1) {
        return 0.5f * (lo + hi);
    }
    return lo + (hi - lo) * (static_cast<float>(i) / static_cast<float>(n - 1));
}

template <class Fn>
void fillEachSample(FlowFieldDef& field, Fn velocityAt) {
    field.velocities.assign(static_cast<std::size_t>(field.nx) * field.ny * field.nz,
                            glm::vec3(0.0f));
    std::size_t index = 0;
    for (std::uint32_t k = 0; k < field.nz; ++k) {
        for (std::uint32_t j = 0; j < field.ny; ++j) {
            for (std::uint32_t i = 0; i < field.nx; ++i) {
                field.velocities[index++] = velocityAt(flowSamplePosition(field, i, j, k));
            }
        }
    }
}

}  // namespace

glm::vec3 flowSamplePosition(const FlowFieldDef& field, std::uint32_t i, std::uint32_t j,
                             std::uint32_t k) {
    return {vertex(field.boundsMin.x, field.boundsMax.x, i, field.nx),
            vertex(field.boundsMin.y, field.boundsMax.y, j, field.ny),
            vertex(field.boundsMin.z, field.boundsMax.z, k, field.nz)};
}

glm::vec3 curlNoise(glm::vec3 p, const CurlNoiseParams& params, bool planar) {
    const glm::vec3 q = p * params.frequency;
    if (planar) {
        // Stream function psi(x, y): v = (d psi / dy, -d psi / dx).
        const glm::vec3 g = potential(0, glm::vec3(q.x, q.y, 0.5f), params).gradient;
        return glm::vec3(g.y, -g.x, 0.0f) * params.frequency;
    }
    const glm::vec3 gx = potential(0, q, params).gradient;
    const glm::vec3 gy = potential(1, q, params).gradient;
    const glm::vec3 gz = potential(2, q, params).gradient;
    // curl (psi_x, psi_y, psi_z); the chain rule brings one factor of frequency.
    return glm::vec3(gz.y - gy.z, gx.z - gz.x, gy.x - gx.y) * params.frequency;
}

std::uint64_t curlNoiseEvaluations(const FlowFieldDef& field, std::uint32_t octaves) {
    const std::uint64_t potentials = field.nz == 1 ? 1 : 3;
    return std::uint64_t{field.nx} * field.ny * field.nz * octaves * potentials;
}

void fillCurlNoise(FlowFieldDef& field, const CurlNoiseParams& params) {
    const bool planar = field.nz == 1;
    fillEachSample(field, [&](glm::vec3 p) { return curlNoise(p, params, planar); });
    // A constant factor keeps the field divergence-free and gives `strength` a
    // meaning that does not depend on frequency or octaves.
    double sumSquares = 0.0;
    for (const glm::vec3& v : field.velocities) {
        sumSquares += static_cast<double>(glm::dot(v, v));
    }
    const double rms = std::sqrt(sumSquares / static_cast<double>(field.velocities.size()));
    const float scale = rms > 0.0 ? static_cast<float>(params.strength / rms) : 0.0f;
    for (glm::vec3& v : field.velocities) {
        v *= scale;
    }
}

void fillUniform(FlowFieldDef& field, glm::vec3 velocity) {
    fillEachSample(field, [&](glm::vec3) { return velocity; });
}

void fillVortex(FlowFieldDef& field, glm::vec3 center, glm::vec3 axis, float speed,
                float coreRadius) {
    fillEachSample(field, [&](glm::vec3 p) {
        const glm::vec3 offset = p - center;
        const glm::vec3 radial = offset - axis * glm::dot(offset, axis);
        const float d = glm::length(radial);
        if (d <= 0.0f) {
            return glm::vec3(0.0f);
        }
        const float profile = d < coreRadius ? d / coreRadius : coreRadius / d;
        return glm::cross(axis, radial / d) * (speed * profile);
    });
}

std::uint64_t hillsEvaluations(const ColliderDef& collider, std::uint32_t octaves) {
    return std::uint64_t{collider.terrainNx} * collider.terrainNz * octaves;
}

void fillHills(ColliderDef& collider, const HillParams& params) {
    const std::uint32_t nx = collider.terrainNx;
    const std::uint32_t nz = collider.terrainNz;
    collider.heights.assign(static_cast<std::size_t>(nx) * nz, 0.0f);
    float largest = 0.0f;
    for (std::uint32_t j = 0; j < nz; ++j) {
        for (std::uint32_t i = 0; i < nx; ++i) {
            const float x = vertex(0.0f, collider.terrainSizeX, i, nx) + collider.position.x;
            const float z = vertex(0.0f, collider.terrainSizeZ, j, nz) + collider.position.z;
            // y = 0.5 slices between lattice planes, where every gradient
            // component contributes (on a plane the y components drop out).
            const glm::vec3 q(x * params.frequency, 0.5f, z * params.frequency);
            const float h = fractalNoise(q, params.seed, params.octaves).value;
            collider.heights[i + static_cast<std::size_t>(nx) * j] = h;
            largest = std::max(largest, std::abs(h));
        }
    }
    const float scale = largest > 0.0f ? params.amplitude / largest : 0.0f;
    for (float& h : collider.heights) {
        h *= scale;
    }
}

}  // namespace spindrift::scene
