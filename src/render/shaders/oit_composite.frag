#version 450
// Weighted blended OIT, composite (McGuire and Bavoil 2013, eq. 6): the
// weighted average colour of the transparent fragments, covering 1 - (the
// product of their 1 - alpha); blended "over" the frame (premultiplied).
#include "frame.glsl"

layout(set = SD_OIT_SET, binding = SD_OIT_BINDING_ACCUM) uniform sampler2D sums;      // rgb sum w c a; a prod (1 - a)
layout(set = SD_OIT_SET, binding = SD_OIT_BINDING_WEIGHTS) uniform sampler2D weights;  // r sum w a

layout(location = 0) out vec4 outColour;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = texelFetch(sums, p, 0);
    float revealed = s.a;
    if (revealed >= 1.0) {
        discard;  // no transparent fragment here
    }
    vec3 average = s.rgb / max(texelFetch(weights, p, 0).r, 1e-5);
    outColour = vec4(average * (1.0 - revealed), 1.0 - revealed);
}
