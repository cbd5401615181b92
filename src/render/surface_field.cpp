// The 2D liquid surface, host side: see surface_field.h.
#include "render/surface_field.h"

#include "fluid/fluid_view.h"
#include "world/world.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace spindrift::render {

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
            out[i] = kernels::surfaceKernel(glm::vec3(out[i].centre), velocity, v.density[i], radius, stretch ? 1u : 0u);
        }
    };
    if (f.def.dimension == 2) fill(fluid::viewFluid<2>(f)); else fill(fluid::viewFluid<3>(f));
    std::vector<SplatInstance> mirrors;
    const std::vector<glm::vec4> planes = wallPlanes(world);
    for (std::size_t p = 0; p + 1 < planes.size(); p += 2) {
        const glm::vec3 point(planes[p]), normal(planes[p + 1]);
        for (std::size_t i = 0; i < n; ++i) {
            if (kernels::mirroredByPlane(glm::vec3(out[i].centre), point, normal, radius) == 0u) continue;
            mirrors.push_back(kernels::mirrorKernel(out[i], point, normal));
        }
    }
    out.insert(out.begin() + static_cast<std::ptrdiff_t>(n), mirrors.begin(), mirrors.end());
    return n + mirrors.size();
}

std::vector<glm::vec4> wallPlanes(const World& world) {
    std::vector<glm::vec4> planes;
    for (const kernels::ColliderParams& c : world.colliders) {
        if (c.kind != kernels::SD_COLLIDER_PLANE) continue;
        planes.emplace_back(glm::vec3(c.position), 0.0f);
        planes.emplace_back(glm::vec3(c.normal), 0.0f);
    }
    return planes;
}

std::size_t screenFluidInstances(WorldId worldId, FluidId fluidId, std::vector<SplatInstance>& out) {
    const fluid::FluidState& f = fluidStateFromId(worldFromId(worldId), fluidId);
    const float radius = kScreenSphereSpacings * f.def.spacing;
    std::size_t n = 0;
    auto fill = [&](const auto& v) {
        n = std::min(v.position.size(), out.size());
        for (std::size_t i = 0; i < n; ++i) {
            glm::vec3 velocity(v.velocity[i].x, v.velocity[i].y, 0.0f);
            if constexpr (requires { v.velocity[i].z; }) velocity.z = v.velocity[i].z;
            out[i] = kernels::screenSphere(glm::vec3(out[i].centre), velocity, v.density[i], radius);
        }
    };
    if (f.def.dimension == 2) fill(fluid::viewFluid<2>(f)); else fill(fluid::viewFluid<3>(f));
    return n;
}

float fluidSpacing(WorldId worldId, FluidId fluidId) {
    return fluidSettingsFromId(worldFromId(worldId), fluidId).def.spacing;
}

std::uint32_t fluidDimension(WorldId worldId, FluidId fluidId) {
    return fluidSettingsFromId(worldFromId(worldId), fluidId).def.dimension;
}

}  // namespace spindrift::render
