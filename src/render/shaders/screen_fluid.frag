#version 450
// The screen-space liquid's composite (src/render/screen_fluid_pass.cpp; van
// der Laan, Green and Sainz 2009, and NVIDIA FleX's fluid renderer): from the
// smoothed view depth, the water's surface point and normal per pixel; the
// scene behind refracted along the normal and absorbed through the water's
// thickness (Beer-Lambert, the water colour being what 1 / kAbsorption m of
// it lets through), a Fresnel reflection of the sky, the sun's highlight and
// foam. Colliders in front hide it: its depth is compared here with the
// opaque depth of pass A (writing gl_FragDepth for the fixed test instead
// made the pass 4x slower on lavapipe: no early depth test). Output
// premultiplied by alpha (the coverage of the field's water at this pixel).
#include "screen_fluid.glsl"
#include "lighting.glsl"

layout(set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_SCENE_BEHIND) uniform sampler2D sceneBehind;
layout(set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_DEPTH) uniform sampler2D opaqueDepth;
layout(set = SD_SCREEN_FLUID_SET, binding = SD_SCREEN_FLUID_BINDING_DEPTH) uniform sampler2D depthField;
layout(set = SD_SCREEN_FLUID_SET, binding = SD_SCREEN_FLUID_BINDING_THICKNESS) uniform sampler2D thickness;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outColour;

// 1/m: the water colour is the light 1 / kAbsorption m of water lets through.
const float kAbsorption = 4.0;
// Light the water scatters back toward the eye, as a share of what it absorbs.
const float kScatter = 0.25;
// Normal-incidence reflectance of water (n = 1.33): ((n - 1) / (n + 1))^2.
const float kF0 = 0.02;
const float kShininess = 200.0;
const float kSpecular = 3.0;  // the sun's highlight may bloom (docs/rendering.md, "Light")
const float kFoamWhite = 0.8;
const float kReflectReach = 1.0;  // m
// m^2: depth steps below about 1 mm count as even (the tangent is central).
const float kStepFloor = 1e-6;

// The field's encoded depth at a field position (texel units, centres at
// +0.5), bilinear over the texels that hold water; w: their share.
vec2 depthAt(vec2 texel) {
    ivec2 size = textureSize(depthField, 0);
    vec2 p = texel - 0.5;
    ivec2 base = ivec2(floor(p));
    vec2 f = p - vec2(base);
    float sum = 0.0, share = 0.0;
    for (int j = 0; j <= 1; ++j) {
        for (int i = 0; i <= 1; ++i) {
            ivec2 q = clamp(base + ivec2(i, j), ivec2(0), size - 1);
            float d = texelFetch(depthField, q, 0).r;
            float w = (i == 1 ? f.x : 1.0 - f.x) * (j == 1 ? f.y : 1.0 - f.y);
            if (d < 1.0) {
                sum += d * w;
                share += w;
            }
        }
    }
    return vec2(share > 0.0 ? sum / share : 1.0, share);
}

// The surface point one field texel along `step` from `texel`; w: 1 where
// there is water there, 0 where not.
vec4 pointAt(vec2 texel, vec2 step) {
    vec2 size = vec2(textureSize(depthField, 0));
    vec2 d = depthAt(texel + step);
    return d.y > 0.0 ? vec4(viewPoint((texel + step) / size, decodeViewDepth(d.x)), 1.0) : vec4(0.0);
}

// The surface's tangent from the differences either side, each weighed by
// the other's depth step squared (van der Laan et al. 2009, section 4.2, take
// the smaller one outright): no tangent is bent across an edge, and inside a
// smooth surface the two blend without the seams a hard choice leaves. A
// side without water does not count.
vec3 tangent(vec3 here, vec4 ahead, vec4 behind) {
    vec3 a = ahead.xyz - here;
    vec3 b = here - behind.xyz;
    if (ahead.w == 0.0 || behind.w == 0.0) {
        return ahead.w != 0.0 ? a : (behind.w != 0.0 ? b : vec3(0.0));
    }
    float da = dot(a, frame.forward.xyz);
    float db = dot(b, frame.forward.xyz);
    float wa = db * db + kStepFloor;
    float wb = da * da + kStepFloor;
    return (a * wa + b * wb) / (wa + wb);
}

// The smaller of the two depth steps (m along the view) either side, 0
// where a side has no water: large on both sides only where the field's
// bilinear depth straddles a step between a drop in front and water behind,
// whose in-between depths belong to no surface.
float straddledStep(vec3 here, vec4 ahead, vec4 behind) {
    if (ahead.w == 0.0 || behind.w == 0.0) {
        return 0.0;
    }
    return min(abs(dot(ahead.xyz - here, frame.forward.xyz)), abs(dot(here - behind.xyz, frame.forward.xyz)));
}

// What the water reflects along r from p: the frame where the reflected ray
// is kReflectReach m out, if that is on the frame (a screen-space reflection
// without a march: right for a room's walls, not for what is occluded), else
// the sky. Only where the frame behind the water was copied (refraction on).
vec3 reflected(vec3 p, vec3 r, vec3 sky) {
    if (frame.waterFlags.x < 0.5) {
        return sky;
    }
    vec4 clip = frame.viewProj * vec4(p + r * kReflectReach, 1.0);
    vec2 at = clip.xy / max(clip.w, 1e-6) * 0.5 + 0.5;
    if (clip.w <= 0.0 || any(lessThan(at, vec2(0.0))) || any(greaterThan(at, vec2(1.0)))) {
        return sky;
    }
    return texture(sceneBehind, at).rgb;
}

void main() {
    vec2 t = texture(thickness, uv).rg;
    if (t.x <= 0.0) {
        discard;  // far from any water (the thickness kernel reaches past the spheres): one fetch
    }
    vec2 size = vec2(textureSize(depthField, 0));
    vec2 texel = uv * size;
    vec2 d = depthAt(texel);
    float coverage = smoothstep(0.25, 0.75, d.y);
    if (coverage <= 0.0) {
        discard;
    }
    float z = decodeViewDepth(d.x);
    vec3 p = viewPoint(uv, z);
    vec4 clip = frame.viewProj * vec4(p, 1.0);
    if (clip.z / clip.w > texelFetch(opaqueDepth, ivec2(gl_FragCoord.xy), 0).r) {
        discard;  // behind a collider
    }
    vec4 right = pointAt(texel, vec2(1.0, 0.0)), left = pointAt(texel, vec2(-1.0, 0.0));
    vec4 down = pointAt(texel, vec2(0.0, 1.0)), up = pointAt(texel, vec2(0.0, -1.0));
    vec3 dx = tangent(p, right, left);
    vec3 dy = tangent(p, down, up);
    // How far this pixel can trust its normal: 1 on a surface, toward 0
    // where it straddles a depth step of half a sphere's radius or more
    // (a drop in front of water behind). There the Fresnel reflection and
    // the highlight fade to what a surface facing the eye shows, so the
    // step does not draw a bright seam along the drop's outline.
    float step = max(straddledStep(p, right, left), straddledStep(p, down, up)) / (0.5 * push.pass.w);
    float trust = exp(-step * step);
    vec3 view = frame.eye.w > 0.5 ? -frame.forward.xyz : normalize(frame.eye.xyz - p);
    vec3 n = cross(dx, dy);
    n = dot(n, n) > 1e-24 ? normalize(n) : view;  // 1e-24 m^4: (1 um)^2 squared
    n = dot(n, view) < 0.0 ? -n : n;

    vec3 water = max(frame.waterColour.rgb, vec3(1e-3));
    vec3 through = exp(log(water) * (kAbsorption * t.x));  // water^(kAbsorption x thickness)
    // The water's own light and foam are lit by the scene (lighting.glsl);
    // the sun's highlight takes the sun's colour.
    vec3 lit = liquidLight(p, n);
    vec3 scatter = water * (vec3(1.0) - through) * (kScatter * lit);
    float fresnel = kF0 + (1.0 - kF0) * pow(1.0 - max(dot(n, view), 0.0), 5.0) * trust;
    vec3 r = reflect(-view, n);
    float skyUp = clamp(0.5 + 0.5 * dot(r, frame.up.xyz), 0.0, 1.0);
    vec3 sky = reflected(p, r, frame.backgroundTop.w > 0.5
                                   ? mix(frame.backgroundBottom.rgb, frame.backgroundTop.rgb, skyUp)
                                   : frame.backgroundTop.rgb);
    vec3 halfway = normalize(frame.sun.xyz + view);
    vec3 highlight = frame.sunColour.rgb * (kSpecular * trust * pow(max(dot(n, halfway), 0.0), kShininess));
    float foam = clamp(t.y / max(t.x, 1e-6), 0.0, 1.0) * kFoamWhite;

    vec3 light;
    float a;
    if (frame.waterFlags.x > 0.5) {
        // What is behind, offset along the normal as the screen sees it,
        // farther through thicker water (at most the refraction's reach).
        vec2 bend = vec2(dot(n, frame.right.xyz), -dot(n, frame.up.xyz));
        vec2 offset = bend * frame.waterFlags.z * min(t.x * kAbsorption, 1.5);
        vec3 behind = texture(sceneBehind, uv + offset).rgb;
        light = mix(behind * through + scatter, sky, fresnel);
        a = 1.0;
    } else {
        float opacity = 1.0 - dot(through, vec3(1.0 / 3.0));
        light = scatter + sky * fresnel;
        a = max(opacity, fresnel);
    }
    light = mix(light, vec3(0.92, 0.96, 1.0) * lit * a, foam) + highlight;
    a = mix(a, 1.0, foam);
    outColour = vec4(light * coverage, a * coverage);
}
