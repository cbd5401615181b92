// What every sprite fragment shader shares (sprites.frag, sprites_soft.frag,
// sprites_oit.frag): the coverage (sprite image, flipbook frames, or the soft
// round spot) and, where SPRITE_SOFT is defined, the soft-particle fade
// against the opaque depth. Only those shaders touch the depth, so the
// others can draw inside pass A, where depth is still being written.
#ifndef SPINDRIFT_RENDER_SPRITE_SHADING
#define SPINDRIFT_RENDER_SPRITE_SHADING
#include "frame.glsl"
#include "sprite_look.glsl"

#ifdef SPRITE_SOFT
layout(set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_DEPTH) uniform sampler2D opaqueDepth;
#endif
layout(set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_IMAGE) uniform sampler2D spriteImage;

layout(push_constant) uniform Draw { SpriteDraw draw; };  // SpriteDraw in layout.glsl

layout(location = 0) in vec4 colour;         // linear, premultiplied by alpha
layout(location = 1) in vec2 local;          // quad coordinates, -1..1, y up
layout(location = 2) flat in vec4 cells;     // flipbook: xy this frame's column and row, zw the next frame's
layout(location = 3) flat in float frameMix; // flipbook: share of the next frame

// Distance (m) along the view of a depth-buffer value: the inverse of
// orthoRH_ZO (linear) and of perspectiveRH_ZO (d = f (z - n) / (z (f - n))).
float viewDistance(float depth) {
    float n = frame.depthRange.x;
    float f = frame.depthRange.y;
    if (frame.depthRange.z > 0.5) {
        return n + depth * (f - n);
    }
    return n * f / (f - depth * (f - n));
}

// One flipbook cell, premultiplied. The image's top row is at the quad's top;
// coordinates stay half a texel inside the cell, so linear filtering never
// reads the neighbouring frame.
vec4 sheetTexel(vec2 cell) {
    vec2 grid = vec2(float(draw.columns), float(draw.rows));
    vec2 halfTexel = 0.5 / vec2(textureSize(spriteImage, 0));
    vec2 inCell = vec2(0.5 + 0.5 * local.x, 0.5 - 0.5 * local.y);
    vec2 uv = clamp((cell + inCell) / grid, cell / grid + halfTexel, (cell + 1.0) / grid - halfTexel);
    vec4 t = texture(spriteImage, uv);
    return vec4(t.rgb * t.a, t.a);
}

// The fragment's colour, premultiplied, before blending; discards outside the
// round spot.
vec4 spriteFragment() {
    vec4 c = colour;
    if (draw.textured == 1u) {
        vec4 t = sheetTexel(cells.xy);
        if (frameMix > 0.0) {
            t = mix(t, sheetTexel(cells.zw), frameMix);
        }
        c *= t;
    } else {
        float r2 = dot(local, local);
        if (r2 >= 1.0) {
            discard;
        }
        float w = (1.0 - r2) * (1.0 - r2);
        c *= w;
    }
#ifdef SPRITE_SOFT
    if (draw.softDistance > 0.0) {
        float behind = texelFetch(opaqueDepth, ivec2(gl_FragCoord.xy), 0).r;
        c *= softFade(viewDistance(behind) - viewDistance(gl_FragCoord.z), draw.softDistance);
    }
#endif
    return c;
}

#endif
