// The 2D liquid surface, host side: see surface_field.h.
#include "render/surface_field.h"

#include "fluid/fluid_view.h"
#include "world/world.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace spindrift::render {
namespace {

/// Foam: speeds (m/s) from which particles start to turn white, and at which
/// they reach kFoamSpeedMost (a fast coherent jet is still water) ...
constexpr float kFoamSpeedStart = 3.0f;
constexpr float kFoamSpeedFull = 8.0f;
constexpr float kFoamSpeedMost = 0.4f;
/// ... and density ratios below which they start to, and are fully (a flat
/// top at rest is about 0.5, a thin jet 0.3: not foam; spray is).
constexpr float kFoamDensityStart = 0.2f;
constexpr float kFoamDensityFull = 0.05f;
/// The most extra length (in radii) a kernel gets from the velocity stretch
/// (kStretchTime, fluid_splats.h).
constexpr float kMaxExtraStretch = 1.0f;

float smoothstep(float edge0, float edge1, float x) {
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace

float surfaceAmplitude(float density) {
    // The kernel integrates to pi R^2 / 4 over the plane; the lattice has one
    // particle per spacing^2, so at rest the sum is pi R^2 / (4 s^2).
    const float atRest = std::numbers::pi_v<float> * kSurfaceKernelSpacings * kSurfaceKernelSpacings / 4.0f;
    const float volume = std::clamp(density > 0.0f ? 1.0f / density : kSurfaceMaxVolume, 1.0f, kSurfaceMaxVolume);
    return volume / atRest;
}

float surfaceFoam(float speed, float density) {
    return std::max(kFoamSpeedMost * smoothstep(kFoamSpeedStart, kFoamSpeedFull, speed),
                    smoothstep(kFoamDensityStart, kFoamDensityFull, density));
}

float surfaceStretch(float speed, float radius) {
    if (!(radius > 0.0f)) return 1.0f;
    return 1.0f + std::min(speed * kStretchTime / radius, kMaxExtraStretch);
}

std::size_t surfaceInstances(WorldId worldId, FluidId fluidId, bool stretch, std::vector<SplatInstance>& out) {
    const World& world = worldFromId(worldId);
    const fluid::FluidState& f = fluidStateFromId(world, fluidId);
    const float radius = kSurfaceKernelSpacings * f.def.spacing;
    std::size_t n = 0;
    auto fill = [&](const auto& v) {
        n = std::min(v.position.size(), out.size());
        for (std::size_t i = 0; i < n; ++i) {
            glm::vec3 velocity(v.velocity[i].x, v.velocity[i].y, 0.0f);
            if constexpr (requires { v.velocity[i].z; }) velocity.z = v.velocity[i].z;
            const float speed = glm::length(velocity);
            const float density = v.density[i];
            SplatInstance& s = out[i];
            s.centre.w = radius;
            s.axis = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            if (stretch && speed > 0.0f) s.axis = glm::vec4(velocity / speed, surfaceStretch(speed, radius));
            s.shade = glm::vec4(surfaceAmplitude(density), surfaceFoam(speed, density),
                                static_cast<float>(SplatKind::Water), density);
        }
    };
    if (f.def.dimension == 2) fill(fluid::viewFluid<2>(f)); else fill(fluid::viewFluid<3>(f));
    std::vector<SplatInstance> mirrors;
    for (const kernels::ColliderParams& c : world.colliders) {
        if (c.kind != kernels::SD_COLLIDER_PLANE) continue;
        const glm::vec3 normal(c.normal);
        const glm::vec3 point(c.position);
        for (std::size_t i = 0; i < n; ++i) {
            const glm::vec3 x(out[i].centre);
            const float d = glm::dot(x - point, normal);
            if (d < 0.0f || d >= radius) continue;
            SplatInstance m = out[i];
            m.centre = glm::vec4(x - 2.0f * d * normal, radius);
            const glm::vec3 axis(m.axis);
            m.axis = glm::vec4(axis - 2.0f * glm::dot(axis, normal) * normal, m.axis.w);
            mirrors.push_back(m);
        }
    }
    out.insert(out.begin() + static_cast<std::ptrdiff_t>(n), mirrors.begin(), mirrors.end());
    return n + mirrors.size();
}

std::size_t screenFluidInstances(WorldId worldId, FluidId fluidId, std::vector<SplatInstance>& out) {
    const fluid::FluidState& f = fluidStateFromId(worldFromId(worldId), fluidId);
    const float radius = kScreenSphereSpacings * f.def.spacing;
    std::size_t n = 0;
    auto fill = [&](const auto& v) {
        n = std::min(v.position.size(), out.size());
        for (std::size_t i = 0; i < n; ++i) {
            SplatInstance& s = out[i];
            s.centre.w = radius;
            s.shade = glm::vec4(1.0f, surfaceFoam(glm::length(v.velocity[i]), v.density[i]),
                                static_cast<float>(SplatKind::Water), v.density[i]);
        }
    };
    if (f.def.dimension == 2) fill(fluid::viewFluid<2>(f)); else fill(fluid::viewFluid<3>(f));
    return n;
}

float fluidSpacing(WorldId worldId, FluidId fluidId) {
    return fluidStateFromId(worldFromId(worldId), fluidId).def.spacing;
}

std::uint32_t fluidDimension(WorldId worldId, FluidId fluidId) {
    return fluidStateFromId(worldFromId(worldId), fluidId).def.dimension;
}

}  // namespace spindrift::render
