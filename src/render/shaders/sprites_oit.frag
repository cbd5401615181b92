#version 450
// Weighted blended order-independent transparency, accumulation (McGuire and
// Bavoil 2013, JCGT 2(2)), with one blend state for both targets (Vulkan
// needs the independentBlend feature otherwise): colour (ONE, ONE), alpha
// (ZERO, ONE_MINUS_SRC_ALPHA). Target 0: rgb sums w x premultiplied colour,
// a multiplies (1 - alpha) (the revealage); target 1 (one channel) sums
// w x alpha. oit_composite.frag resolves them. No sort: sums and products
// do not depend on the order. Always drawn in its own pass, where depth is
// read-only, so soft particles work here too.
#define SPRITE_SOFT
#include "sprite_shading.glsl"

layout(location = 0) out vec4 outSums;
layout(location = 1) out vec4 outWeights;

void main() {
    vec4 c = spriteFragment();
    float w = oitWeight(c.a, viewDistance(gl_FragCoord.z));
    outSums = vec4(c.rgb * w, c.a);
    outWeights = vec4(c.a * w);
}
