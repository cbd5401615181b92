// How an effect sprite looks beyond its colour and size: the flipbook frame
// it shows, its soft-particle fade and its weight in weighted blended
// order-independent transparency. The renderer's sprite shaders and the
// tests share these (src/render/shaders/sprite_shading.glsl).
#ifndef SPINDRIFT_KERNELS_SPRITE_LOOK
#define SPINDRIFT_KERNELS_SPRITE_LOOK
#include "prelude.glsl"
SD_BEGIN

// The flipbook frames a particle shows: x the frame, y the next one, z how
// far the cross-fade to the next has gone (0 when not blending). With fps = 0
// the `frames` frames share the life evenly and the last one holds; with
// fps > 0 they play at that rate from birth and loop. Frame i is on row
// i / columns, column i % columns.
SD_FN vec3 flipbookFrames(float age, float lifetime, uint frames, float fps, uint blend) {
    float position = fps > 0.0f ? max(age, 0.0f) * fps
                                : clamp(age / lifetime, 0.0f, 1.0f) * float(frames);
    float first = floor(position);
    float weight = blend != 0u ? position - first : 0.0f;
    uint a = uint(first);
    uint b = a + 1u;
    if (fps > 0.0f) {
        a = a % frames;
        b = b % frames;
    } else {
        a = min(a, frames - 1u);
        b = min(b, frames - 1u);
    }
    vec3 result;
    result.x = float(a);
    result.y = float(b);
    result.z = weight;
    return result;
}

// Soft particles: the share of a sprite fragment kept at `gap` metres in
// front of the opaque surface behind it, fading linearly to 0 where it
// touches it over `distance` metres (0: kept whole).
SD_FN float softFade(float gap, float distance) {
    if (distance <= 0.0f) {
        return 1.0f;
    }
    return clamp(gap / distance, 0.0f, 1.0f);
}

// Weighted blended OIT (McGuire and Bavoil 2013, JCGT 2(2), eq. 7): a
// fragment's weight from its coverage and its distance z (m) along the
// view; nearer fragments count more, clamped to [1e-2, 3e3] so 16-bit float
// accumulation neither underflows nor overflows.
SD_FN float oitWeight(float alpha, float z) {
    float a = abs(z) / 5.0f;
    float b = abs(z) / 200.0f;
    float b2 = b * b;
    return alpha * clamp(10.0f / (1e-5f + a * a + b2 * b2 * b2), 1e-2f, 3e3f);
}

SD_END
#endif
