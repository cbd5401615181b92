// Sampled data the forces and colliders read: flow-velocity grids, terrain
// height maps and depth cube maps, with CPU samplers that follow Vulkan's
// linear filtering (texel centres at (i + 0.5) / n, clamp to edge), so the CPU
// backend and a GPU sampler read the same field.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace spindrift {

struct FlowGrid {
    std::uint32_t nx = 0, ny = 0, nz = 0;
    std::vector<glm::vec3> velocity;  // x fastest (m/s)
};

struct HeightMap {
    std::uint32_t nx = 0, nz = 0;
    std::vector<float> height;  // x fastest (m)
};

struct DepthCubeMap {
    std::uint32_t resolution = 0;
    std::vector<glm::vec4> texels;  // 6 faces of res x res: outward normal xyz, depth w (m)
};

/// All sampled data of one world, indexed by ForceParams::flowField and
/// ColliderParams::dataIndex.
struct FieldSet {
    std::vector<FlowGrid> flows;
    std::vector<HeightMap> heights;
    std::vector<DepthCubeMap> cubes;
};

glm::vec3 sampleFlow(const FlowGrid& grid, glm::vec3 uvw);
float sampleHeight(const HeightMap& map, glm::vec2 uv);
glm::vec4 sampleCube(const DepthCubeMap& cube, glm::vec3 direction);

/// Builds a cube map's texels from its depths, with per-texel outward normals
/// from the surface points of neighbouring texels.
DepthCubeMap makeDepthCubeMap(std::uint32_t resolution, const std::vector<float>& depths);

}  // namespace spindrift
