#version 450
// The liquid surface's field, step 4, at the field's resolution: the depth
// tint's input, the water above within the reach as a share of it
// (frame.surface.z, uv of the frame's height), into b; r and g (the water and
// its foam) copied through.
#include "frame.glsl"

layout(set = SD_SURFACE_SET, binding = SD_SURFACE_BINDING_FIELD) uniform sampler2D field;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outField;

const int kDepthTaps = 8;

// The water above `at0` within the reach, as a share of the reach: the
// length of the vertical segment [at0 - reach, at0] that lies in water, the
// field taken as linear between taps, so each piece between two taps counts
// its water up to where the field crosses the threshold. Under a flat
// surface at distance d this is d / reach, continuous in d (a count of the
// taps in water showed as bands, one per tap, close up). A pocket of air
// above takes only its own height off: the first air going up, used before,
// jumped from the pocket to the surface at the pocket's side and drew deep
// water as bright and dark columns with vertical edges. Above the frame
// nothing is known: the frame's top edge counts as air, so water whose
// surface is just out of the frame is tinted like its neighbours whose
// surface is just inside (clamped lookups counted it as deep water: a hard
// vertical seam where the surface crossed the top).
float waterAbove(vec2 at0, float threshold, float reach) {
    float below = texture(field, at0).r;
    float water = 0.0;
    for (int i = 1; i <= kDepthTaps; ++i) {
        vec2 at = at0 - vec2(0.0, reach * float(i) / float(kDepthTaps));
        float above = at.y < 0.0 ? 0.0 : texture(field, at).r;
        bool wetBelow = below >= threshold;
        bool wetAbove = above >= threshold;
        if (wetBelow && wetAbove) {
            water += 1.0;
        } else if (wetBelow != wetAbove) {
            // The share of the piece on the wet side of the crossing.
            water += (max(below, above) - threshold) / abs(below - above);
        }
        below = above;
    }
    return water / float(kDepthTaps);
}

void main() {
    float threshold = frame.surface.w;
    float reach = frame.surface.z;
    // Averaged over a tent of five columns 3 field texels apart: where the
    // surface is steep (a wave's front, a wave running up a wall) the water
    // above changes fast from one column to the next, and one column, or
    // three 2 texels apart, drew that change as a vertical seam in deep water.
    float spacing = 3.0 * frame.surface.x;
    const float kWeights[5] = float[5](1.0, 2.0, 3.0, 2.0, 1.0);
    float depth = 0.0;
    for (int c = 0; c < 5; ++c) {
        depth += kWeights[c] * waterAbove(uv + vec2(float(c - 2) * spacing, 0.0), threshold, reach);
    }
    depth /= 9.0;
    outField = vec4(texture(field, uv).rg, depth, 0.0);
}
