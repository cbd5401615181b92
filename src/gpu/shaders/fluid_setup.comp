#version 450
// The constraint fluid's setup on the device (the CPU's setupConstraints in
// src/fluid/neighbours.cpp, slides 35 and 46-52), after the grid
// (fluid_grid.comp). Passes (a specialization constant, one small pipeline
// each):
//   0 gather:  positions, velocities (gravity x dt added) and pressures
//              into grid order;
//   1 count:   each particle's neighbours within h (at most `cap`), and each
//              workgroup's sum of them;
//   2 tiles:   the workgroups' exclusive prefix sum, in one invocation (a
//              100k fluid has 1,563 tiles: a few microseconds of additions,
//              and one fixed order);
//   3 setup:   each particle's first list entry (the tile's first plus a
//              prefix sum inside the workgroup), its list (the neighbours;
//              the solve computes each pair's g = w dir again from the
//              positions, fluidPairG), density, bias, effective mass, the gathered warm
//              start and the fastest closing speed.
// The candidates are visited in the CPU's order (the 3^D sub-cells z, y, x
// outermost first, each in grid order), so the lists are the CPU's entry for
// entry; the sums over them are added in list order, where the CPU adds
// sixteen lanes and then the lanes as a tree, so they may differ in the last bits
// (tests/gpu/gpu_fluid_setup_test.cpp states the tolerance).
#include "fluid.glsl"
#include "layout.glsl"

layout(constant_id = 0) const uint PASS = 0u;

layout(local_size_x = SD_FLUID_SETUP_WORKGROUP) in;

layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_ORDER) readonly buffer Order { uint order[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_SORTED_KEYS) readonly buffer SortedKeys { uint sortedKeys[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_KEY_START) readonly buffer KeyStart { uint keyStart[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_POSITIONS) readonly buffer Positions { float positions[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_VELOCITIES) readonly buffer Velocities { float velocities[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_PRESSURES) readonly buffer Pressures { float pressures[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_X) buffer X { float xs[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_V) buffer V { float vs[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_P) buffer P { float ps[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_WALL) readonly buffer Wall { vec4 wall[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_COUNTS) buffer Counts { uint counts[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_TILES) buffer Tiles { uint tiles[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_HEADER) buffer Header { FluidSetupHeader header; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_FIRST) writeonly buffer First { uint first[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_LIST_INDEX) writeonly buffer ListIndex { uint listIndex[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_CONSTRAINTS) writeonly buffer Constraints { vec4 constraints[]; };
layout(std430, set = 0, binding = SD_FLUID_SETUP_BINDING_WARM) writeonly buffer Warm { vec4 warm[]; };

layout(push_constant) uniform Setup { FluidSetupPush args; };  // FluidSetupPush in layout.glsl

shared uint tileCounts[SD_FLUID_SETUP_WORKGROUP];

uint dimension() { return uint(args.cells.w); }

vec3 xAt(uint i) {
    uint d = dimension();
    return vec3(xs[d * i], xs[d * i + 1u], d == 3u ? xs[d * i + 2u] : 0.0f);
}

vec3 vAt(uint i) {
    uint d = dimension();
    return vec3(vs[d * i], vs[d * i + 1u], d == 3u ? vs[d * i + 2u] : 0.0f);
}

void gather(uint i) {
    if (i >= args.count) {
        return;
    }
    uint d = dimension();
    uint from = order[i];
    for (uint a = 0u; a < d; ++a) {
        xs[d * i + a] = positions[d * from + a];
        // External forces first (semi-implicit Euler, fluid_step.cpp): the
        // constraints see this substep's weight.
        precise float v = velocities[d * from + a] + args.velocityChange[a];
        vs[d * i + a] = v;
    }
    // Capped where it is kept, as the CPU's setup does (fluidWarmCap): the
    // setup's warm start and the solve read these.
    ps[i] = fluidCappedPressure(pressures[from], args.warmCap);
}

// One particle's sums over its pairs (the CPU's PairSums).
struct PairSums {
    uint near;       // neighbours within h
    uint paired;     // of them stored (at most cap)
    uint overflows;  // left out: crushed sub-cells' particles and those past cap
    float density;   // the neighbours' W
    float mass;      // sum w^2
    float fastest;   // m/s
    vec3 gSum;
    vec3 warm;       // m/s
};

// Particle i's neighbours in the CPU's order (gatherBlock, filterNear,
// setUpPairLanes); with `write`, their terms summed and the stored ones
// written from list entry `entry` on.
PairSums visitNeighbours(uint i, bool write, uint entry) {
    uint d = dimension();
    ivec3 cells = args.cells.xyz;
    ivec3 subCells = ivec3(2 * cells.x, 2 * cells.y, d == 3u ? 2 * cells.z : 1);
    int zReach = d == 3u ? 1 : 0;
    ivec3 sc = fluidKeySubCell(sortedKeys[i], d, cells);
    vec3 xi = xAt(i);
    vec3 vi = write ? vAt(i) : vec3(0.0f);
    float lambdaI = write ? ps[i] * args.warmFraction : 0.0f;
    PairSums s;
    s.near = 0u;
    s.paired = 0u;
    s.overflows = 0u;
    s.density = 0.0f;
    s.mass = 0.0f;
    s.fastest = 0.0f;
    s.gSum = vec3(0.0f);
    s.warm = vec3(0.0f);
    for (int dz = -zReach; dz <= zReach; ++dz) {
        int sz = sc.z + dz;
        if (sz < 0 || sz >= subCells.z) continue;
        for (int dy = -1; dy <= 1; ++dy) {
            int sy = sc.y + dy;
            if (sy < 0 || sy >= subCells.y) continue;
            for (int dx = -1; dx <= 1; ++dx) {
                int sx = sc.x + dx;
                if (sx < 0 || sx >= subCells.x) continue;
                uint k = fluidSubCellKey(ivec3(sx, sy, sz), d, cells);
                uint begin = keyStart[k];
                uint end = keyStart[k + 1u];
                uint last = min(end, begin + args.readLimit);
                s.overflows += end - last;
                for (uint j = begin; j < last; ++j) {
                    vec3 xj = xAt(j);
                    // The CPU's filter: glm's x_j - x_i, then dot without
                    // fused multiply-adds, so both keep the same particles.
                    precise vec3 offset = xj - xi;
                    precise float r2x = offset.x * offset.x;
                    precise float r2y = offset.y * offset.y;
                    precise float r2 = r2x + r2y;
                    if (d == 3u) {
                        precise float r2z = offset.z * offset.z;
                        r2 = r2 + r2z;
                    }
                    if (!(r2 < args.h2) || j == i) continue;
                    s.near += 1u;
                    if (!write) continue;
                    precise float r = sqrt(r2);
                    s.density += fluidDensityKernel(r * args.invH);
                    if (s.paired >= args.cap) continue;
                    bool apart = r2 > 0.0f;
                    precise float invR = apart ? 1.0f / r : 0.0f;
                    float w = fluidWeight(r2, args.invH2);
                    // The entry's g, as the solve computes it again at each
                    // visit; one variable per component, no vector indexed
                    // by the axis (see fluid_solve.comp, applyImpulse).
                    precise vec3 gOf = fluidPairG(offset, r2, i, j, args.invH2);
                    precise float gx = gOf.x;
                    precise float gy = gOf.y;
                    precise float gz = d == 3u ? gOf.z : 0.0f;
                    vec3 g = vec3(gx, gy, gz);
                    precise float warmPressure = lambdaI + ps[j] * args.warmFraction;
                    s.gSum += g;
                    s.warm -= g * warmPressure;
                    s.mass += w * w;
                    // The closing speed reads the neighbour's velocity: only
                    // in the step's first substep, as on the CPU.
                    if (args.countClosing != 0u) {
                        vec3 vj = vAt(j);
                        precise float approachX = (vi.x - vj.x) * offset.x;
                        precise float approachY = (vi.y - vj.y) * offset.y;
                        precise float closing = approachX + approachY;
                        if (d == 3u) {
                            precise float approachZ = (vi.z - vj.z) * offset.z;
                            closing = closing + approachZ;
                        }
                        closing = closing * invR;
                        s.fastest = closing > s.fastest ? closing : s.fastest;
                    }
                    uint e = entry + s.paired;
                    if (e < args.listCapacity) listIndex[e] = j;
                    s.paired += 1u;
                }
            }
        }
    }
    if (!write) {
        s.paired = min(s.near, args.cap);
    }
    s.overflows += s.near - s.paired;
    return s;
}

void countNeighbours(uint i) {
    uint local = gl_LocalInvocationID.x;
    uint stored = 0u;
    if (i < args.count) {
        PairSums s = visitNeighbours(i, false, 0u);
        stored = s.paired;
        counts[i] = stored;
        if (s.overflows != 0u) atomicAdd(header.overflows, s.overflows);  // integers: any order, one sum
    }
    // The tile's sum (a tree of integer additions: exact).
    tileCounts[local] = stored;
    barrier();
    for (uint stride = SD_FLUID_SETUP_WORKGROUP / 2u; stride > 0u; stride /= 2u) {
        if (local < stride) tileCounts[local] += tileCounts[local + stride];
        barrier();
    }
    if (local == 0u) tiles[gl_WorkGroupID.x] = tileCounts[0];
}

void scanTiles() {
    if (gl_GlobalInvocationID.x != 0u) {
        return;
    }
    uint sum = 0u;
    for (uint t = 0u; t < args.tiles; ++t) {
        uint c = tiles[t];
        tiles[t] = sum;
        sum += c;
    }
    header.entries = sum;
}

void setUp(uint i) {
    // The particle's first entry: its tile's, plus the counts before it in
    // the tile (an inclusive Hillis-Steele scan in shared memory).
    uint local = gl_LocalInvocationID.x;
    uint own = i < args.count ? counts[i] : 0u;
    tileCounts[local] = own;
    barrier();
    for (uint stride = 1u; stride < SD_FLUID_SETUP_WORKGROUP; stride *= 2u) {
        uint add = local >= stride ? tileCounts[local - stride] : 0u;
        barrier();
        tileCounts[local] += add;
        barrier();
    }
    if (i >= args.count) {
        return;
    }
    uint entry = tiles[gl_WorkGroupID.x] + tileCounts[local] - own;
    first[i] = entry;
    PairSums s = visitNeighbours(i, true, entry);
    // The colliders' ghosts (src/fluid/wall_density.cpp): motionless
    // neighbours, in the density and in the particle's own Jacobian entry.
    vec4 ghosts = wall[i];
    precise float density = 1.0f + s.density + ghosts.x;
    precise vec3 gSum = s.gSum + ghosts.yzw;
    precise vec3 warmStart = s.warm;
    if (s.paired != 0u) warmStart -= ghosts.yzw * (ps[i] * args.warmFraction);
    float invMass = fluidInverseMass(s.mass, gSum, args.relaxation);
    float bias = fluidBias(density, args.restDensity, args.baumgarte, args.h, args.invDt);
    constraints[i] = vec4(bias, invMass, density * args.invRest, s.fastest);
    warm[i] = vec4(warmStart, 0.0f);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (PASS == SD_FLUID_SETUP_PASS_GATHER) {
        gather(i);
    } else if (PASS == SD_FLUID_SETUP_PASS_COUNT) {
        countNeighbours(i);
    } else if (PASS == SD_FLUID_SETUP_PASS_TILES) {
        scanTiles();
    } else {
        setUp(i);
    }
}
