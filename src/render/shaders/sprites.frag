#version 450
// A sprite's colour for additive and sorted "over" blending: the sprite
// image (a flipbook frame), or a soft round spot (1 - r^2)^2 that falls
// smoothly to zero at the quad's inscribed circle; faded near opaque
// geometry (sprite_shading.glsl).
#include "sprite_shading.glsl"

layout(location = 0) out vec4 outColour;

void main() {
    outColour = spriteFragment();
}
