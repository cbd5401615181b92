#version 450
// The liquid surface's composite: one large quad in the 2D fluids' plane
// (z = 0) around the camera's target, so colliders in front of that plane
// (the slabs of a tank's walls and floor) hide the liquid behind them.
#include "frame.glsl"

layout(push_constant) uniform Push { SurfacePush push; };  // values.x: half side of the quad (m)

void main() {
    vec2 corner = quadCorner(gl_VertexIndex);
    // Where the view ray through the eye meets z = 0 (the eye itself when it
    // runs along the plane).
    float t = abs(frame.forward.z) > 1e-4 ? max(0.0, -frame.eye.z / frame.forward.z) : 0.0;
    vec2 centre = frame.eye.xy + frame.forward.xy * t;
    gl_Position = frame.viewProj * vec4(centre + corner * push.values.x, 0.0, 1.0);
}
