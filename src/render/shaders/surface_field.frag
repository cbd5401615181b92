#version 450
// The liquid surface's field, step 1: a smooth kernel (1 - q^2)^3 per
// particle, summed (additive blending into R16G16B16A16_SFLOAT): r the
// water, g the water weighted by its foam.
#include "frame.glsl"

layout(location = 0) in vec2 local;
layout(location = 1) in vec2 weight;
layout(location = 0) out vec4 outField;

void main() {
    float q2 = dot(local, local);
    if (q2 >= 1.0) {
        discard;
    }
    float k = 1.0 - q2;
    float w = weight.x * k * k * k;
    outField = vec4(w, w * weight.y, 0.0, 0.0);
}
