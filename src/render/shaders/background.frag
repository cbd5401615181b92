#version 450
// The background: one colour, a vertical gradient, or an image over the frame.
#include "frame.glsl"

layout(set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_BACKGROUND) uniform sampler2D backgroundImage;

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 colour;

void main() {
    uint kind = uint(frame.backgroundTop.w);
    vec3 c = frame.backgroundTop.rgb;
    if (kind == 1u) {
        c = mix(frame.backgroundTop.rgb, frame.backgroundBottom.rgb, uv.y);  // uv.y = 0 at the top row
    } else if (kind == 2u) {
        c = texture(backgroundImage, uv).rgb;
    }
    colour = vec4(c, 1.0);
}
