#version 450
// Bloom's blur between levels: four linear fetches at +-push.values.xy (uv)
// around the texel, their mean. Going down a level (offsets of one finer
// texel) each fetch lands on a corner of four finer texels, so the four
// together are a 4 x 4 box of the level above; going up (offsets of half a
// coarser texel, added onto the finer level) a tent over about 3 x 3 coarser
// texels (Jimenez 2014, "Next Generation Post Processing in Call of Duty:
// Advanced Warfare", SIGGRAPH course: a chain of downsamples, then upsamples
// added onto each level).
#include "frame.glsl"

layout(set = SD_LIGHT_SET, binding = SD_LIGHT_BINDING_SOURCE) uniform sampler2D level;
layout(push_constant) uniform Push { LightPush push; };

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outColour;

void main() {
    vec2 d = push.values.xy;
    vec3 sum = texture(level, uv + vec2(-d.x, -d.y)).rgb + texture(level, uv + vec2(d.x, -d.y)).rgb +
               texture(level, uv + vec2(-d.x, d.y)).rgb + texture(level, uv + vec2(d.x, d.y)).rgb;
    outColour = vec4(0.25 * sum, 1.0);
}
