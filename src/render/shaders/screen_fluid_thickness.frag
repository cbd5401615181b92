#version 450
// The screen-space liquid, step 2: the water's thickness along the view, a
// smooth kernel (1 - q^2)^3 per particle summed (additive, no depth test),
// the same weighted by foam. The kernel is two spacings wide (push.pass.w),
// wide enough that a lattice of them sums to an even thickness with no
// moire of the lattice, and scaled so that its integral over the screen
// plane is the particle's own volume, spacing^3 (push.pass.z): a column of
// water L deep sums to L.
#include "screen_fluid.glsl"

layout(location = 0) in vec4 sphere;  // screen_fluid_sphere.vert
layout(location = 0) out vec4 outThickness;

void main() {
    float q2 = dot(sphere.xy, sphere.xy);
    if (q2 >= 1.0) {
        discard;
    }
    float w = 1.0 - q2;
    float thickness = push.pass.z * w * w * w;
    outThickness = vec4(thickness, thickness * sphere.w, 0.0, 0.0);
}
