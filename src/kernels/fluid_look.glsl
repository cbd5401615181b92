// How a fluid particle looks when the liquid is drawn as one surface (issue
// 15): its kernel in the 2D surface's field, its sphere in the 3D
// screen-space liquid, the mirror image of a kernel behind a wall, and
// whether it throws a splash this frame. Written once for the host's
// instances (src/render/surface_field.cpp, fluid_splats.cpp) and the
// device's, built from a device fluid's buffers without reading them back
// (src/render/shaders/fluid_water.comp, issue 16). docs/rendering.md
// ("Liquid surface", "Fluid splats") lists the constants.
#ifndef SPINDRIFT_KERNELS_FLUID_LOOK
#define SPINDRIFT_KERNELS_FLUID_LOOK
#include "prelude.glsl"
#include "random.glsl"
#include "render_layout.glsl"
SD_BEGIN

// Kernel radius in spacings: wide enough that the sum is smooth across the
// lattice (the splats' fish scales come from discs about one spacing wide).
SD_CONST float SD_SURFACE_KERNEL_SPACINGS = 2.0f;
// Most volume a particle carries (1 / (rho / rho0) is clamped to [1, this]):
// lone drops stay visible without one stray becoming a large blob.
SD_CONST float SD_SURFACE_MAX_VOLUME = 3.0f;
// The screen-space liquid's sphere radius in spacings: wider than half a
// spacing so that the front layer of a lattice leaves no gap between spheres
// however it is seen (the cube's half diagonal is 0.87 spacing, the face's
// 0.71).
SD_CONST float SD_SCREEN_SPHERE_SPACINGS = 0.75f;
// Foam: speeds (m/s) from which particles start to turn white, and at which
// they reach SD_FOAM_SPEED_MOST (a fast coherent jet is still water) ...
SD_CONST float SD_FOAM_SPEED_START = 3.0f;
SD_CONST float SD_FOAM_SPEED_FULL = 8.0f;
SD_CONST float SD_FOAM_SPEED_MOST = 0.4f;
// ... and density ratios below which they start to, and are fully (a flat
// top at rest is about 0.5, a thin jet 0.3: not foam; spray is).
SD_CONST float SD_FOAM_DENSITY_START = 0.2f;
SD_CONST float SD_FOAM_DENSITY_FULL = 0.05f;
// Along its velocity a kernel's major semi-axis grows by the distance the
// particle moves in this time (s), like a short motion blur (slide 64) ...
SD_CONST float SD_STRETCH_TIME = 0.02f;
// ... by at most this many radii.
SD_CONST float SD_MAX_EXTRA_STRETCH = 1.0f;
// Splashes (slide 61): thrown by particles below this density ratio ...
SD_CONST float SD_SPLASH_MAX_DENSITY = 0.5f;
// ... rising faster than this (m/s, along -gravity) ...
SD_CONST float SD_SPLASH_MIN_RISE = 1.0f;
// ... each frame with probability 1 - exp(-SD_SPLASH_RATE dt) ...
SD_CONST float SD_SPLASH_RATE = 10.0f;
// ... leaving with the particle's velocity times a factor in this range, so
// neighbouring splashes fan out.
SD_CONST float SD_SPLASH_SPEED_MIN = 0.9f;
SD_CONST float SD_SPLASH_SPEED_MAX = 1.1f;
// The counter-based RNG's salt for splashes (random.glsl).
SD_CONST uint SD_SPLASH_SALT = 0x5B1A5Bu;

SD_FN float fluidLookSmoothstep(float edge0, float edge1, float x) {
    float t = clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// The surface kernel's amplitude for a particle at density ratio `density`.
// The kernel (1 - q^2)^3 integrates to pi R^2 / 4 over the plane and the
// lattice has one particle per spacing^2, so at rest the sum is
// pi R^2 / (4 s^2): the amplitude is the particle's volume over that.
SD_FN float surfaceAmplitude(float density) {
    float atRest = SD_PI * SD_SURFACE_KERNEL_SPACINGS * SD_SURFACE_KERNEL_SPACINGS / 4.0f;
    float volume = clamp(density > 0.0f ? 1.0f / density : SD_SURFACE_MAX_VOLUME, 1.0f, SD_SURFACE_MAX_VOLUME);
    return volume / atRest;
}

// Foam in [0, 1]: where particles are fast or sparse (white water).
SD_FN float surfaceFoam(float speed, float density) {
    return max(SD_FOAM_SPEED_MOST * fluidLookSmoothstep(SD_FOAM_SPEED_START, SD_FOAM_SPEED_FULL, speed),
               fluidLookSmoothstep(SD_FOAM_DENSITY_START, SD_FOAM_DENSITY_FULL, density));
}

// Major semi-axis / radius of a kernel moving at `speed` (m/s) whose radius
// is `radius` (m).
SD_FN float surfaceStretch(float speed, float radius) {
    if (!(radius > 0.0f)) {
        return 1.0f;
    }
    return 1.0f + min(speed * SD_STRETCH_TIME / radius, SD_MAX_EXTRA_STRETCH);
}

// A particle's kernel in the 2D surface's field (radius `radius` m): stretched
// along its velocity when `stretch` is not 0.
SD_FN SplatInstance surfaceKernel(vec3 x, vec3 velocity, float density, float radius, uint stretch) {
    float speed = length(velocity);
    SplatInstance s;
    s.centre = vec4(x, radius);
    s.axis = vec4(1.0f, 0.0f, 0.0f, 1.0f);
    if (stretch != 0u && speed > 0.0f) {
        s.axis = vec4(velocity / speed, surfaceStretch(speed, radius));
    }
    s.shade = vec4(surfaceAmplitude(density), surfaceFoam(speed, density), float(SD_SPLAT_WATER), density);
    return s;
}

// A particle's sphere in the 3D screen-space liquid (radius `radius` m).
SD_FN SplatInstance screenSphere(vec3 x, vec3 velocity, float density, float radius) {
    SplatInstance s;
    s.centre = vec4(x, radius);
    s.axis = vec4(1.0f, 0.0f, 0.0f, 1.0f);
    s.shade = vec4(1.0f, surfaceFoam(length(velocity), density), float(SD_SPLAT_WATER), density);
    return s;
}

// Whether a kernel centred at x of radius `radius` gets a mirror image behind
// the plane through `point` with unit normal `normal` (facing the fluid):
// when it lies in front of it, closer than its radius, so the field does not
// fall off at walls and floor (the edge would show there as a line).
SD_FN uint mirroredByPlane(vec3 x, vec3 point, vec3 normal, float radius) {
    float d = dot(x - point, normal);
    return d >= 0.0f && d < radius ? 1u : 0u;
}

// The mirror image of kernel k behind that plane.
SD_FN SplatInstance mirrorKernel(SplatInstance k, vec3 point, vec3 normal) {
    vec3 x = vec3(k.centre);
    float d = dot(x - point, normal);
    vec3 axis = vec3(k.axis);
    SplatInstance m = k;
    m.centre = vec4(x - 2.0f * d * normal, k.centre.w);
    m.axis = vec4(axis - 2.0f * dot(axis, normal) * normal, k.axis.w);
    return m;
}

// Whether the particle with serial `id` throws a splash in frame `frame`:
// sparse, rising (`up` the unit vector against gravity) and drawn with
// probability `chance` from a hash of (id, frame), so the host and the device
// pick the same particles.
SD_FN uint throwsSplash(float density, vec3 velocity, vec3 up, uint id, uint frame, float chance) {
    if (!(density < SD_SPLASH_MAX_DENSITY) || !(dot(velocity, up) > SD_SPLASH_MIN_RISE)) {
        return 0u;
    }
    uint key = pcgHash(id ^ SD_SPLASH_SALT);
    return randomUnit(key, 2u * frame) < chance ? 1u : 0u;
}

// The factor on the velocity of the splash that particle `id` throws in frame
// `frame`.
SD_FN float splashSpeedFactor(uint id, uint frame) {
    uint key = pcgHash(id ^ SD_SPLASH_SALT);
    return randomRange(key, 2u * frame + 1u, SD_SPLASH_SPEED_MIN, SD_SPLASH_SPEED_MAX);
}

SD_END
#endif
