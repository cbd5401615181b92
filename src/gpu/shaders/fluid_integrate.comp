#version 450
// The constraint fluid's integration on the device (the CPU's
// integratePositions in src/fluid/collide.cpp; rigid bodies in 2D). Passes
// (a specialization constant):
//   0 move:   each particle's sleep and creation serial carried into grid
//             order, its sleep (fluid.glsl, fluidSleepStep), its move by
//             velocity plus pseudo velocity, and the path tests that put back
//             a particle whose path crossed a collider or ends inside a
//             polygon; the substep's statistics (largest speed, depth under
//             pressure, the particles' box; from the setup's constraints the
//             closing-speed histogram, the largest compression and the
//             neighbours) reduced with integer atomics (the same in any
//             order; in shared memory first, then one global atomic per
//             workgroup), and each workgroup's sum of compression in a
//             fixed tree;
//   1 totals: the workgroups' sums added in order (one invocation), so the
//             mean compression is the same from run to run.
// The arithmetic of the move is the CPU's, operation for operation, with one
// variable per component (see fluid_solve.comp, applyImpulse).
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

layout(constant_id = 0) const uint PASS = 0u;

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
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_CONSTRAINTS) readonly buffer Constraints { vec4 constraints[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_COUNTS) readonly buffer Counts { uint counts[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_PARTIALS) buffer Partials { float partials[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_ID_IN) readonly buffer IdIn { uint idIn[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_ID) writeonly buffer Id { uint ids[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_SHAPES) readonly buffer Shapes { FluidBodyShape shapes[]; };
layout(std430, set = 0, binding = SD_FLUID_INTEGRATE_BINDING_SHAPE_CELLS) readonly buffer ShapeCells { ivec4 shapeCells[]; };

layout(push_constant) uniform Integrate { FluidIntegratePush args; };  // FluidIntegratePush in layout.glsl

vec3 readD(uint d, uint at, bool velocity) {
    if (velocity) return vec3(vs[at], vs[at + 1u], d == 3u ? vs[at + 2u] : 0.0f);
    return vec3(xs[at], xs[at + 1u], d == 3u ? xs[at + 2u] : 0.0f);
}

// The workgroup's statistics of the setup, reduced before one atomic each.
shared float groupError[SD_FLUID_INTEGRATE_WORKGROUP];
shared uint groupStored[SD_FLUID_INTEGRATE_WORKGROUP];
shared uint groupWorst[SD_FLUID_INTEGRATE_WORKGROUP];
shared uint groupBins[SD_FLUID_APPROACH_BINS];
// The move's order-free extremes, gathered per workgroup with shared-memory
// atomics and then given to the global statistics by one invocation: a
// global atomic per particle on one address serialises a GPU's whole grid.
shared uint groupFastest, groupPressedLow, groupPressedHigh;
shared uint groupLowX, groupLowY, groupLowZ, groupHighX, groupHighY, groupHighZ;

// The particles' box, which places the next substep's grid.
void addToBox(vec3 x) {
    atomicMin(groupLowX, fluidOrderKey(x.x));
    atomicMin(groupLowY, fluidOrderKey(x.y));
    atomicMin(groupLowZ, fluidOrderKey(x.z));
    atomicMax(groupHighX, fluidOrderKey(x.x));
    atomicMax(groupHighY, fluidOrderKey(x.y));
    atomicMax(groupHighZ, fluidOrderKey(x.z));
}

// The body shapes near a particle (its grid cell's, or every shape when the
// path leaves the distance within which the cell lists them all).
bool nearShape(uint key, uint k, bool everyShape) {
    return everyShape || fluidCellInShapeCells(key, shapeCells[k], args.cells.x);
}

float distance2(vec2 a, vec2 b) {
    vec2 d = a - b;
    return fluidLength(vec3(d.x, d.y, 0.0f));
}

// The path from -> to stopped before the edges of the still shapes it
// crosses, a few passes for a corner of joined segments (the CPU's
// stopBeforeStillEdges, src/fluid/body_contacts.cpp).
FluidPathEnd stopBeforeStillEdges(uint key, vec2 origin, vec2 from, vec2 to, vec2 v) {
    float reach = args.grid.w;
    bool everyShape = distance2(origin, from) > reach || distance2(origin, to) > reach;
    FluidPathEnd end;
    end.stopped = 0u;
    end.x1 = to;
    end.v = v;
    for (int pass = 0; pass < 3; ++pass) {
        bool crossed = false;
        for (uint k = 0u; k < uint(args.cells.z); ++k) {
            if (!nearShape(key, k, everyShape) || shapes[k].pad0 == 0u) continue;
            FluidPathEnd edge = fluidStopBeforeShapeEdges(shapes[k], from, end.x1, end.v);
            end.x1 = edge.x1;
            end.v = edge.v;
            crossed = crossed || edge.stopped != 0u;
        }
        if (!crossed) break;
    }
    return end;
}

// Rigid bodies at their end-of-substep poses (the CPU's pushOutOfBodies): a
// path across a still shape's edge stops before it, an end point inside a
// shape goes out through its nearest surface, and that push may not cross a
// still edge either.
FluidPathEnd pushOutOfBodies(vec3 x0, vec2 x1, vec2 v) {
    uint key = fluidGridKey(x0, 2u, vec3(args.grid.x, args.grid.y, 0.0f), args.grid.z, ivec3(args.cells.x, args.cells.y, 1));
    vec2 origin = vec2(x0.x, x0.y);
    FluidPathEnd end = stopBeforeStillEdges(key, origin, origin, x1, v);
    vec2 stopped = end.x1;
    bool everyShape = distance2(origin, stopped) > args.grid.w;
    vec2 pushed = stopped;
    for (uint k = 0u; k < uint(args.cells.z); ++k) {
        if (nearShape(key, k, everyShape)) pushed = fluidPushOutOfShape(shapes[k], pushed);
    }
    if (pushed == stopped) {
        return end;
    }
    return stopBeforeStillEdges(key, origin, stopped, pushed, end.v);
}

void move(uint i) {
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
        atomicMin(groupPressedLow, fluidOrderKey(along));
        atomicMax(groupPressedHigh, fluidOrderKey(along));
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
    if (args.carriesIds != 0u) ids[i] = idIn[from];
    if (asleep) {
        vs[d * i] = 0.0f;
        vs[d * i + 1u] = 0.0f;
        if (d == 3u) vs[d * i + 2u] = 0.0f;
        addToBox(x0);
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
        if (args.cells.z > 0) {
            FluidPathEnd end = pushOutOfBodies(x0, vec2(x1.x, x1.y), vec2(v.x, v.y));
            x1 = vec3(end.x1.x, end.x1.y, 0.0f);
            v = vec3(end.v.x, end.v.y, 0.0f);
        }
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
        atomicMax(groupFastest, floatBitsToUint(fluidLength(vec3(v.x, v.y, d == 3u ? v.z : 0.0f))));
        addToBox(vec3(x1.x, x1.y, d == 3u ? x1.z : 0.0f));
    }
    xs[d * i] = x1.x;
    xs[d * i + 1u] = x1.y;
    if (d == 3u) xs[d * i + 2u] = x1.z;
    vs[d * i] = v.x;
    vs[d * i + 1u] = v.y;
    if (d == 3u) vs[d * i + 2u] = v.z;
}

// The workgroups' sums of compression, added in workgroup order.
void addPartials() {
    if (gl_GlobalInvocationID.x != 0u) {
        return;
    }
    float sum = 0.0f;
    for (uint g = 0u; g < args.groups; ++g) {
        sum += partials[g];
    }
    stats.errorSum = sum;
}

void main() {
    if (PASS == SD_FLUID_INTEGRATE_PASS_TOTALS) {
        addPartials();
        return;
    }
    uint i = gl_GlobalInvocationID.x;
    uint local = gl_LocalInvocationID.x;
    for (uint b = local; b < SD_FLUID_APPROACH_BINS; b += SD_FLUID_INTEGRATE_WORKGROUP) {
        groupBins[b] = 0u;
    }
    if (local == 0u) {
        // Empty: no speed, empty ranges (as the host fills the statistics).
        groupFastest = 0u;
        groupPressedLow = 0xFFFFFFFFu;
        groupPressedHigh = 0u;
        groupLowX = 0xFFFFFFFFu;
        groupLowY = 0xFFFFFFFFu;
        groupLowZ = 0xFFFFFFFFu;
        groupHighX = 0u;
        groupHighY = 0u;
        groupHighZ = 0u;
    }
    barrier();
    // The setup's statistics (the CPU's setupConstraints counts them):
    // compression rho / rho0 - 1, neighbours, and the fastest closing speed.
    float error = 0.0f;
    uint stored = 0u;
    uint worst = 0u;
    if (i < args.count) {
        vec4 c = constraints[i];
        error = max(c.z - 1.0f, 0.0f);
        worst = fluidOrderKey(c.z - 1.0f);
        stored = counts[i];
        atomicAdd(groupBins[fluidApproachBin(c.w)], 1u);
        move(i);
    }
    groupError[local] = error;
    groupStored[local] = stored;
    groupWorst[local] = worst;
    barrier();
    for (uint stride = SD_FLUID_INTEGRATE_WORKGROUP / 2u; stride > 0u; stride /= 2u) {
        if (local < stride) {
            groupError[local] += groupError[local + stride];  // a fixed tree: the same sum every run
            groupStored[local] += groupStored[local + stride];
            groupWorst[local] = max(groupWorst[local], groupWorst[local + stride]);
        }
        barrier();
    }
    if (local == 0u) {
        partials[gl_WorkGroupID.x] = groupError[0];
        atomicAdd(stats.neighbours, groupStored[0]);
        atomicMax(stats.maxError, groupWorst[0]);
        atomicMax(stats.fastest, groupFastest);
        atomicMin(stats.pressedLow, groupPressedLow);
        atomicMax(stats.pressedHigh, groupPressedHigh);
        atomicMin(stats.lowX, groupLowX);
        atomicMin(stats.lowY, groupLowY);
        atomicMin(stats.lowZ, groupLowZ);
        atomicMax(stats.highX, groupHighX);
        atomicMax(stats.highY, groupHighY);
        atomicMax(stats.highZ, groupHighZ);
    }
    for (uint b = local; b < SD_FLUID_APPROACH_BINS; b += SD_FLUID_INTEGRATE_WORKGROUP) {
        if (groupBins[b] != 0u) atomicAdd(stats.approach[b], groupBins[b]);
    }
}
