#version 450
// The screen-space liquid, spheres (src/render/screen_fluid_pass.cpp): one
// camera-facing quad per particle, push.pass.w in radius, for its view depth
// (screen_fluid_depth.frag) and its thickness (screen_fluid_thickness.frag).
// shade.y of the instance is the particle's foam (surface_field.cpp).
#include "screen_fluid.glsl"

layout(std430, set = SD_SPLAT_SET, binding = SD_SPLAT_BINDING_INSTANCES) readonly buffer Splats {
    SplatInstance splats[];
};

// xy: the quad's corner in radii; z: the centre's view depth (m); w: foam.
// One output, so that each fragment shader consumes what it reads of it.
layout(location = 0) out vec4 sphere;

void main() {
    SplatInstance s = splats[gl_InstanceIndex];
    vec2 corner = quadCorner(gl_VertexIndex);
    float r = push.pass.w;
    sphere = vec4(corner, dot(s.centre.xyz - frame.eye.xyz, frame.forward.xyz), s.shade.y);
    vec3 world = s.centre.xyz + (frame.right.xyz * corner.x + frame.up.xyz * corner.y) * r;
    gl_Position = frame.viewProj * vec4(world, 1.0);
}
