#version 450
// The liquid surface's field, step 4, at the field's resolution: the depth
// tint's input, the share of points above this one (up to the reach,
// frame.surface.z) that are water too, into b; r and g (the water and its
// foam) copied through.
#include "frame.glsl"

layout(set = SD_SURFACE_SET, binding = SD_SURFACE_BINDING_FIELD) uniform sampler2D field;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outField;

const int kDepthTaps = 8;

void main() {
    float threshold = frame.surface.w;
    float depth = 0.0;
    for (int i = 1; i <= kDepthTaps; ++i) {
        float above = texture(field, uv - vec2(0.0, frame.surface.z * float(i) / float(kDepthTaps))).r;
        depth += smoothstep(threshold * 0.7, threshold * 1.3, above);
    }
    vec4 here = texture(field, uv);
    outField = vec4(here.rg, depth / float(kDepthTaps), 0.0);
}
