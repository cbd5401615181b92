#version 450
// The liquid surface's field, steps 2 and 3: a 9-tap Gaussian (sigma 2
// texels) along one direction; run across, then down.
#include "frame.glsl"

layout(set = SD_SURFACE_SET, binding = SD_SURFACE_BINDING_FIELD) uniform sampler2D field;
layout(push_constant) uniform Push { SurfacePush push; };

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 outField;

void main() {
    // exp(-i^2 / 8) for i = 0..4, normalised over -4..4.
    const float w[5] = float[5](0.2042, 0.1802, 0.1238, 0.0663, 0.0276);
    vec4 sum = texture(field, uv) * w[0];
    for (int i = 1; i < 5; ++i) {
        vec2 o = push.values.xy * float(i);
        sum += (texture(field, uv + o) + texture(field, uv - o)) * w[i];
    }
    outField = sum;
}
