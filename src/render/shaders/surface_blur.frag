#version 450
// The liquid surface's field, steps 2 and 3: a 9-tap Gaussian (sigma 2
// texels) along one direction, run across, then down. Pairs of taps share
// one linear fetch between them (weights summed, offset at their weighted
// mean), so it costs 5 fetches, not 9.
#include "frame.glsl"

layout(set = SD_SURFACE_SET, binding = SD_SURFACE_BINDING_FIELD) uniform sampler2D field;
layout(push_constant) uniform Push { SurfacePush push; };

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outField;

void main() {
    // exp(-i^2 / 8) for i = 0..4 normalised over -4..4: 0.2042, 0.1802,
    // 0.1238, 0.0663, 0.0276; taps 1+2 and 3+4 merged.
    const float w0 = 0.2042, w12 = 0.3040, w34 = 0.0939;
    const float o12 = 1.4073, o34 = 3.2942;
    vec2 step = push.values.xy;
    outField = texture(field, uv) * w0 +
               (texture(field, uv + step * o12) + texture(field, uv - step * o12)) * w12 +
               (texture(field, uv + step * o34) + texture(field, uv - step * o34)) * w34;
}
