#version 450
// Simple shading so a scene reads at a glance: Lambert from the sun plus a
// hemisphere ambient term (brighter facing up), both sides lit.
#include "frame.glsl"

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 baseColour;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(worldNormal);
    if (dot(n, frame.forward.xyz) > 0.0) {
        n = -n;  // the side facing the camera
    }
    float diffuse = max(dot(n, frame.sun.xyz), 0.0);
    float ambient = 0.35 + 0.15 * n.y;
    colour = vec4(baseColour * (ambient + 0.65 * diffuse), 1.0);
}
