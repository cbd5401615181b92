// Light after the frame is drawn into its float target (docs/rendering.md,
// "Light"): which part of a colour blooms and the filmic tone map that turns
// linear light into the 0..1 the 8-bit sRGB image holds. The renderer's
// light shaders (src/render/shaders/bloom_*.frag, tone_map.frag) and the
// tests share these.
#ifndef SPINDRIFT_KERNELS_LIGHT
#define SPINDRIFT_KERNELS_LIGHT
#include "prelude.glsl"
SD_BEGIN

// Bloom's threshold (linear light): only what is brighter than the brightest
// colour an 8-bit image can hold glows.
SD_CONST float SD_BLOOM_THRESHOLD = 1.0f;

// The share of a colour that blooms: the part of its brightest channel above
// the threshold, as a fraction of that channel, so the glow keeps the
// colour's hue (a colour times this share). 0 at or below the threshold.
SD_FN float bloomShare(float brightest) {
    return max(brightest - SD_BLOOM_THRESHOLD, 0.0f) / max(brightest, 1e-4f);
}

// The ACES filmic curve as fitted by Krzysztof Narkowicz, "ACES Filmic Tone
// Mapping Curve" (2016-01-06, knarkowicz.wordpress.com): ODT(RRT(x)) of
// the Academy Color Encoding System sampled and fitted with a rational
// function, max fit error 0.0138, input pre-exposed so that 1 maps to about
// 0.8. Per channel, clamped to [0, 1] ("saturate" in the original).
SD_FN float acesFilm(float x) {
    float a = 2.51f;
    float b = 0.03f;
    float c = 2.43f;
    float d = 0.59f;
    float e = 0.14f;
    return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

SD_END
#endif
