// What every render pipeline reads: the camera and the frame's settings
// (FrameUniforms in src/kernels/layout.glsl, shared with the renderer's C++).
#ifndef SPINDRIFT_RENDER_FRAME
#define SPINDRIFT_RENDER_FRAME
#include "render_layout.glsl"

layout(std140, set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_FRAME) uniform Frame { FrameUniforms frame; };

// The quad corner of vertex `v` of two triangles (-1..1 in both axes).
vec2 quadCorner(int v) {
    const vec2 corners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                    vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
    return corners[v];
}

// A point outside the clip volume: a vertex of an instance not drawn.
const vec4 kCulled = vec4(2.0, 2.0, 2.0, 1.0);

#endif
