#version 450
// Simple shading so a scene reads at a glance: the scene's light
// (lighting.glsl: ambient brighter facing up, the sun, point lights), both
// sides lit.
#include "lighting.glsl"

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 baseColour;
layout(location = 2) in vec3 worldPosition;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(worldNormal);
    if (dot(n, frame.forward.xyz) > 0.0) {
        n = -n;  // the side facing the camera
    }
    colour = vec4(baseColour * surfaceLight(worldPosition, n), 1.0);
}
