#version 450
// sprites.frag for soft particles: the same colour, faded by the gap to the
// opaque depth behind it (sprite_shading.glsl); drawn in pass B, where the
// depth is read-only.
#define SPRITE_SOFT
#include "sprite_shading.glsl"

layout(location = 0) out vec4 outColour;

void main() {
    outColour = spriteFragment();
}
