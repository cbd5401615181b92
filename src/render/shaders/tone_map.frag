#version 450
// The frame's last pass: the float frame plus its bloom, times the exposure,
// through the tone map (ACES filmic, or a plain clamp) into the 8-bit sRGB
// image that is read back or presented (the format encodes sRGB on write).
#include "frame.glsl"
#include "light.glsl"

layout(set = SD_LIGHT_SET, binding = SD_LIGHT_BINDING_SOURCE) uniform sampler2D hdrFrame;
layout(set = SD_LIGHT_SET, binding = SD_LIGHT_BINDING_BLOOM) uniform sampler2D bloom;
layout(push_constant) uniform Push { LightPush push; };

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outColour;

void main() {
    vec4 c = texelFetch(hdrFrame, ivec2(gl_FragCoord.xy), 0);
    vec3 rgb = c.rgb;
    if (push.values.y > 0.0) {
        rgb += push.values.y * texture(bloom, uv).rgb;
    }
    rgb *= push.values.x;
    if (uint(push.values.z) == SD_TONE_MAP_ACES) {
        rgb = vec3(acesFilm(rgb.r), acesFilm(rgb.g), acesFilm(rgb.b));
    } else {
        rgb = clamp(rgb, 0.0, 1.0);
    }
    outColour = vec4(rgb, clamp(c.a, 0.0, 1.0));
}
