// Meshes of colliders and obstacles (see collider_mesh.h).
#include "render/collider_mesh.h"

#include "world/world.h"

#include <spindrift/bodies.h>
#include <spindrift/fluid.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <optional>
#include <utility>
#include <cmath>

namespace spindrift::render {
namespace {

// Defaults, for what has no colour of its own (ColliderDef::colour,
// BodyDef::colour, BodyShapeDef::colour), linear RGB.
const glm::vec3 kColliderColour{0.42f, 0.40f, 0.37f};
const glm::vec3 kTerrainColour{0.30f, 0.38f, 0.22f};
const glm::vec3 kObstacleColour{0.50f, 0.45f, 0.40f};
const glm::vec3 kDynamicBodyColour{0.62f, 0.42f, 0.22f};
// Half thickness (m) of the wall drawn for an edge or chain segment.
constexpr float kSegmentHalfWidth = 0.01f;
// Depth (m) of 2D obstacles along z: they stand in front of the particles in
// the xy plane, so a wall covers the water at its edge.
constexpr float kPrismDepth = 0.5f;

// Triangles of closed shapes are wound counter-clockwise seen from outside
// (`inside` is a point within the shape), so the pipeline culls back faces:
// on lavapipe a collider slab's hidden faces cost as much as its visible ones.
void triangle(std::vector<MeshVertex>& out, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 colour,
              glm::vec3 inside) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    if (glm::dot(n, (a + b + c) / 3.0f - inside) < 0.0f) {
        std::swap(b, c);
        n = -n;
    }
    out.push_back({a, n, colour});
    out.push_back({b, n, colour});
    out.push_back({c, n, colour});
}

void quad(std::vector<MeshVertex>& out, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 colour,
          glm::vec3 inside) {
    triangle(out, a, b, c, colour, inside);
    triangle(out, a, c, d, colour, inside);
}

// Two unit vectors perpendicular to n and to each other.
glm::mat3 basisAround(glm::vec3 n) {
    glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 t = glm::normalize(glm::cross(helper, n));
    return glm::mat3(n, t, glm::cross(n, t));
}

void appendSphere(std::vector<MeshVertex>& out, glm::vec3 centre, float r, glm::vec3 colour) {
    constexpr int kRings = 12, kSegments = 24;
    auto point = [&](int i, int j) {
        float theta = glm::pi<float>() * float(i) / kRings;
        float phi = glm::two_pi<float>() * float(j) / kSegments;
        return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    for (int i = 0; i < kRings; ++i) {
        for (int j = 0; j < kSegments; ++j) {
            glm::vec3 n[4] = {point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)};
            // Counter-clockwise seen from outside (see triangle), smooth normals.
            const bool flip = glm::dot(glm::cross(n[1] - n[0], n[2] - n[0]), n[0] + n[1] + n[2]) < 0.0f;
            int order[6] = {0, 1, 2, 0, 2, 3};
            if (flip) {
                std::swap(order[1], order[2]);
                std::swap(order[4], order[5]);
            }
            for (int k : order) {
                out.push_back({centre + r * n[k], n[k], colour});
            }
        }
    }
}

// A height map's surface, both sides (it is open), each wound toward its
// viewer, with smooth normals: the surface's gradient by differences across
// each grid point (one-sided at the edges). Face normals drew each quad as a
// facet of its own and the hills as a quilt.
void appendTerrain(std::vector<MeshVertex>& out, const kernels::ColliderParams& c, const HeightMap& map,
                   glm::vec3 colour) {
    if (map.nx < 2 || map.nz < 2) {
        return;
    }
    // Every other vertex of large maps: the picture needs shape, not detail.
    const std::uint32_t stride = std::max(1u, std::max(map.nx, map.nz) / 128u);
    auto height = [&](std::uint32_t i, std::uint32_t j) { return map.height[i + std::size_t{map.nx} * j]; };
    auto x = [&](std::uint32_t i) { return c.position.x + c.grid.x * float(i) / float(map.nx - 1); };
    auto z = [&](std::uint32_t j) { return c.position.z + c.grid.y * float(j) / float(map.nz - 1); };
    auto vertex = [&](std::uint32_t i, std::uint32_t j, float side) {
        i = std::min(i, map.nx - 1);
        j = std::min(j, map.nz - 1);
        const std::uint32_t i0 = i >= stride ? i - stride : 0u, i1 = std::min(i + stride, map.nx - 1);
        const std::uint32_t j0 = j >= stride ? j - stride : 0u, j1 = std::min(j + stride, map.nz - 1);
        const float slopeX = (height(i1, j) - height(i0, j)) / (x(i1) - x(i0));
        const float slopeZ = (height(i, j1) - height(i, j0)) / (z(j1) - z(j0));
        const glm::vec3 n = glm::normalize(glm::vec3(-slopeX, 1.0f, -slopeZ));
        return MeshVertex{glm::vec3(x(i), c.position.y + height(i, j), z(j)), side * n, colour};
    };
    for (std::uint32_t j = 0; j + 1 < map.nz; j += stride) {
        for (std::uint32_t i = 0; i + 1 < map.nx; i += stride) {
            // Corners a (i, j), b (i, j+), c (i+, j+), d (i+, j): a b c and
            // a c d face up (counter-clockwise seen from above, as triangle()
            // winds them), a c b and a d c down.
            const std::uint32_t i1 = i + stride, j1 = j + stride;
            for (float side : {1.0f, -1.0f}) {
                const MeshVertex a = vertex(i, j, side), b = vertex(i, j1, side), cc = vertex(i1, j1, side),
                                 d = vertex(i1, j, side);
                if (side > 0.0f) {
                    out.insert(out.end(), {a, b, cc, a, cc, d});
                } else {
                    out.insert(out.end(), {a, cc, b, a, d, cc});
                }
            }
        }
    }
}

float layerOf(const MaterialLayers& layers, const SurfaceTexture& texture) {
    if (texture.path.empty()) return -1.0f;
    const auto it = std::find(layers.begin(), layers.end(), texture.path);
    return it == layers.end() ? -1.0f : static_cast<float>(it - layers.begin());
}

// Texture coordinates of out[first..]: each vertex's position in the
// object's frame (rotated by -angle about z around `origin`: a body's; 0 for
// colliders, which do not move), projected along its normal's main axis,
// one repeat per `scale` metres; v grows downward as the image's rows do.
void applyTexture(std::vector<MeshVertex>& out, std::size_t first, const MaterialLayers& layers,
                  const SurfaceTexture& texture, glm::vec2 origin = glm::vec2(0.0f), float angle = 0.0f) {
    const float layer = layerOf(layers, texture);
    if (layer < 0.0f) return;
    const float c = std::cos(angle), s = std::sin(angle);
    auto local = [&](glm::vec3 v, glm::vec2 shift) {
        const glm::vec2 p = glm::vec2(v) - shift;
        return glm::vec3(c * p.x + s * p.y, -s * p.x + c * p.y, v.z);
    };
    for (std::size_t i = first; i < out.size(); ++i) {
        const glm::vec3 p = local(out[i].position, origin) / texture.scale;
        const glm::vec3 n = glm::abs(local(out[i].normal, glm::vec2(0.0f)));
        const glm::vec2 uv = n.z >= n.x && n.z >= n.y ? glm::vec2(p.x, -p.y)
                             : n.y >= n.x             ? glm::vec2(p.x, p.z)
                                                      : glm::vec2(p.z, -p.y);
        out[i].uvLayer = glm::vec3(uv, layer);
    }
}

}  // namespace

float planeExtent(const CameraDef& camera, float aspect) {
    float view = camera.orthographic ? camera.orthoHeight * std::max(aspect, 1.0f)
                                     : glm::length(camera.target - camera.eye);
    return 4.0f * view + 10.0f;
}

void appendBox(std::vector<MeshVertex>& out, glm::vec3 centre, const glm::mat3& axes, glm::vec3 h, glm::vec3 colour) {
    auto corner = [&](float sx, float sy, float sz) {
        return centre + axes[0] * (sx * h.x) + axes[1] * (sy * h.y) + axes[2] * (sz * h.z);
    };
    quad(out, corner(1, -1, -1), corner(1, 1, -1), corner(1, 1, 1), corner(1, -1, 1), colour, centre);      // +x
    quad(out, corner(-1, -1, -1), corner(-1, -1, 1), corner(-1, 1, 1), corner(-1, 1, -1), colour, centre);  // -x
    quad(out, corner(-1, 1, -1), corner(-1, 1, 1), corner(1, 1, 1), corner(1, 1, -1), colour, centre);      // +y
    quad(out, corner(-1, -1, -1), corner(1, -1, -1), corner(1, -1, 1), corner(-1, -1, 1), colour, centre);  // -y
    quad(out, corner(-1, -1, 1), corner(1, -1, 1), corner(1, 1, 1), corner(-1, 1, 1), colour, centre);      // +z
    quad(out, corner(-1, -1, -1), corner(-1, 1, -1), corner(1, 1, -1), corner(1, -1, -1), colour, centre);  // -z
}

void appendPrism(std::vector<MeshVertex>& out, const std::vector<glm::vec2>& polygon, float depth, glm::vec3 colour) {
    const std::size_t n = polygon.size();
    if (n < 2) {
        return;
    }
    glm::vec2 mean(0.0f);
    for (glm::vec2 v : polygon) mean += v;
    const glm::vec3 inside(mean / float(n), 0.0f);
    auto at = [&](std::size_t i, float z) { return glm::vec3(polygon[i % n], z); };
    for (std::size_t i = 1; i + 1 < n; ++i) {  // caps: fans (the polygon is convex)
        triangle(out, at(0, depth), at(i, depth), at(i + 1, depth), colour, inside);
        triangle(out, at(0, -depth), at(i + 1, -depth), at(i, -depth), colour, inside);
    }
    for (std::size_t i = 0; i < (n == 2 ? 1 : n); ++i) {
        quad(out, at(i, -depth), at(i + 1, -depth), at(i + 1, depth), at(i, depth), colour, inside);
    }
}

std::vector<MeshVertex> staticColliderMesh(WorldId id, float extent, const MaterialLayers& layers) {
    const World& world = worldFromId(id);
    std::vector<MeshVertex> out;
    for (std::size_t i = 0; i < world.colliders.size(); ++i) {
        const kernels::ColliderParams& c = world.colliders[i];
        const glm::vec3 p(c.position);
        // A texture's own colours show on white unless a colour is given.
        const glm::vec3 colour = world.colliderDefs[i].colour.value_or(
            !world.colliderDefs[i].texture.path.empty()  ? glm::vec3(1.0f)
            : c.kind == kernels::SD_COLLIDER_TERRAIN ? kTerrainColour
                                                     : kColliderColour);
        const std::size_t first = out.size();
        switch (c.kind) {
            case kernels::SD_COLLIDER_PLANE: {
                glm::mat3 axes = basisAround(glm::vec3(c.normal));
                appendBox(out, p - axes[0] * (0.5f * extent), axes, glm::vec3(0.5f * extent, extent, extent),
                          colour);
                break;
            }
            case kernels::SD_COLLIDER_SPHERE: appendSphere(out, p, c.position.w, colour); break;
            case kernels::SD_COLLIDER_BOX:
                appendBox(out, p, glm::mat3(glm::vec3(c.axisX), glm::vec3(c.axisY), glm::vec3(c.axisZ)),
                          glm::vec3(c.halfExtents), colour);
                break;
            case kernels::SD_COLLIDER_TERRAIN:
                if (c.dataIndex < world.fields.heights.size()) {
                    appendTerrain(out, c, world.fields.heights[c.dataIndex], colour);
                }
                break;
            default: break;  // cube maps: not drawn
        }
        applyTexture(out, first, layers, world.colliderDefs[i].texture);
    }
    for (std::uint32_t f = 0; f < world.fluids.size(); ++f) {
        for (const FluidPolygonDef& polygon : fluidDef(id, FluidId{f + 1}).polygons) {
            appendPrism(out, polygon.vertices, kPrismDepth, kObstacleColour);
        }
    }
    return out;
}

namespace {

void appendSegment(std::vector<MeshVertex>& out, glm::vec2 a, glm::vec2 b, glm::vec3 colour) {
    glm::vec2 d = b - a;
    float len = glm::length(d);
    if (len <= 0.0f) {
        return;
    }
    glm::vec2 n = glm::vec2(-d.y, d.x) * (kSegmentHalfWidth / len);
    appendPrism(out, {a - n, b - n, b + n, a + n}, kPrismDepth, colour);
}

void appendBodyShape(std::vector<MeshVertex>& out, const BodyShapeView& shape, glm::vec3 colour) {
    switch (shape.kind) {
        case BodyShapeView::Kind::Circle: {
            constexpr int kSegments = 32;
            std::vector<glm::vec2> polygon;
            for (int i = 0; i < kSegments; ++i) {
                float a = glm::two_pi<float>() * float(i) / kSegments;
                polygon.push_back(shape.centre + shape.radius * glm::vec2(std::cos(a), std::sin(a)));
            }
            appendPrism(out, polygon, kPrismDepth, colour);
            break;
        }
        case BodyShapeView::Kind::Polygon: appendPrism(out, shape.vertices, kPrismDepth, colour); break;
        case BodyShapeView::Kind::Edge:
        case BodyShapeView::Kind::Chain: {
            const std::size_t n = shape.vertices.size();
            for (std::size_t i = 0; i + 1 < n; ++i) {
                appendSegment(out, shape.vertices[i], shape.vertices[i + 1], colour);
            }
            if (shape.loop && n > 2) {
                appendSegment(out, shape.vertices[n - 1], shape.vertices[0], colour);
            }
            break;
        }
    }
}

}  // namespace

std::vector<MeshVertex> bodyMesh(const std::vector<BodySnapshot>& bodies, const MaterialLayers& layers) {
    std::vector<MeshVertex> out;
    for (const BodySnapshot& body : bodies) {
        const std::size_t first = out.size();
        // A texture's own colours show on white unless a colour is given.
        const glm::vec3 fallback = !body.texture.path.empty() ? glm::vec3(1.0f)
                                   : body.dynamic               ? kDynamicBodyColour
                                                                : kObstacleColour;
        for (const BodyShapeView& shape : body.shapes) {
            appendBodyShape(out, shape, shape.colour.value_or(fallback));
        }
        applyTexture(out, first, layers, body.texture, body.position, body.angle);
    }
    return out;
}

}  // namespace spindrift::render
