#version 450
// The liquid surface's field, step 4, at the field's resolution: the depth
// tint's input, the distance up to the surface as a share of the reach
// (frame.surface.z, uv of the frame's height), into b; r and g (the water and
// its foam) copied through.
#include "frame.glsl"

layout(set = SD_SURFACE_SET, binding = SD_SURFACE_BINDING_FIELD) uniform sampler2D field;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outField;

const int kDepthTaps = 8;

// Distance up from `at0` to the surface as a share of the reach: march up
// to the first tap in air and place the surface between it and the tap below
// where the field crosses the threshold linearly, so the depth is continuous
// (a count of the taps in water showed as bands, one per tap, close up).
// Above the frame nothing is known: the frame's top edge counts as the
// surface, so water whose surface is just out of the frame is tinted like its
// neighbours whose surface is just inside (clamped lookups counted it as
// deep water: a hard vertical seam where the surface crossed the top).
float depthBelowSurface(vec2 at0, float threshold, float reach) {
    float below = texture(field, at0).r;
    for (int i = 1; i <= kDepthTaps; ++i) {
        vec2 at = at0 - vec2(0.0, reach * float(i) / float(kDepthTaps));
        if (at.y < 0.0) {
            return min(at0.y / reach, 1.0);
        }
        float above = texture(field, at).r;
        if (above < threshold) {
            float crossing = below > threshold ? (below - threshold) / (below - above) : 0.0;
            return (float(i - 1) + crossing) / float(kDepthTaps);
        }
        below = above;
    }
    return 1.0;
}

void main() {
    float threshold = frame.surface.w;
    float reach = frame.surface.z;
    // Averaged over three columns 2 field texels apart: where the surface
    // is steep (a wave running up a wall) the depth jumps from one column to
    // the next, and a single column drew that jump as a hard vertical seam.
    vec2 across = vec2(2.0 * frame.surface.x, 0.0);
    float depth = (depthBelowSurface(uv - across, threshold, reach) + depthBelowSurface(uv, threshold, reach) +
                   depthBelowSurface(uv + across, threshold, reach)) / 3.0;
    outField = vec4(texture(field, uv).rg, depth, 0.0);
}
