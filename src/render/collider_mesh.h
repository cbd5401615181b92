// Triangle meshes of what particles collide with, so a scene reads at a
// glance: the world's colliders, the fluids' obstacles and (per frame) the
// rigid bodies. Built on the CPU, drawn by mesh.vert / mesh.frag.
#pragma once

#include <spindrift/render.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace spindrift::render {

struct MeshVertex {
    glm::vec3 position;  // m
    glm::vec3 normal;    // unit
    glm::vec3 colour;    // linear RGB
    /// Texture coordinates (repeats) and the material texture's layer; a
    /// layer < 0 is untextured. Four float3 attributes, as the mesh pipeline reads them.
    glm::vec3 uvLayer{0.0f, 0.0f, -1.0f};
};
static_assert(sizeof(MeshVertex) == 48);

/// The layer of each material texture (SurfaceTexture::path) in the
/// renderer's texture array: its index here; absent paths draw untextured.
using MaterialLayers = std::vector<std::string>;

/// Half-size (m) of what stands for an unbounded plane: a slab this wide and
/// half as deep behind the plane, large against the camera's view.
float planeExtent(const CameraDef& camera, float aspect);

/// Colliders that do not move: planes (as slabs), spheres, boxes, terrain,
/// and the fluids' polygon obstacles (prisms along z), each collider in its
/// ColliderDef::colour or the default. Cube-map colliders have no mesh
/// (their shape is only known as depths) and are not drawn.
std::vector<MeshVertex> staticColliderMesh(WorldId world, float extent, const MaterialLayers& layers);

/// The world's Box2D bodies where they are now (readBodies): polygons and
/// circles as prisms along z, edges and chains as thin walls; each shape in
/// its colour (BodyShapeView::colour: the shape's, else the body's), else
/// dynamic bodies in a wood colour, static and kinematic ones in grey.
/// A textured body's texture is fixed to the body: it moves and turns with it.
std::vector<MeshVertex> bodyMesh(const std::vector<BodySnapshot>& bodies, const MaterialLayers& layers);

/// Axis-aligned box helper shared with the bodies' mesh: a box of half
/// extents `h` with world axes `axes` at `centre`.
void appendBox(std::vector<MeshVertex>& out, glm::vec3 centre, const glm::mat3& axes, glm::vec3 h, glm::vec3 colour);
/// A convex polygon in the xy plane extruded over z in [-depth, depth].
void appendPrism(std::vector<MeshVertex>& out, const std::vector<glm::vec2>& polygon, float depth, glm::vec3 colour);

}  // namespace spindrift::render
