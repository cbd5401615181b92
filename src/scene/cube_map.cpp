#include "scene/cube_map.h"

#include <algorithm>
#include <limits>

namespace spindrift::scene {

namespace {

// Far root of |origin + t dir - centre| = r; the ray leaves the sphere there.
float sphereExit(const CubeShape& s, glm::vec3 origin, glm::vec3 dir) {
    const glm::vec3 m = origin - s.center;
    const float b = glm::dot(m, dir);
    const float c = glm::dot(m, m) - s.radius * s.radius;
    const float disc = b * b - c;
    if (disc < 0.0f) {
        return -1.0f;
    }
    return -b + std::sqrt(disc);
}

// Slab test: the ray is inside the box for t in [tEnter, tExit].
float boxExit(const CubeShape& s, glm::vec3 origin, glm::vec3 dir) {
    const glm::vec3 lo = s.center - s.halfExtents;
    const glm::vec3 hi = s.center + s.halfExtents;
    float tEnter = -std::numeric_limits<float>::infinity();
    float tExit = std::numeric_limits<float>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(dir[axis]) < 1e-12f) {
            // Parallel to this slab: inside it everywhere or nowhere.
            if (origin[axis] < lo[axis] || origin[axis] > hi[axis]) {
                return -1.0f;
            }
            continue;
        }
        float ta = (lo[axis] - origin[axis]) / dir[axis];
        float tb = (hi[axis] - origin[axis]) / dir[axis];
        tEnter = std::max(tEnter, std::min(ta, tb));
        tExit = std::min(tExit, std::max(ta, tb));
    }
    return tEnter <= tExit ? tExit : -1.0f;
}

}  // namespace

float rayExitDistance(const CubeShape& shape, glm::vec3 origin, glm::vec3 dir) {
    return shape.kind == CubeShape::Kind::Sphere ? sphereExit(shape, origin, dir)
                                                 : boxExit(shape, origin, dir);
}

std::vector<float> cubeDepthsFromShapes(const std::vector<CubeShape>& shapes, glm::vec3 center,
                                        std::uint32_t res) {
    std::vector<float> depths(static_cast<std::size_t>(kCubeFaceCount) * res * res, 0.0f);
    for (std::uint32_t face = 0; face < kCubeFaceCount; ++face) {
        for (std::uint32_t j = 0; j < res; ++j) {
            for (std::uint32_t i = 0; i < res; ++i) {
                const float u = (static_cast<float>(i) + 0.5f) / static_cast<float>(res);
                const float v = (static_cast<float>(j) + 0.5f) / static_cast<float>(res);
                const glm::vec3 dir = cubeTexelDirection(face, u, v);
                // Coming in from far outside, the first surface met is the
                // union's outermost exit point along the ray from the centre.
                float depth = 0.0f;
                for (const CubeShape& shape : shapes) {
                    depth = std::max(depth, rayExitDistance(shape, center, dir));
                }
                depths[cubeTexelIndex(face, i, j, res)] = depth;
            }
        }
    }
    return depths;
}

}  // namespace spindrift::scene
