#version 450
// Colliders, obstacles and bodies: triangles with a normal, a colour and
// texture coordinates each vertex, built on the CPU
// (src/render/collider_mesh.cpp).
#include "frame.glsl"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
layout(location = 3) in vec3 uvLayer;  // repeats; the material layer (< 0: none)

layout(location = 0) out vec3 worldNormal;
layout(location = 1) out vec3 baseColour;
layout(location = 2) out vec3 worldPosition;
layout(location = 3) out vec2 uv;
layout(location = 4) flat out float layer;

void main() {
    worldNormal = normal;
    baseColour = albedo;
    worldPosition = position;
    uv = uvLayer.xy;
    layer = uvLayer.z;
    gl_Position = frame.viewProj * vec4(position, 1.0);
}
