#version 450
// Simple shading so a scene reads at a glance: the surface's colour, times
// its texture if it has one (SurfaceTexture), lit by the scene's light
// (lighting.glsl: ambient brighter facing up, the sun, point lights), both
// sides lit.
#include "lighting.glsl"

layout(set = SD_RENDER_SET_FRAME, binding = SD_RENDER_BINDING_MATERIALS) uniform sampler2DArray materials;

layout(location = 0) in vec3 worldNormal;
layout(location = 1) in vec3 baseColour;
layout(location = 2) in vec3 worldPosition;
layout(location = 3) in vec2 uv;
layout(location = 4) flat in float layer;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(worldNormal);
    // The side facing the camera: the normal is turned to the side of the
    // triangle's own plane (from the position's screen derivatives) that
    // faces this fragment's view ray. Testing against the view's centre line
    // lit slopes at the edge of a perspective view from behind, in dark
    // jagged patches; testing the smooth normal itself darkened the crests,
    // where a front-facing triangle's smooth normal turns away from the eye.
    vec3 toViewer = frame.eye.w > 0.5 ? -frame.forward.xyz : frame.eye.xyz - worldPosition;
    vec3 face = cross(dFdx(worldPosition), dFdy(worldPosition));
    face = dot(face, toViewer) < 0.0 ? -face : face;
    if (dot(n, face) < 0.0) {
        n = -n;
    }
    vec3 albedo = baseColour;
    if (layer >= 0.0) {
        albedo *= texture(materials, vec3(uv, layer)).rgb;
    }
    colour = vec4(albedo * surfaceLight(worldPosition, n), 1.0);
}
