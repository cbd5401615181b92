#version 450
// Bloom, first pass: the float frame reduced to its finest bloom level
// (SD_BLOOM_DIVISOR of the frame's side), keeping only the light above the
// threshold. Each frame texel is thresholded before the average (16 exact
// fetches, not 1 filtered one), so a spark one pixel wide still blooms.
#include "frame.glsl"
#include "light.glsl"

layout(set = SD_LIGHT_SET, binding = SD_LIGHT_BINDING_SOURCE) uniform sampler2D hdrFrame;
layout(push_constant) uniform Push { LightPush push; };  // xy: level 0's size (texels)

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outColour;

void main() {
    ivec2 last = textureSize(hdrFrame, 0) - 1;
    ivec2 base = ivec2(uv * push.values.xy) * int(SD_BLOOM_DIVISOR);  // this texel's first frame texel
    vec3 sum = vec3(0.0);
    for (int y = 0; y < int(SD_BLOOM_DIVISOR); ++y) {
        for (int x = 0; x < int(SD_BLOOM_DIVISOR); ++x) {
            vec3 c = texelFetch(hdrFrame, min(base + ivec2(x, y), last), 0).rgb;
            sum += c * bloomShare(max(c.r, max(c.g, c.b)));
        }
    }
    outColour = vec4(sum / float(SD_BLOOM_DIVISOR * SD_BLOOM_DIVISOR), 1.0);
}
