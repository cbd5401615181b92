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

// --- Sprinkle's splats (slides 55-69; src/render/fluid_splats.h lists the
// steps): one oriented, stretched disc per particle -------------------------

// Rule 2: radius multiplier sqrt(rho / rho0) clamped to this range: a lone
// particle (rho / rho0 ~ 0.1 at the default h) shrinks to 0.3, a compressed
// one grows by at most 20%.
SD_CONST float SD_SPLAT_DENSITY_SCALE_MIN = 0.3f;
SD_CONST float SD_SPLAT_DENSITY_SCALE_MAX = 1.2f;
// Rules 3 and 5: |d| (average neighbour direction) at or below which a
// particle is interior, and at or above which it is surface. On the block
// lattice |d| is 0.45 on a flat top in 2D (h = 3 spacings) and 0.30 in 3D
// (h = 2.5), one row below the top 0.06 (2D) and 0.009 (3D), and 0 deeper.
SD_CONST float SD_SPLAT_EDGE_INTERIOR = 0.08f;
SD_CONST float SD_SPLAT_EDGE_SURFACE = 0.25f;
// Rule 3: extra stretch along the surface tangent at edge factor 1 (slide
// 57: "stretch and rotate in direction of edge tangent") ...
SD_CONST float SD_SPLAT_EDGE_STRETCH = 0.8f;
// ... the most stretch (major semi-axis / radius) of the combined axis ...
SD_CONST float SD_SPLAT_MAX_STRETCH = 3.0f;
// ... the time constant (s) with which the displayed stretch follows its
// target (slide 60: temporal coherence) ...
SD_CONST float SD_SPLAT_STRETCH_TAU = 0.1f;
// ... and the fastest turn of a displayed axis (rad/s): slide 60 "allow
// small rotations"; 6 rad/s is 0.1 rad (5.7 degrees) per frame at 60 fps.
SD_CONST float SD_SPLAT_MAX_TURN_RATE = 6.0f;
// Rule 5: brightness 1 + this on a surface facing straight up (slide 58:
// "render upward facing particles in brighter color").
SD_CONST float SD_SPLAT_SUN_HIGHLIGHT = 0.5f;
// Rule 7 (slide 68): one in SD_BUBBLE_ONE_IN particles (by id) denser than
// SD_BUBBLE_DENSITY x rho0 is drawn as a bubble.
SD_CONST float SD_BUBBLE_DENSITY = 1.02f;
SD_CONST uint SD_BUBBLE_ONE_IN = 8u;
SD_CONST uint SD_BUBBLE_SALT = 0xB0BB1Eu;

// Rule 5's edge factor from |d|, d the average neighbour direction (slide
// 57): 0 in the interior, 1 on a flat surface.
SD_FN float splatEdgeFactor(float averageDirectionLength) {
    return clamp((averageDirectionLength - SD_SPLAT_EDGE_INTERIOR) / (SD_SPLAT_EDGE_SURFACE - SD_SPLAT_EDGE_INTERIOR),
                 0.0f, 1.0f);
}

// Rule 2's radius multiplier from rho / rho0 (slide 63): monotone, clamped.
SD_FN float splatDensityScale(float density) {
    return clamp(sqrt(max(density, 0.0f)), SD_SPLAT_DENSITY_SCALE_MIN, SD_SPLAT_DENSITY_SCALE_MAX);
}

// The average neighbour direction d = sum g / sum |g| (slide 57; g = w times
// the unit direction to the neighbour) from the two sums over a particle's
// list: ~0 inside, large at the surface, pointing into the fluid.
SD_FN vec3 splatAverageDirection(vec3 sumG, float sumWeights) {
    return sumWeights > 0.0f ? sumG / sumWeights : vec3(0.0f);
}

// Unit tangent of the surface whose inward direction is d (|d| > 0): in 2D d
// turned by 90 degrees; in 3D the previous axis projected onto the tangent
// plane (the most stable choice), else any tangent.
SD_FN vec3 splatSurfaceTangent(vec3 d, vec3 previousAxis, uint dimension) {
    vec3 n = normalize(d);
    if (dimension == 2u) {
        return vec3(-n.y, n.x, 0.0f);
    }
    vec3 projected = previousAxis - n * dot(previousAxis, n);
    if (length(projected) > 0.3f) {
        return normalize(projected);
    }
    vec3 helper = abs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    return normalize(cross(n, helper));
}

// Rule 3's target orientation (xyz the unit axis, w the stretch): surface
// stretch along the tangent (growing with the edge factor) plus velocity
// stretch along the velocity (growing with speed), summed as sign-free
// vectors (the velocity flipped into the tangent's hemisphere), capped at
// SD_SPLAT_MAX_STRETCH.
SD_FN vec4 splatTargetOrientation(vec3 tangent, float edge, vec3 velocity, float radius, vec3 previousAxis) {
    vec3 sum = tangent * (SD_SPLAT_EDGE_STRETCH * edge);
    float speed = length(velocity);
    if (speed > 0.0f && radius > 0.0f) {
        vec3 along = velocity / speed;
        if (dot(along, sum) < 0.0f) {
            along = -along;
        }
        sum += along * min(speed * SD_STRETCH_TIME / radius, SD_SPLAT_MAX_STRETCH - 1.0f);
    }
    float len = length(sum);
    if (!(len > 1e-6f)) {
        return vec4(previousAxis, 1.0f);
    }
    return vec4(sum / len, min(1.0f + len, SD_SPLAT_MAX_STRETCH));
}

// Rotates `previous` toward `target` (unit, sign-free: target is first
// flipped into previous's hemisphere) by at most `maxAngle` radians.
SD_FN vec3 splatTurnToward(vec3 previous, vec3 target, float maxAngle) {
    if (!(maxAngle > 0.0f)) {
        return previous;  // bit for bit: a repeated frame changes nothing
    }
    float cosine = dot(previous, target);
    vec3 toward = cosine < 0.0f ? -target : target;  // sign-free: the nearer of +-target
    float c = min(abs(cosine), 1.0f);
    float angle = acos(c);
    if (angle <= maxAngle) {
        return toward;
    }
    vec3 offAxis = toward - previous * c;
    float offLength = length(offAxis);
    if (!(offLength > 0.0f)) {
        return toward;
    }
    vec3 across = offAxis / offLength;
    return normalize(previous * cos(maxAngle) + across * sin(maxAngle));
}

// Temporal smoothing of one particle's displayed orientation (slide 60;
// xyz the axis, w the stretch) toward `target` over dt seconds.
SD_FN vec4 splatSmoothOrientation(vec4 previous, vec4 target, float dt) {
    float follow = 1.0f - exp(-max(dt, 0.0f) / SD_SPLAT_STRETCH_TAU);
    vec3 axis = splatTurnToward(vec3(previous), vec3(target), SD_SPLAT_MAX_TURN_RATE * max(dt, 0.0f));
    return vec4(axis, previous.w + (target.w - previous.w) * follow);
}

// Rule 7: whether particle `id` at density ratio `density` is drawn as a
// bubble (slide 68): a pure function, so the choice never flickers.
SD_FN uint splatIsBubble(uint id, float density) {
    return density > SD_BUBBLE_DENSITY && pcgHash(id ^ SD_BUBBLE_SALT) % SD_BUBBLE_ONE_IN == 0u ? 1u : 0u;
}

// One particle's splat and its displayed orientation after this frame
// (rules 1, 2, 3, 5, 7).
struct WaterSplat {
    SplatInstance instance;
    vec4 shown;  // xyz the axis, w the stretch (0: never seen)
};

// Rules 1, 2, 3, 5 and 7 for a particle at x moving at `velocity`, at
// density ratio `density`, whose average neighbour direction is d and whose
// orientation was shown as `shown` (w 0: never seen).
SD_FN WaterSplat splatOfParticle(vec3 x, vec3 velocity, float density, uint id, vec3 d, vec4 shown,
                                 SD_IN(SplatSteps) s) {
    WaterSplat result;
    result.shown = shown;
    // Rule 1: round, base colour (slide 62).
    result.instance.centre = vec4(x, s.radius);
    result.instance.axis = vec4(1.0f, 0.0f, 0.0f, 1.0f);
    result.instance.shade = vec4(1.0f, 0.0f, float(SD_SPLAT_WATER), density);
    // Rule 2: strays smaller (slide 63).
    if (s.sizeFromDensity != 0u) {
        result.instance.centre.w = s.radius * splatDensityScale(density);
    }
    float edge = s.stretch != 0u || s.edges != 0u ? splatEdgeFactor(length(d)) : 0.0f;
    // Rule 3: stretch along surface and velocity, smoothed (slides 57, 60, 64).
    if (s.stretch != 0u) {
        vec3 previousAxis = shown.w > 0.0f ? vec3(shown) : vec3(1.0f, 0.0f, 0.0f);
        vec3 tangent = edge > 0.0f ? splatSurfaceTangent(d, previousAxis, s.dimension) : vec3(0.0f);
        vec4 target = splatTargetOrientation(tangent, edge, velocity, s.radius, previousAxis);
        result.shown = shown.w > 0.0f ? splatSmoothOrientation(shown, target, s.up.w) : target;
        result.instance.axis = result.shown;
    }
    // Rule 5: edge factor; upward-facing surface brighter (slides 57-58, 66).
    if (s.edges != 0u) {
        result.instance.shade.y = edge;
        float len = length(d);
        if (len > 0.0f) {
            result.instance.shade.x = 1.0f + SD_SPLAT_SUN_HIGHLIGHT * max(dot(-d / len, vec3(s.up)), 0.0f) * edge;
        }
    }
    // Rule 7: a stable subset of dense particles as bubbles (slide 68).
    if (s.bubbles != 0u && splatIsBubble(id, density) != 0u) {
        result.instance.shade.z = float(SD_SPLAT_BUBBLE);
    }
    return result;
}

SD_END
#endif
