#version 450
// Colliders, obstacles and bodies: triangles with a normal and a colour each
// vertex, built on the CPU (src/render/collider_mesh.cpp).
#include "frame.glsl"

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;

layout(location = 0) out vec3 worldNormal;
layout(location = 1) out vec3 baseColour;
layout(location = 2) out vec3 worldPosition;

void main() {
    worldNormal = normal;
    baseColour = albedo;
    worldPosition = position;
    gl_Position = frame.viewProj * vec4(position, 1.0);
}
