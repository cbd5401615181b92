#version 450
// The screen-space liquid, step 1: the nearest sphere's front surface, as
// encoded view depth in the depth attachment (no colour).
#include "screen_fluid.glsl"

layout(location = 0) in vec4 sphere;  // screen_fluid_sphere.vert

void main() {
    float q2 = dot(sphere.xy, sphere.xy);
    if (q2 >= 1.0) {
        discard;
    }
    gl_FragDepth = encodeViewDepth(sphere.z - push.pass.w * sqrt(1.0 - q2));
}
