#version 450
// The screen-space liquid, steps 3 and 4: a bilateral filter of the view
// depth along one direction (across, then down; van der Laan et al. 2009,
// section 4, run separably as FleX does): a Gaussian over about two sphere
// radii on screen, each tap weighed down by how far its depth is from this
// texel's (push.pass.z m), so the surfaces of separate bodies of water in
// front of each other are not blended. Texels without water stay without.
#include "screen_fluid.glsl"

layout(set = SD_SCREEN_FLUID_SET, binding = SD_SCREEN_FLUID_BINDING_DEPTH) uniform sampler2D depthField;

layout(location = 0) in vec2 uv;
layout(location = 0) out float outDepth;

const int kMaxTaps = 12;  // each side

// The encoded depth of the nearest texel with water within `taps` along
// `dir` (1 when there is none).
float nearestWater(ivec2 at, ivec2 dir, int taps, ivec2 size) {
    for (int i = 1; i <= kMaxTaps; ++i) {
        ivec2 p = at + dir * i;
        if (i > taps || any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) {
            break;
        }
        float d = texelFetch(depthField, p, 0).r;
        if (d < 1.0) {
            return d;
        }
    }
    return 1.0;
}

void main() {
    ivec2 size = textureSize(depthField, 0);
    ivec2 at = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
    ivec2 dir = ivec2(push.pass.xy);
    float d0 = texelFetch(depthField, at, 0).r;
    // Two sphere radii on the field, in texels, at this depth (or, for a
    // texel without water, at that of its nearest water either side).
    float scale = float(size.y) / frame.up.w;
    float dRef = d0;
    if (d0 >= 1.0) {
        // A texel without water between water on both sides, at depths
        // within the falloff of each other (one surface), is filled: the
        // dips between the spheres along an edge close, and the edge is the
        // line over their tops rather than a row of scallops. A texel
        // beside one body of water, or between two far apart in depth,
        // stays without.
        // Water must lie within a sphere's radius (at most kMaxTaps / 2
        // texels) on both sides; most texels without water have none on
        // one side and stop after that scan.
        float ahead = nearestWater(at, dir, kMaxTaps / 2, size);
        float behind = ahead < 1.0 ? nearestWater(at, -dir, kMaxTaps / 2, size) : 1.0;
        if (behind >= 1.0 || abs(decodeViewDepth(ahead) - decodeViewDepth(behind)) > push.pass.z) {
            outDepth = 1.0;
            return;
        }
        float zMid = decodeViewDepth(0.5 * (ahead + behind));
        int probe = int(ceil(clamp(push.pass.w * pixelsPerMetre(zMid) * scale, 1.0, float(kMaxTaps) / 2.0)));
        if (nearestWater(at, dir, probe, size) >= 1.0 || nearestWater(at, -dir, probe, size) >= 1.0) {
            outDepth = 1.0;  // the gap is wider than a sphere's radius here: not a dip
            return;
        }
        dRef = 0.5 * (ahead + behind);
    }
    float z0 = decodeViewDepth(dRef);
    float sigma = clamp(push.pass.w * pixelsPerMetre(z0) * scale, 1.0, float(kMaxTaps) / 2.0);
    int taps = int(ceil(2.0 * sigma));
    float falloff = 1.0 / (2.0 * push.pass.z * push.pass.z);
    float sum = 0.0, weights = 0.0;
    for (int i = -taps; i <= taps; ++i) {
        ivec2 p = at + dir * i;
        if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) {
            continue;
        }
        float d = texelFetch(depthField, p, 0).r;
        if (d >= 1.0) {
            continue;
        }
        float dz = decodeViewDepth(d) - z0;
        float w = exp(-float(i * i) / (2.0 * sigma * sigma) - dz * dz * falloff);
        sum += d * w;
        weights += w;
    }
    outDepth = weights > 0.0 ? sum / weights : 1.0;
}
