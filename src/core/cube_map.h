// Cube-map face selection and texel directions, in Vulkan's convention (spec
// section "Cube Map Face Selection and Transformations"), so data built on the
// CPU samples the same way on the GPU. Faces: +x, -x, +y, -y, +z, -z.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace spindrift {

struct CubeFaceUv {
    std::uint32_t face = 0;
    float u = 0.0f;  // [0, 1]
    float v = 0.0f;  // [0, 1]
};

/// Face and normalised face coordinates of a direction (any length > 0).
inline CubeFaceUv cubeFaceUv(glm::vec3 d) {
    glm::vec3 a = glm::abs(d);
    float sc, tc, ma;
    std::uint32_t face;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0.0f ? 0u : 1u;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = d.y >= 0.0f ? 2u : 3u;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
        ma = a.y;
    } else {
        face = d.z >= 0.0f ? 4u : 5u;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
        ma = a.z;
    }
    return {face, 0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)};
}

/// Unit direction through face coordinates (u, v) of `face`; inverse of cubeFaceUv.
inline glm::vec3 cubeTexelDirection(std::uint32_t face, float u, float v) {
    float sc = 2.0f * u - 1.0f;
    float tc = 2.0f * v - 1.0f;
    glm::vec3 d;
    switch (face) {
        case 0: d = {1.0f, -tc, -sc}; break;
        case 1: d = {-1.0f, -tc, sc}; break;
        case 2: d = {sc, 1.0f, tc}; break;
        case 3: d = {sc, -1.0f, -tc}; break;
        case 4: d = {sc, -tc, 1.0f}; break;
        default: d = {-sc, -tc, -1.0f}; break;
    }
    return glm::normalize(d);
}

}  // namespace spindrift
