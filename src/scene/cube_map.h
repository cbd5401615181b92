// Depth cube maps made from shapes. Addressing (cubeFaceUv and
// cubeTexelDirection, in core/cube_map.h) is shared with the backends.
//
// Faces are in Vulkan layer order +x, -x, +y, -y, +z, -z, and (u, v) follow the
// major-axis table of the Vulkan specification ("Cube Map Face Selection and
// Transformations"), so a direction sampled on the GPU lands on the texel the
// CPU wrote:
//
//   face  major   sc    tc    ma          u = (sc / |ma| + 1) / 2
//   +x    +rx    -rz   -ry    rx          v = (tc / |ma| + 1) / 2
//   -x    -rx    +rz   -ry    rx
//   +y    +ry    +rx   +rz    ry
//   -y    -ry    +rx   -rz    ry
//   +z    +rz    +rx   -ry    rz
//   -z    -rz    -rx   -ry    rz
//
// Texel (i, j) of a res x res face has its centre at u = (i + 0.5) / res,
// v = (j + 0.5) / res, and is stored at index (face * res + j) * res + i.
#pragma once

#include "core/cube_map.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace spindrift {

inline constexpr std::uint32_t kCubeFaceCount = 6;

/// Index of texel (i, j) of `face` in a res x res cube map.
inline std::size_t cubeTexelIndex(std::uint32_t face, std::uint32_t i, std::uint32_t j,
                                  std::uint32_t res) {
    return (static_cast<std::size_t>(face) * res + j) * res + i;
}

namespace scene {

/// A solid the cube-map collider is made from; positions in world space (m).
struct CubeShape {
    enum class Kind { Sphere, Box } kind = Kind::Sphere;
    glm::vec3 center{0.0f};
    float radius = 1.0f;          ///< sphere
    glm::vec3 halfExtents{0.5f};  ///< axis-aligned box
};

/// Distance (m) from `origin` along unit `dir` to where the ray finally leaves
/// the shape (its outermost surface point); negative if it never does ahead.
float rayExitDistance(const CubeShape& shape, glm::vec3 origin, glm::vec3 dir);

/// Depth cube map of the union of `shapes` seen from `center`: for each texel
/// direction the distance to the outermost surface of the union along that
/// ray, 6 * res * res values in the order of cubeTexelIndex().
std::vector<float> cubeDepthsFromShapes(const std::vector<CubeShape>& shapes, glm::vec3 center,
                                        std::uint32_t res);

}  // namespace scene
}  // namespace spindrift
