#version 450
// Shading of a fluid splat (constraint-fluid talk, slides 62-68): water
// colour, brighter where the instance says (sun on upward-facing surface
// particles, splashes); the scene behind seen through the water with a
// lens-like offset (refraction, step 4); a rim highlight on surface particles
// (edges, step 5); bubbles as rings (step 7). Output premultiplied by alpha.
#include "lighting.glsl"

layout(set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_SCENE_BEHIND) uniform sampler2D sceneBehind;

layout(location = 0) in vec2 local;
layout(location = 1) in vec4 shade;
layout(location = 2) in vec2 screenAxis;
layout(location = 3) in vec3 worldCentre;
layout(location = 0) out vec4 outColour;

void main() {
    float r2 = dot(local, local);
    if (r2 >= 1.0) {
        discard;
    }
    float coverage = 1.0 - r2 * r2;  // soft edge, full in the middle
    float brightness = shade.x;
    float edge = shade.y;
    uint kind = uint(shade.z + 0.5);
    vec3 lit = liquidLight(worldCentre, frame.up.xyz);  // the scene's light (lighting.glsl)
    vec3 water = frame.waterColour.rgb * brightness * lit;
    float opacity = frame.waterColour.a;
    if (kind == SD_SPLAT_SPLASH) {  // splash: small, bright, opaque
        outColour = vec4(min(water + vec3(0.35) * lit, vec3(1.0)) * coverage, coverage);
        return;
    }
    if (kind == SD_SPLAT_BUBBLE) {  // bubble: a light ring with a clear middle
        float ring = smoothstep(0.45, 0.8, r2) * (1.0 - smoothstep(0.8, 1.0, r2));
        vec3 c = mix(water, vec3(0.85, 0.95, 1.0) * lit, 0.7);
        outColour = vec4(c * ring, ring);
        return;
    }
    vec3 c = water;
    if (frame.waterFlags.x > 0.5) {
        // The splat as a lens: the offset grows toward the rim, along the
        // local position rotated onto the screen.
        vec2 d = local.x * screenAxis + local.y * vec2(-screenAxis.y, screenAxis.x);
        vec2 uv = gl_FragCoord.xy / vec2(frame.right.w, frame.up.w);
        vec2 offset = d * sqrt(r2) * frame.waterFlags.z;
        vec3 behind = texture(sceneBehind, uv + offset).rgb;
        c = mix(behind, water, opacity);
        opacity = 1.0;
    }
    if (frame.waterFlags.y > 0.5) {
        c += vec3(0.9, 0.95, 1.0) * lit * (0.5 * edge * smoothstep(0.3, 1.0, r2));
    }
    float a = opacity * coverage;
    outColour = vec4(c * a, a);
}
