#version 450
// The liquid surface's composite (src/render/surface_pass.cpp): the blurred
// field cut at its threshold into an anti-aliased edge; inside, what is
// behind refracted by the field's gradient, a tint that deepens with the
// water above, foam where the particles are fast or sparse, and a bright rim
// along the edge lit from the sun. Output premultiplied by alpha.
#include "lighting.glsl"

layout(set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_SCENE_BEHIND) uniform sampler2D sceneBehind;
layout(set = SD_SURFACE_SET, binding = SD_SURFACE_BINDING_FIELD) uniform sampler2D field;

layout(location = 0) out vec4 outColour;

// Rim width as a fraction of the frame's height, and its strength.
const float kRimWidth = 0.004;
const float kRimStrength = 0.7;
// Foam: how white it gets.
const float kFoamWhite = 0.7;

void main() {
    vec2 size = vec2(frame.right.w, frame.up.w);
    vec2 uv = gl_FragCoord.xy / size;
    vec2 texel = frame.surface.xy;
    float threshold = frame.surface.w;
    vec4 here = texture(field, uv);  // r water, g foam x water, b depth (surface_depth.frag)
    float f = here.r;
    // The field's gradient per frame pixel (the quad's derivatives: one
    // fetch), and from it the signed distance to the edge in pixels.
    vec2 g = vec2(dFdx(f), dFdy(f));
    float slope = max(length(g), 1e-5);
    float inside = (f - threshold) / slope;  // pixels inside the edge (negative outside)
    float coverage = clamp(inside + 0.5, 0.0, 1.0);
    if (coverage <= 0.0) {
        discard;
    }
    float depth = here.b;
    // The liquid's own colours are lit by the scene (lighting.glsl).
    vec3 lit = liquidLight(pixelOnPlaneZ0(uv), frame.up.xyz);
    vec3 water = frame.waterColour.rgb;
    vec3 tint = mix(water * 1.1 + vec3(0.02, 0.03, 0.04), water * 0.55, depth);
    float opacity = mix(frame.waterColour.a, min(1.0, frame.waterColour.a + 0.3), depth);
    vec3 light = tint * opacity;  // premultiplied
    float a = opacity;
    // Foam: the kernels' foam, averaged.
    float foam = clamp(here.g / max(f, 1e-4), 0.0, 1.0);
    light = mix(light, vec3(0.92, 0.96, 1.0), foam * kFoamWhite);
    a = mix(a, 1.0, foam * kFoamWhite);
    // Rim: within a few pixels of the edge, brighter where the surface faces
    // the sun (the outward normal is -g; screen y grows downward).
    vec2 normal = -g / slope;
    vec2 sun = vec2(dot(frame.sun.xyz, frame.right.xyz), -dot(frame.sun.xyz, frame.up.xyz));
    float facing = length(sun) > 1e-4 ? max(dot(normal, normalize(sun)), 0.0) : 0.0;
    float rim = exp(-max(inside, 0.0) / max(kRimWidth * size.y, 0.5));
    light += vec3(0.85, 0.93, 1.0) * (kRimStrength * rim * (0.35 + 0.65 * facing));
    a = max(a, min(1.0, kRimStrength * rim));
    light *= lit;
    if (frame.waterFlags.x > 0.5) {
        // Refraction: what is behind, seen through a lens shaped by the field.
        // The field's change per field texel, times 4 x the strength: about
        // the strength at the edge, where the field climbs over ~5 texels.
        vec2 offset = -g * size * texel * (4.0 * frame.waterFlags.z);
        float reach = 1.5 * frame.waterFlags.z;
        offset *= min(1.0, reach / max(length(offset), 1e-6));
        vec3 behind = texture(sceneBehind, uv + offset).rgb;
        outColour = vec4((behind * (1.0 - a) + light) * coverage, coverage);
    } else {
        outColour = vec4(light * coverage, a * coverage);
    }
}
