#version 450
// The liquid surface's field, step 1 (src/render/surface_pass.cpp): one quad
// per particle covering its kernel, drawn additively into the
// reduced-resolution field. centre.w is the kernel's radius, axis its
// velocity stretch (major semi-axis / radius), shade.x its amplitude and
// shade.y its foam (src/render/surface_field.cpp).
#include "frame.glsl"

layout(std430, set = SD_SPLAT_SET, binding = SD_SPLAT_BINDING_INSTANCES) readonly buffer Splats {
    SplatInstance splats[];
};

layout(location = 0) out vec2 local;
layout(location = 1) out vec2 weight;  // x amplitude (spread over the stretched area), y foam

void main() {
    SplatInstance s = splats[gl_InstanceIndex];
    vec2 corner = quadCorner(gl_VertexIndex);
    local = corner;
    vec2 a = vec2(dot(s.axis.xyz, frame.right.xyz), dot(s.axis.xyz, frame.up.xyz));
    float len = length(a);
    a = len > 1e-4 ? a / len : vec2(1.0, 0.0);
    float stretch = mix(1.0, max(s.axis.w, 1.0), min(len, 1.0));
    // The stretched kernel covers `stretch` times the area: the same volume
    // of water, spread thinner.
    weight = vec2(s.shade.x / stretch, s.shade.y);
    vec3 axisA = a.x * frame.right.xyz + a.y * frame.up.xyz;
    vec3 axisB = -a.y * frame.right.xyz + a.x * frame.up.xyz;
    float r = s.centre.w;
    vec3 world = s.centre.xyz + axisA * (corner.x * r * stretch) + axisB * (corner.y * r);
    gl_Position = frame.viewProj * vec4(world, 1.0);
}
