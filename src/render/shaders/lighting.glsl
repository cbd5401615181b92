// The scene's light on a surface (docs/rendering.md, "Light"): the sky's
// ambient (brighter facing up), the sun (Lambert) and the point lights, each
// scaled by its colour in FrameUniforms. With the default colours (1, 1, 1)
// and no point lights a surface gets 0.35 + 0.15 n.y + 0.65 max(n.sun, 0)
// of its colour, as before lights had colours.
#ifndef SPINDRIFT_RENDER_LIGHTING
#define SPINDRIFT_RENDER_LIGHTING
#include "frame.glsl"

// A point light's share at `p` for a surface of normal `n`: a smooth
// falloff to 0 at the light's reach, (1 - (d/r)^2)^2, times a wrapped
// Lambert term (half the light on a surface edge-on to it, as the front of a
// 2D scene's bodies is to a fire in their plane).
vec3 pointLights(vec3 p, vec3 n) {
    vec3 sum = vec3(0.0);
    int count = min(int(frame.ambient.w + 0.5), int(SD_MAX_LIGHTS));
    for (int i = 0; i < count; ++i) {
        vec3 toLight = frame.lightPosition[i].xyz - p;
        float reach = frame.lightPosition[i].w;
        float q = dot(toLight, toLight) / (reach * reach);
        if (q >= 1.0) {
            continue;
        }
        float facing = dot(n, toLight) * inversesqrt(max(dot(toLight, toLight), 1e-8));
        float falloff = (1.0 - q) * (1.0 - q);
        sum += frame.lightColour[i].rgb * (falloff * max(0.5 + 0.5 * facing, 0.0));
    }
    return sum;
}

// What multiplies an opaque surface's colour.
vec3 surfaceLight(vec3 p, vec3 n) {
    float diffuse = max(dot(n, frame.sun.xyz), 0.0);
    return frame.ambient.rgb * (0.35 + 0.15 * n.y) + frame.sunColour.rgb * (0.65 * diffuse) + pointLights(p, n);
}

// What multiplies the liquid's own colours (tint, foam, rim, highlight): the
// mean of the sky's and the sun's colours, 1 by default, plus the point
// lights as on a surface facing them.
vec3 liquidLight(vec3 p, vec3 n) {
    return 0.5 * (frame.ambient.rgb + frame.sunColour.rgb) + pointLights(p, n);
}

// The world point a pixel (uv in [0, 1], y down) shows in the plane z = 0,
// where 2D scenes live: the pixel's ray, from the near to the far plane,
// cut by that plane.
vec3 pixelOnPlaneZ0(vec2 uv) {
    vec4 a = frame.invViewProj * vec4(2.0 * uv - 1.0, 0.0, 1.0);
    vec4 b = frame.invViewProj * vec4(2.0 * uv - 1.0, 1.0, 1.0);
    vec3 near = a.xyz / a.w, far = b.xyz / b.w;
    float dz = far.z - near.z;
    float s = abs(dz) > 1e-9 ? clamp(-near.z / dz, 0.0, 1.0) : 0.0;
    return mix(near, far, s);
}

#endif
