#version 450
// Fluid particles as Sprinkle-style splats (constraint-fluid talk, slides
// 55-68): an ellipse in the camera plane per SplatInstance, prepared on the
// CPU from what the solver knows (src/render/fluid_splats.cpp).
#include "frame.glsl"

// SplatInstance in layout.glsl (included by frame.glsl), shared with the C++.
layout(std430, set = SD_SPLAT_SET, binding = SD_SPLAT_BINDING_INSTANCES) readonly buffer Splats {
    SplatInstance splats[];
};

layout(location = 0) out vec2 local;
layout(location = 1) out vec4 shade;
layout(location = 2) out vec2 screenAxis;  // the major axis on screen, for the refraction offset
layout(location = 3) out vec3 worldCentre;  // where the scene's light is taken

void main() {
    SplatInstance s = splats[gl_InstanceIndex];
    vec2 corner = quadCorner(gl_VertexIndex);
    local = corner;
    shade = s.shade;
    vec2 a = vec2(dot(s.axis.xyz, frame.right.xyz), dot(s.axis.xyz, frame.up.xyz));
    float len = length(a);
    a = len > 1e-4 ? a / len : vec2(1.0, 0.0);
    // A stretch seen end-on shortens with the axis' projection.
    float stretch = mix(1.0, max(s.axis.w, 1.0), min(len, 1.0));
    vec3 axisA = a.x * frame.right.xyz + a.y * frame.up.xyz;
    vec3 axisB = -a.y * frame.right.xyz + a.x * frame.up.xyz;
    float r = s.centre.w;
    vec3 world = s.centre.xyz + axisA * (corner.x * r * stretch) + axisB * (corner.y * r);
    screenAxis = a;
    gl_Position = frame.viewProj * vec4(world, 1.0);
    worldCentre = s.centre.xyz;
}
