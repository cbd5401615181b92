// What every render pipeline reads: the camera and the frame's settings
// (FrameUniforms in src/render/renderer.h; keep the two in step).
#ifndef SPINDRIFT_RENDER_FRAME
#define SPINDRIFT_RENDER_FRAME

layout(std140, set = 0, binding = 0) uniform Frame {
    mat4 viewProj;
    vec4 eye;             // xyz camera position (m); w: 1 orthographic, 0 perspective
    vec4 right;           // xyz camera right (world); w: viewport width (px)
    vec4 up;              // xyz camera up (world); w: viewport height (px)
    vec4 forward;         // xyz view direction (world); w: world time (s)
    vec4 sun;             // xyz unit direction toward the sun
    vec4 backgroundTop;   // rgb linear; w: background kind (0 colour, 1 gradient, 2 image)
    vec4 backgroundBottom;
    vec4 waterColour;     // rgb linear; a: opacity
    vec4 waterFlags;      // x refraction, y edges (0 or 1); z refraction strength (uv units)
} frame;

// The quad corner of vertex `v` of two triangles (-1..1 in both axes).
vec2 quadCorner(int v) {
    const vec2 corners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),
                                    vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));
    return corners[v];
}

// A point outside the clip volume: a vertex of an instance not drawn.
const vec4 kCulled = vec4(2.0, 2.0, 2.0, 1.0);

#endif
