#version 450
// A sprite's coverage: the sprite image's alpha, or a soft round spot
// (1 - r^2)^2 that falls smoothly to zero at the quad's inscribed circle.
#include "layout.glsl"

layout(set = SD_SPRITE_SET, binding = SD_SPRITE_BINDING_IMAGE) uniform sampler2D spriteImage;

layout(push_constant) uniform Draw { SpriteDraw draw; };  // SpriteDraw in layout.glsl

layout(location = 0) in vec4 colour;
layout(location = 1) in vec2 local;
layout(location = 0) out vec4 outColour;

void main() {
    vec4 c = colour;
    if (draw.textured == 1u) {
        vec4 t = texture(spriteImage, local * 0.5 + 0.5);
        c *= vec4(t.rgb * t.a, t.a);
    } else {
        float r2 = dot(local, local);
        if (r2 >= 1.0) {
            discard;
        }
        float w = (1.0 - r2) * (1.0 - r2);
        c *= w;
    }
    outColour = c;
}
