#include "particles/fields.h"

#include "core/cube_map.h"

#include <algorithm>
#include <cmath>

namespace spindrift {
namespace {

// Linear-filter footprint along one axis: the two texels and the weight of the
// second, as Vulkan computes it (coordinate u * n - 0.5, clamp to edge).
struct Footprint {
    std::uint32_t i0, i1;
    float w;
};

Footprint footprint(float u, std::uint32_t n) {
    float x = u * static_cast<float>(n) - 0.5f;
    float lo = std::floor(x);
    float w = x - lo;
    auto clampIndex = [n](float i) {
        return static_cast<std::uint32_t>(std::clamp(i, 0.0f, static_cast<float>(n - 1)));
    };
    if (!std::isfinite(x)) {
        return {0, 0, 0.0f};
    }
    return {clampIndex(lo), clampIndex(lo + 1.0f), w};
}

}  // namespace

glm::vec3 sampleFlow(const FlowGrid& g, glm::vec3 uvw) {
    Footprint fx = footprint(uvw.x, g.nx);
    Footprint fy = footprint(uvw.y, g.ny);
    Footprint fz = footprint(uvw.z, g.nz);
    auto at = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
        return g.velocity[(static_cast<std::size_t>(z) * g.ny + y) * g.nx + x];
    };
    auto row = [&](std::uint32_t y, std::uint32_t z) { return glm::mix(at(fx.i0, y, z), at(fx.i1, y, z), fx.w); };
    auto slice = [&](std::uint32_t z) { return glm::mix(row(fy.i0, z), row(fy.i1, z), fy.w); };
    return glm::mix(slice(fz.i0), slice(fz.i1), fz.w);
}

float sampleHeight(const HeightMap& m, glm::vec2 uv) {
    Footprint fx = footprint(uv.x, m.nx);
    Footprint fz = footprint(uv.y, m.nz);
    auto at = [&](std::uint32_t x, std::uint32_t z) { return m.height[static_cast<std::size_t>(z) * m.nx + x]; };
    float a = glm::mix(at(fx.i0, fz.i0), at(fx.i1, fz.i0), fx.w);
    float b = glm::mix(at(fx.i0, fz.i1), at(fx.i1, fz.i1), fx.w);
    return glm::mix(a, b, fz.w);
}

// Bilinear within the face, clamped at its edges. A GPU filters across face
// seams; the two differ only within half a texel of an edge.
glm::vec4 sampleCube(const DepthCubeMap& c, glm::vec3 direction) {
    CubeFaceUv f = cubeFaceUv(direction);
    Footprint fu = footprint(f.u, c.resolution);
    Footprint fv = footprint(f.v, c.resolution);
    std::size_t base = static_cast<std::size_t>(f.face) * c.resolution * c.resolution;
    auto at = [&](std::uint32_t u, std::uint32_t v) { return c.texels[base + static_cast<std::size_t>(v) * c.resolution + u]; };
    glm::vec4 a = glm::mix(at(fu.i0, fv.i0), at(fu.i1, fv.i0), fu.w);
    glm::vec4 b = glm::mix(at(fu.i0, fv.i1), at(fu.i1, fv.i1), fu.w);
    return glm::mix(a, b, fv.w);
}

DepthCubeMap makeDepthCubeMap(std::uint32_t res, const std::vector<float>& depths) {
    DepthCubeMap cube;
    cube.resolution = res;
    cube.texels.resize(depths.size());
    auto surfacePoint = [&](std::uint32_t face, std::uint32_t u, std::uint32_t v) {
        float fu = (static_cast<float>(u) + 0.5f) / static_cast<float>(res);
        float fv = (static_cast<float>(v) + 0.5f) / static_cast<float>(res);
        return cubeTexelDirection(face, fu, fv) * depths[(static_cast<std::size_t>(face) * res + v) * res + u];
    };
    for (std::uint32_t face = 0; face < 6; ++face) {
        for (std::uint32_t v = 0; v < res; ++v) {
            for (std::uint32_t u = 0; u < res; ++u) {
                // One-sided differences at the face edges keep every sample on this face.
                std::uint32_t u0 = u > 0 ? u - 1 : u, u1 = u + 1 < res ? u + 1 : u;
                std::uint32_t v0 = v > 0 ? v - 1 : v, v1 = v + 1 < res ? v + 1 : v;
                glm::vec3 du = surfacePoint(face, u1, v) - surfacePoint(face, u0, v);
                glm::vec3 dv = surfacePoint(face, u, v1) - surfacePoint(face, u, v0);
                glm::vec3 dir = cubeTexelDirection(face, (u + 0.5f) / res, (v + 0.5f) / res);
                glm::vec3 n = glm::cross(du, dv);
                float len = glm::length(n);
                n = len > 0.0f ? n / len : dir;
                if (glm::dot(n, dir) < 0.0f) {
                    n = -n;
                }
                std::size_t i = (static_cast<std::size_t>(face) * res + v) * res + u;
                cube.texels[i] = glm::vec4(n, depths[i]);
            }
        }
    }
    return cube;
}

}  // namespace spindrift
