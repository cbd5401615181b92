// The screen-space liquid's shared rules (src/render/screen_fluid_pass.cpp):
// its depth encoding and the view ray through a point of the frame.
#ifndef SPINDRIFT_SCREEN_FLUID
#define SPINDRIFT_SCREEN_FLUID
#include "frame.glsl"

layout(push_constant) uniform Push { ScreenFluidPush push; };

// View depth z (m along the view direction) as stored: (z - near) / (far -
// near), the frame's own near and far planes, so 1 (the clear) is "no water".
float encodeViewDepth(float z) {
    return clamp((z - frame.depthRange.x) / (frame.depthRange.y - frame.depthRange.x), 0.0, 1.0);
}
float decodeViewDepth(float d) {
    return frame.depthRange.x + d * (frame.depthRange.y - frame.depthRange.x);
}

// The world point at view depth z seen through uv (0..1, y down).
vec3 viewPoint(vec2 uv, float z) {
    vec2 ndc = vec2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    vec2 across = push.view.z > 0.5 ? ndc * push.view.xy : ndc * push.view.xy * z;
    return frame.eye.xyz + frame.forward.xyz * z + frame.right.xyz * across.x + frame.up.xyz * across.y;
}

// Frame pixels per metre across the view at view depth z (at the field's
// resolution multiply by its scale).
float pixelsPerMetre(float z) {
    float halfHeight = push.view.z > 0.5 ? push.view.y : push.view.y * max(z, 1e-4);
    return 0.5 * frame.up.w / halfHeight;
}

#endif
