#version 450
// The constraint fluid's integration on the device (the CPU's
// integratePositions in src/fluid/collide.cpp, without rigid bodies): each
// particle's sleep (fluid.glsl, fluidSleepStep), its move by velocity plus
// pseudo velocity, and the path tests that put back a particle whose path
// crossed a collider or ends inside a polygon; the step's statistics reduced
// with integer atomics (the same in any order). The arithmetic is the CPU's,
// operation for operation, with one variable per component (see
// fluid_solve.comp, applyImpulse).
#include "types.glsl"
// collide.glsl's terrain and cube-map colliders read their maps through the
// backend's context (context_hooks.glsl); they are not fluid colliders, so
// this shader's context has none.
struct KernelContext {
    uint none;
};
float sampleTerrainHeight(KernelContext ctx, uint map, vec2 uv) { return 0.0f; }
vec4 sampleCubeMap(KernelContext ctx, uint map, vec3 direction) { return vec4(0.0f, 1.0f, 0.0f, 3.0e38f); }
#include "collide.glsl"
#include "fluid.glsl"
#include "layout.glsl"

layout(local_size_x = SD_FLUID_INTEGRATE_WORKGROUP) in;

layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_ORDER) readonly buffer Order { uint order[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_X) buffer X { float xs[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_V) buffer V { float vs[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_P) readonly buffer P { float pressure[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_MOTION) readonly buffer Motion { float motion[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_ANCHOR_IN) readonly buffer AnchorIn { float anchorIn[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_STILL_IN) readonly buffer StillIn { float stillIn[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_ANCHOR) writeonly buffer Anchor { float anchors[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_STILL) writeonly buffer Still { float stills[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_COLLIDERS) readonly buffer Colliders { ColliderParams colliders[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_POLYGONS) readonly buffer Polygons { FluidPolygon polygons[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_STATS) buffer Stats { FluidIntegrateStats stats; };

layout(push_constant) uniform Integrate { FluidIntegratePush args; };  // FluidIntegratePush in layout.glsl

vec3 readD(uint d, uint at, bool velocity) {
    if (velocity) return vec3(vs[at], vs[at + 1u], d == 3u ? vs[at + 2u] : 0.0f);
    return vec3(xs[at], xs[at + 1u], d == 3u ? xs[at + 2u] : 0.0f);
}

// A float as a uint whose order is the float's (for atomicMin and atomicMax).
uint orderKey(float f) {
    uint bits = floatBitsToUint(f);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= args.count) {
        return;
    }
    uint d = args.dimension;
    vec3 x0 = readD(d, d * i, false);
    vec3 v = readD(d, d * i, true);
    uint from = order[i];
    // Depth under pressure: the extent along gravity of the particles the
    // solver holds up (the substep rule's depth).
    if (pressure[i] > 0.0f) {
        precise float alongX = x0.x * args.down.x;
        precise float alongY = x0.y * args.down.y;
        precise float along = alongX + alongY;
        if (d == 3u) {
            precise float alongZ = x0.z * args.down.z;
            along = along + alongZ;
        }
        atomicMin(stats.pressedLow, orderKey(along));
        atomicMax(stats.pressedHigh, orderKey(along));
    }
    // Sleeping, from the particle's anchor and time still (particle order in,
    // grid order out).
    vec3 anchor = vec3(anchorIn[d * from], anchorIn[d * from + 1u], d == 3u ? anchorIn[d * from + 2u] : 0.0f);
    float still = stillIn[from];
    bool asleep = false;
    if (args.sleeps != 0u) {
        FluidSleep sleep = fluidSleepStep(x0, v, anchor, still, args.dt, args.sleepTime, args.wakeSpeed, args.drift);
        anchor = sleep.anchor;
        still = sleep.still;
        asleep = sleep.asleep;
    }
    anchors[d * i] = anchor.x;
    anchors[d * i + 1u] = anchor.y;
    if (d == 3u) anchors[d * i + 2u] = anchor.z;
    stills[i] = still;
    if (asleep) {
        vs[d * i] = 0.0f;
        vs[d * i + 1u] = 0.0f;
        if (d == 3u) vs[d * i + 2u] = 0.0f;
        return;
    }
    vec3 moving = v;
    if (args.split != 0u) {
        uint m = 2u * d * i + d;
        moving = v + vec3(motion[m], motion[m + 1u], d == 3u ? motion[m + 2u] : 0.0f);
    }
    precise float x1x = x0.x + moving.x * args.dt;
    precise float x1y = x0.y + moving.y * args.dt;
    precise float x1z = x0.z + moving.z * args.dt;
    vec3 x1 = vec3(x1x, x1y, x1z);
    bool lost = !fluidFinite(x1) || !fluidFiniteSpeed(v);
    if (!lost) {
        // Path tests: a path that crosses a plane, sphere or box ends at the
        // contact, moving no further in.
        for (uint k = 0u; k < args.colliders; ++k) {
            KernelContext none;
            none.none = 0u;
            Hit hit = intersectCollider(none, colliders[k], x0, x1);  // planes, spheres and boxes only
            if (hit.hit != 0u) {
                FluidSurface s = makeSurface(0.0f, hit.normal);
                vec3 n = d == 2u ? fluidFlatSurface(s).normal : s.normal;
                precise vec3 put = hit.point + n * SD_FLUID_SKIN;
                x1 = put;
                v = fluidWithoutInward(v, n);
            }
        }
        // Polygons: an end point inside goes out through the nearest edge.
        for (uint k = 0u; k < args.polygons; ++k) {
            FluidSurface s = fluidPolygonSurface(polygons[k], x1);
            if (s.distance < 0.0f) {
                precise float out1 = SD_FLUID_SKIN - s.distance;
                precise vec3 put = x1 + s.normal * out1;
                x1 = put;
                v = fluidWithoutInward(v, s.normal);
            }
        }
        lost = !fluidFinite(x1) || !fluidFiniteSpeed(v);
    }
    if (lost) {
        // Counted, and marked with a NaN position (the CPU removes such a
        // particle; the device's removal is a later slice).
        atomicAdd(stats.nonFinite, 1u);
        x1 = vec3(uintBitsToFloat(0x7FC00000u));
    } else {
        atomicMax(stats.fastest, floatBitsToUint(fluidLength(vec3(v.x, v.y, d == 3u ? v.z : 0.0f))));
    }
    xs[d * i] = x1.x;
    xs[d * i + 1u] = x1.y;
    if (d == 3u) xs[d * i + 2u] = x1.z;
    vs[d * i] = v.x;
    vs[d * i + 1u] = v.y;
    if (d == 3u) vs[d * i + 2u] = v.z;
}
