#version 450
// The constraint fluid's solve on the device (the CPU's solveConstraints in
// src/fluid/solver.cpp, Parallel order; slides 36-39), on the setup's lists
// (fluid_setup.comp). Passes (a specialization constant):
//   0 start:  the working copy of the velocities, with the gathered warm
//             start when no list overflowed (the setup's header says);
//   1 warm:   otherwise the scattered warm start, one colour per dispatch;
//   2 sweep:  one colour's visits, one dispatch per colour and iteration;
//   3 finish: the velocities back from the working copy.
// A colour is the cells whose coordinates have its parities: cells 2h wide,
// so two cells of one colour are at least 2h apart and their particles'
// constraints (reach h) share no particle. One invocation takes one cell and
// visits its particles in grid order, as the CPU's forEachColourChunk does, so
// the visits are the CPU's, in the same order per cell. The arithmetic is the
// CPU's too, operation for operation (`precise`: no fused multiply-adds, no
// reordering), so on a device that rounds to nearest the results are the
// CPU's bit for bit (tests/gpu/gpu_fluid_solve_test.cpp).
#include "fluid.glsl"
#include "layout.glsl"

layout(constant_id = 0) const uint PASS = 0u;

layout(local_size_x = SD_FLUID_SOLVE_WORKGROUP) in;

layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_KEY_START) readonly buffer KeyStart { uint keyStart[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_FIRST) readonly buffer First { uint first[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_COUNTS) readonly buffer Counts { uint counts[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_X) readonly buffer X { float xs[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_LIST_INDEX) readonly buffer ListIndex { uint listIndex[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_CONSTRAINTS) readonly buffer Constraints { vec4 constraints[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_WARM) readonly buffer Warm { vec4 warm[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_WALL) readonly buffer Wall { vec4 wall[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_V) buffer V { float vs[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_P) buffer P { float pressure[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_PSEUDO_IMPULSE) buffer PseudoImpulse { float pseudoImpulse[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_MOTION) buffer Motion { float motion[]; };
layout(std430, set = 0, binding = SD_FLUID_SOLVE_BINDING_HEADER) readonly buffer Header { FluidSetupHeader header; };

layout(push_constant) uniform Solve { FluidSolvePush args; };  // FluidSolvePush in layout.glsl

uint dimension() { return uint(args.cells.w); }

// Motion of particle i: D velocity floats, then D pseudo velocity floats
// (the CPU's Motion<D>). part 0: velocity, 1: pseudo velocity.
uint motionAt(uint i, uint part) { return 2u * dimension() * i + part * dimension(); }

vec3 motionOf(uint i, uint part) {
    uint m = motionAt(i, part);
    return vec3(motion[m], motion[m + 1u], dimension() == 3u ? motion[m + 2u] : 0.0f);
}

// The warm start's pressure: the previous substep's, scaled, or none for a
// particle without neighbours (solver.cpp, warmPressure).
float warmPressure(uint i) {
    return counts[i] != 0u ? pressure[i] * args.warmFraction : 0.0f;
}

vec3 xAt(uint i) {
    uint d = dimension();
    return vec3(xs[d * i], xs[d * i + 1u], d == 3u ? xs[d * i + 2u] : 0.0f);
}

// g of particle i's pair with neighbour j, computed again from the positions
// with the setup's operations (fluidPairG), so the same bits the setup would
// have stored: 4 bytes an entry read instead of 12 (2D) or 16 (3D).
vec3 pairG(uint i, vec3 xi, uint j) {
    precise vec3 offset = xAt(j) - xi;
    precise float r2x = offset.x * offset.x;
    precise float r2y = offset.y * offset.y;
    precise float r2 = r2x + r2y;
    if (dimension() == 3u) {
        precise float r2z = offset.z * offset.z;
        r2 = r2 + r2z;
    }
    return fluidPairG(offset, r2, i, j, args.invH2);
}

// dot(g, m_j - m_i) of neighbour j as glm computes it: (x + y) + z.
float rateTerm(uint i, vec3 xi, uint j, vec3 mi, uint part) {
    uint d = dimension();
    uint m = motionAt(j, part);
    vec3 g = pairG(i, xi, j);
    precise float x = g.x * (motion[m] - mi.x);
    precise float y = g.y * (motion[m + 1u] - mi.y);
    precise float t = x + y;
    if (d == 3u) {
        precise float z = g.z * (motion[m + 2u] - mi.z);
        t = t + z;
    }
    return t;
}

// C' of particle i's constraint over part `part` of the motion (slide 36):
// four chains of additions, entry k in chain k % 4, the first starting from
// the ghosts' term, added as (0 + 1) + (2 + 3), as the CPU's rateOf.
float rateOf(uint i, uint part) {
    uint d = dimension();
    vec3 mi = motionOf(i, part);
    vec3 ghosts = wall[i].yzw;
    precise float ownX = ghosts.x * mi.x;
    precise float ownY = ghosts.y * mi.y;
    precise float ownDot = ownX + ownY;
    if (d == 3u) {
        precise float ownZ = ghosts.z * mi.z;
        ownDot = ownDot + ownZ;
    }
    precise float chain0 = -ownDot;  // the ghosts are at rest
    precise float chain1 = 0.0f;
    precise float chain2 = 0.0f;
    precise float chain3 = 0.0f;
    uint begin = first[i];
    uint count = counts[i];
    vec3 xi = xAt(i);
    uint k = 0u;
    for (; k + 3u < count; k += 4u) {
        chain0 = chain0 + rateTerm(i, xi, listIndex[begin + k], mi, part);
        chain1 = chain1 + rateTerm(i, xi, listIndex[begin + k + 1u], mi, part);
        chain2 = chain2 + rateTerm(i, xi, listIndex[begin + k + 2u], mi, part);
        chain3 = chain3 + rateTerm(i, xi, listIndex[begin + k + 3u], mi, part);
    }
    if (k < count) chain0 = chain0 + rateTerm(i, xi, listIndex[begin + k], mi, part);
    if (k + 1u < count) chain1 = chain1 + rateTerm(i, xi, listIndex[begin + k + 1u], mi, part);
    if (k + 2u < count) chain2 = chain2 + rateTerm(i, xi, listIndex[begin + k + 2u], mi, part);
    precise float low = chain0 + chain1;
    precise float high = chain2 + chain3;
    precise float rate = low + high;
    return rate;
}

// Adds g delta to neighbour j's part `part` of the motion and returns it.
vec3 pushNeighbour(uint i, vec3 xi, uint j, float delta, uint part) {
    uint m = motionAt(j, part);
    vec3 g = pairG(i, xi, j);
    precise float x = g.x * delta;
    precise float y = g.y * delta;
    precise float z = 0.0f;
    precise float movedX = motion[m] + x;
    precise float movedY = motion[m + 1u] + y;
    motion[m] = movedX;
    motion[m + 1u] = movedY;
    if (dimension() == 3u) {
        z = g.z * delta;
        precise float movedZ = motion[m + 2u] + z;
        motion[m + 2u] = movedZ;
    }
    return vec3(x, y, z);
}

// Applies impulse `delta` of particle i's constraint to part `part` of the
// motion: m_n += g delta on every neighbour, m_i -= (wall + sum g) delta
// (Newton's third law, slide 39; the motionless ghosts take none), the sum
// in rateOf's four chains. One variable per component and chain, no array
// indexed at run time: written as a `precise vec3` indexed by the axis in a
// loop, lavapipe lost whole visits of the 3D split impulses when several
// invocations of a workgroup diverged (tests/gpu/gpu_fluid_solve_test.cpp
// found it; one active invocation per workgroup gave the CPU's bits).
void applyImpulse(uint i, float delta, uint part) {
    uint d = dimension();
    vec3 ghosts = wall[i].yzw;
    precise float x0 = ghosts.x * delta;
    precise float y0 = ghosts.y * delta;
    precise float z0 = ghosts.z * delta;
    precise float x1 = 0.0f, y1 = 0.0f, z1 = 0.0f;
    precise float x2 = 0.0f, y2 = 0.0f, z2 = 0.0f;
    precise float x3 = 0.0f, y3 = 0.0f, z3 = 0.0f;
    uint begin = first[i];
    uint count = counts[i];
    vec3 xi = xAt(i);
    uint k = 0u;
    for (; k + 3u < count; k += 4u) {
        vec3 a = pushNeighbour(i, xi, listIndex[begin + k], delta, part);
        vec3 b = pushNeighbour(i, xi, listIndex[begin + k + 1u], delta, part);
        vec3 c = pushNeighbour(i, xi, listIndex[begin + k + 2u], delta, part);
        vec3 e = pushNeighbour(i, xi, listIndex[begin + k + 3u], delta, part);
        x0 = x0 + a.x; y0 = y0 + a.y; z0 = z0 + a.z;
        x1 = x1 + b.x; y1 = y1 + b.y; z1 = z1 + b.z;
        x2 = x2 + c.x; y2 = y2 + c.y; z2 = z2 + c.z;
        x3 = x3 + e.x; y3 = y3 + e.y; z3 = z3 + e.z;
    }
    if (k < count) {
        vec3 a = pushNeighbour(i, xi, listIndex[begin + k], delta, part);
        x0 = x0 + a.x; y0 = y0 + a.y; z0 = z0 + a.z;
    }
    if (k + 1u < count) {
        vec3 b = pushNeighbour(i, xi, listIndex[begin + k + 1u], delta, part);
        x1 = x1 + b.x; y1 = y1 + b.y; z1 = z1 + b.z;
    }
    if (k + 2u < count) {
        vec3 c = pushNeighbour(i, xi, listIndex[begin + k + 2u], delta, part);
        x2 = x2 + c.x; y2 = y2 + c.y; z2 = z2 + c.z;
    }
    precise float sumX = (x0 + x1) + (x2 + x3);
    precise float sumY = (y0 + y1) + (y2 + y3);
    uint m = motionAt(i, part);
    precise float leftX = motion[m] - sumX;
    precise float leftY = motion[m + 1u] - sumY;
    motion[m] = leftX;
    motion[m + 1u] = leftY;
    if (d == 3u) {
        precise float sumZ = (z0 + z1) + (z2 + z3);
        precise float leftZ = motion[m + 2u] - sumZ;
        motion[m + 2u] = leftZ;
    }
}

// The scattered warm start of particle i (solver.cpp, warmStart).
void warmStart(uint i) {
    float start = warmPressure(i);
    pressure[i] = start;
    if (start != 0.0f) applyImpulse(i, start, 0u);
}

// One visit of particle i's constraint (solver.cpp, visit; signs in
// fluid.glsl): with split impulses an over-dense particle solves its real
// and its pseudo constraint. The CPU makes both passes over the neighbours in
// one; each sum and each store is the same.
void visit(uint i) {
    float bias = constraints[i].x;
    float invMass = constraints[i].y;
    if (args.split == 0u || bias >= 0.0f) {
        float b = args.split == 0u ? bias : fluidAllowance(bias, args.allowanceSlop);
        FluidImpulse r = fluidSolveImpulse(rateOf(i, 0u), b, invMass, pressure[i]);
        pressure[i] = r.accumulated;
        if (r.delta != 0.0f) applyImpulse(i, r.delta, 0u);
    } else {
        FluidImpulse r = fluidSolveImpulse(rateOf(i, 0u), fluidRealBias(bias), invMass, pressure[i]);
        FluidImpulse q = fluidSolveImpulse(rateOf(i, 1u), fluidPseudoBias(bias), invMass, pseudoImpulse[i]);
        pressure[i] = r.accumulated;
        pseudoImpulse[i] = q.accumulated;
        applyImpulse(i, r.delta, 0u);
        applyImpulse(i, q.delta, 1u);
    }
}

// Invocation t's cell of the pass's colour, its particles in grid order.
void forCell(uint t) {
    uint d = dimension();
    ivec3 cells = args.cells.xyz;
    uint c = args.colour;
    ivec3 parity = ivec3(int(c & 1u), int((c >> 1) & 1u), int((c >> 2) & 1u));
    ivec3 halves = (cells - parity + 1) / 2;  // cells of this parity per axis
    if (t >= uint(halves.x * halves.y * halves.z)) {
        return;
    }
    ivec3 at = ivec3(int(t) % halves.x, (int(t) / halves.x) % halves.y, int(t) / (halves.x * halves.y));
    ivec3 cell = 2 * at + parity;
    uint index = uint(cell.x + cells.x * (cell.y + cells.y * cell.z));
    uint quadrants = 1u << d;
    uint end = keyStart[(index + 1u) * quadrants];
    for (uint i = keyStart[index * quadrants]; i < end; ++i) {
        if (PASS == SD_FLUID_SOLVE_PASS_WARM) {
            warmStart(i);
        } else {
            visit(i);
        }
    }
}

void start(uint i) {
    if (i >= args.count) {
        return;
    }
    uint d = dimension();
    bool gathered = header.overflows == 0u;
    uint m = motionAt(i, 0u);
    for (uint a = 0u; a < d; ++a) {
        precise float v = gathered ? vs[d * i + a] + warm[i][a] : vs[d * i + a];
        motion[m + a] = v;
        motion[m + d + a] = 0.0f;
    }
    pseudoImpulse[i] = 0.0f;
    if (gathered) pressure[i] = warmPressure(i);
}

void finish(uint i) {
    if (i >= args.count) {
        return;
    }
    uint d = dimension();
    uint m = motionAt(i, 0u);
    for (uint a = 0u; a < d; ++a) vs[d * i + a] = motion[m + a];
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (PASS == SD_FLUID_SOLVE_PASS_START) {
        start(i);
    } else if (PASS == SD_FLUID_SOLVE_PASS_WARM) {
        if (header.overflows != 0u) forCell(i);
    } else if (PASS == SD_FLUID_SOLVE_PASS_SWEEP) {
        forCell(i);
    } else {
        finish(i);
    }
}
