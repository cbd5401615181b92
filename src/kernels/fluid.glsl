// The constraint fluid's per-particle math (Sprinkle, Gustafsson; slides 32-39
// and 51): kernel weight, constraint setup, the impulse of one solver visit and
// the velocity constraint of a particle against a static collider. Shared by
// the CPU solver (src/fluid/) and, later, compute shaders.
//
// Sign conventions, derived here because the slides' are loose (docs/design.md):
//   dir   unit vector from particle p to its neighbour n;
//   g     = w * dir, the neighbour's "gradient" entry (slide 36 scales the
//           projected relative velocity by the weight);
//   C'    = sum_n dot(g, v_n - v_p): positive when the neighbours move away,
//           i.e. the density at p is falling;
//   lambda  the impulse magnitude: v_n += g lambda, v_p -= g lambda, so a
//           positive lambda pushes the neighbours apart and raises C' by
//           A lambda with A = sum |g|^2 + |sum g|^2, the effective mass of
//           this Jacobian. (Slide 35's A = sum 2 w^2 is exact for one
//           neighbour only; at walls and free surfaces, where the g do not
//           cancel, it is several times too small and the solver diverges;
//           src/fluid/neighbours.cpp.)
//   The constraint asks C' + bias' = 0 with bias' = -bias, bias = (rho0 - rho)
//   * baumgarte (velocity steering, slide 34): an over-dense particle
//   (bias < 0) wants its neighbours to separate at -bias. Hence
//   lambda = -(C' + bias) / A, and the accumulated lambda is clamped to >= 0
//   (slide 38: clamp the accumulated impulse, not the per-iteration one) so
//   pressure only ever pushes. At rest density with no relative motion lambda
//   is 0: a tank at rest stays at rest.
#ifndef SPINDRIFT_KERNELS_FLUID
#define SPINDRIFT_KERNELS_FLUID
#include "layout.glsl"
#include "types.glsl"
SD_BEGIN

// --- Grid keys (slide 46) ---------------------------------------------------------
// The uniform grid of src/fluid/grid.cpp and src/gpu/gpu_fluid_grid.cpp: cells
// 2h wide, each split into 2^D sub-cells h wide; a particle's key is cell *
// 2^D + quadrant, so a sort by key makes every sub-cell one contiguous range.
// Both backends sort by this key and must agree bit for bit, so it is written
// once. Every operation is `precise`: (x - origin) * invH then floor is what
// the CPU computes (it does not fuse, -ffp-contract=off), and no compiler may
// rewrite it (as x * invH - origin * invH, say), or a particle on a sub-cell
// boundary lands in the other sub-cell.

// Sub-cell coordinate of x along one axis (origin in m, invH in 1/m), clamped
// into [0, subCells - 1]: a particle outside the (capped) grid goes to its
// edge sub-cell. Clamped as floats before the conversion, so a coordinate
// far beyond the int range still converts exactly.
SD_FN int fluidSubCell(float x, float origin, float invH, int subCells) {
    SD_PRECISE float s = floor((x - origin) * invH);
    SD_PRECISE float clamped = clamp(s, 0.0f, float(subCells - 1));
    return int(clamped);
}

// Key of the particle at x (m; z unused when dimension is 2) in the grid of
// `cells` cells per axis (z 1 in 2D) whose sub-cell 0 has its corner at origin
// (m); invH = 1 / h (1/m). Cells are numbered x fastest; the quadrant's bit a
// is the sub-cell's parity along axis a.
SD_FN uint fluidGridKey(vec3 x, uint dimension, vec3 origin, float invH, ivec3 cells) {
    uint cell = 0u;
    uint quadrant = 0u;
    uint stride = 1u;
    for (uint a = 0u; a < dimension; ++a) {
        int s = fluidSubCell(x[a], origin[a], invH, 2 * cells[a]);
        cell += uint(s >> 1) * stride;
        quadrant |= uint(s & 1) << a;
        stride *= uint(cells[a]);
    }
    return cell * (1u << dimension) + quadrant;
}

// Sub-cell coordinates of a key (the inverse of fluidGridKey's numbering; z 0
// in 2D): the neighbour search's start.
SD_FN ivec3 fluidKeySubCell(uint key, uint dimension, ivec3 cells) {
    uint cell = key >> dimension;
    uint quadrant = key & ((1u << dimension) - 1u);
    uint cx = cell % uint(cells.x);
    uint cy = (cell / uint(cells.x)) % uint(cells.y);
    uint cz = cell / uint(cells.x * cells.y);
    return ivec3(2 * int(cx) + int(quadrant & 1u), 2 * int(cy) + int((quadrant >> 1) & 1u),
                 2 * int(cz) + int((quadrant >> 2) & 1u));
}

// Key of sub-cell s (inside the grid; z 0 in 2D).
SD_FN uint fluidSubCellKey(ivec3 s, uint dimension, ivec3 cells) {
    uint cell = uint((s.x >> 1) + cells.x * ((s.y >> 1) + cells.y * (s.z >> 1)));
    uint quadrant = uint((s.x & 1) | ((s.y & 1) << 1) | ((s.z & 1) << 2));
    return (cell << dimension) | quadrant;
}

// Kernel of slide 35: w = (1 - d^2)^3, d = distance / h; 0 at and beyond h.
// Takes the squared distance so the caller needs no square root to reject.
SD_FN float fluidWeight(float distanceSquared, float invHSquared) {
    float q = 1.0f - distanceSquared * invHSquared;
    return q > 0.0f ? q * q * q : 0.0f;
}

// The density kernel: W(d) = 1 - (35/16) (d - d^3 + 3 d^5 / 5 - d^7 / 7), d =
// distance / h in [0, 1): the kernel whose slope is the slides' weight,
// dW/dd = -(35/16) (1 - d^2)^3, with W(0) = 1 (a lone particle has density 1)
// and W(1) = 0. The slides measure density with w itself; w is flat at d = 0
// and steep near d = 0.45, so its sum over a disordered packing reads several
// per cent above its sum over the lattice at the same number of particles per
// area, and a fluid held at the lattice's rest density settles expanded
// (measured: 5 % more area in a 60-layer 2D tank, docs/fluid.md). W weighs
// neighbours far more evenly. And with W the Jacobian entry g = w dir is
// exactly -(16/35) h times the gradient of the density, so the bias below
// corrects a known fraction of a density error.
SD_FN float fluidDensityKernel(float d) {
    float d2 = d * d;
    float d3 = d2 * d;
    return 1.0f - 2.1875f * (d - d3 + 0.6f * d3 * d2 - d3 * d2 * d2 * (1.0f / 7.0f));
}

// C' per unit of d(rho)/dt, in units of h (see fluidDensityKernel): 16 / 35.
SD_CONST float SD_FLUID_RATE_PER_DENSITY = 0.45714286f;

// Velocity steering toward the rest density (slide 34-35), in m/s: the bias
// that, solved as C' = -bias, changes the density by baumgarte x (rho0 - rho)
// over a step of 1 / invDt s (rho in units of the kernel sum, where a particle
// alone has density 1; h in m).
SD_FN float fluidBias(float density, float restDensity, float baumgarte, float h, float invDt) {
    return (restDensity - density) * baumgarte * SD_FLUID_RATE_PER_DENSITY * h * invDt;
}

// --- Constraint setup (slide 35) ---------------------------------------------
// One pair's Jacobian entry g = w * direction from particle i to neighbour j,
// along one axis: offset (m) is x_j - x_i along it, wOverR = w / r (1/m).
// For a neighbour on top of i (r = 0, `apart` false) the direction is along
// x, away from the higher index (fluidCoincidentSide): the opposite of j's
// direction to i, so the pair's constraints push them apart. In a crushed
// corner several particles end on one point; W's slope there is w(0) = 1
// along any direction. When such a pair counted in the density only, a
// particle among several on one point was over-dense with almost nothing to
// push against: effective mass 3e-6, impulses of 8e4 m/s a visit, and a 50
// m/s launch into a tank of edges blew up (docs/fluid.md, "Launches into
// tanks").
SD_FN float fluidCoincidentSide(uint i, uint j) {
    return j > i ? 1.0f : -1.0f;
}
SD_FN float fluidPairGradient(float offset, float w, float wOverR, bool apart, bool xAxis, float side) {
    return apart ? offset * wOverR : (xAxis ? side : 0.0f) * w;
}

// The pair's whole entry g = w dir (slide 35), from the offset x_j - x_i and
// its squared length r2 as the setup's filter computes them (no fused
// multiply-adds; z 0 in 2D). The device's setup adds it into its sums and its
// solve computes it again at every visit from the positions instead of
// storing it (an entry is then 4 bytes, not 12 in 2D: docs/performance.md,
// "The fluid on the device"); the CPU's pairTerm (src/fluid/neighbours.cpp)
// computes the same operations in its lanes and stores the result.
SD_FN vec3 fluidPairG(vec3 offset, float r2, uint i, uint j, float invH2) {
    SD_PRECISE float r = sqrt(r2);
    bool apart = r2 > 0.0f;
    SD_PRECISE float invR = apart ? 1.0f / r : 0.0f;
    float w = fluidWeight(r2, invH2);
    SD_PRECISE float wOverR = w * invR;
    float side = fluidCoincidentSide(i, j);
    return vec3(fluidPairGradient(offset.x, w, wOverR, apart, true, side),
                fluidPairGradient(offset.y, w, wOverR, apart, false, side),
                fluidPairGradient(offset.z, w, wOverR, apart, false, side));
}

// 1 / A, the effective mass of the Jacobian (g_n for each neighbour, -sum g
// for the particle itself; the colliders' motionless ghosts in gSum):
// A = sum |g|^2 + |sum g|^2, from sumW2 = sum w^2 and gSum (z 0 in 2D). The
// slides' A = sum 2 w^2 is exact for one neighbour only; at a wall or a free
// surface, where the g do not cancel, it under-estimates the particle's own
// response several times and the solver over-corrects and diverges
// (measured: a 20-layer tank collapsed). 0 for a particle alone. Scaled by
// the relaxation (FluidDef::relaxation, successive over-relaxation: each
// visit applies that many times the impulse that solves its own constraint
// with the neighbours held, which carries a correction through a column's
// layers in fewer sweeps; docs/fluid.md, "Over-relaxed sweeps").
SD_FN float fluidInverseMass(float sumW2, vec3 gSum, float relaxation) {
    float mass = sumW2 + (gSum.x * gSum.x + gSum.y * gSum.y + gSum.z * gSum.z);
    return mass > 0.0f ? relaxation / mass : 0.0f;
}

// One visit of the solver to particle p's constraint.
struct FluidImpulse {
    float accumulated;  // new accumulated impulse (m/s), >= 0: the pressure
    float delta;        // impulse to apply now (m/s): v_n += g delta, v_p -= g delta
};

// rate: C' = sum_n dot(w dir, v_n - v_p) (m/s); bias (m/s) from fluidBias;
// invMass: 1 / A (0 for a particle without neighbours).
// `precise`: the device's solve is the CPU's bit for bit (fluid_solve.comp),
// so no compiler may fuse accumulated + lambda into a multiply-add.
SD_FN FluidImpulse fluidSolveImpulse(float rate, float bias, float invMass, float accumulated) {
    SD_PRECISE float lambda = -(rate + bias) * invMass;
    SD_PRECISE float total = max(accumulated + lambda, 0.0f);
    SD_PRECISE float delta = total - accumulated;
    FluidImpulse r;
    r.accumulated = total;
    r.delta = delta;
    return r;
}

// --- Split impulses (FluidDef::splitImpulse; src/fluid/solver.cpp) ---------
// Most of the Baumgarte bias is solved on a second, pseudo velocity that moves
// particles this substep and is then forgotten, as rigid-body solvers do for
// penetration. The bias splits by sign: an under-dense particle's positive
// bias lets its neighbours approach (it relaxes the constraint, no energy
// added) and stays with the real velocity, past a slop; an over-dense
// particle's negative bias pushes apart, mostly on the pseudo velocity.

// Density deficit (fraction of rho0) below which an under-dense particle gets
// no approach allowance in the real velocity. Inside the fluid the density of
// a disordered packing fluctuates by a few per cent; letting gravity pull
// neighbours toward every slightly under-dense particle kept a resting tank
// moving at 0.16 m/s (measured), while surface and splash particles, far
// below rest density, still fall together.
SD_CONST float SD_FLUID_ALLOWANCE_SLOP = 0.1f;
// Share of an over-dense particle's bias kept in the real velocity (the rest
// goes to the pseudo velocity). All in the pseudo one leaves a resting tank
// quietest but lets a falling column compress: the real velocity then has
// nothing that pushes back and the positional correction lags (dam break of
// 10k particles, 0.5 s: 1.8 % mean density error); all in the real one is the
// slides' form (0.35 %, but a resting tank jitters at 0.25 m/s). A quarter
// (measured, baumgarte 0.05): 0.56 % and 0.11 m/s.
SD_CONST float SD_FLUID_REAL_BIAS_SHARE = 0.25f;

// The slop in m/s of bias (fluidBias of a deficit SD_FLUID_ALLOWANCE_SLOP x
// rho0, over a substep dt in s).
SD_FN float fluidAllowanceSlop(float restDensity, float baumgarte, float h, float dt) {
    return SD_FLUID_ALLOWANCE_SLOP * restDensity * baumgarte * h / dt;
}
// The bias an under-dense particle's (bias >= 0) real constraint solves.
SD_FN float fluidAllowance(float bias, float slop) {
    SD_PRECISE float allowance = max(bias - slop, 0.0f);
    return allowance;
}
// An over-dense particle's (bias < 0) biases: the real and the pseudo shares.
SD_FN float fluidRealBias(float bias) {
    return bias * SD_FLUID_REAL_BIAS_SHARE;
}
SD_FN float fluidPseudoBias(float bias) {
    return bias * (1.0f - SD_FLUID_REAL_BIAS_SHARE);
}

// --- The warm start's cap ------------------------------------------------------
// The warm start re-applies the last substep's pressure along this substep's
// directions. A hydrostatic pressure changes slowly and is worth carrying; an
// impact's is not: the pressure that stopped a drop in one substep is spent
// once the drop has stopped, and re-applied it flings the drop's neighbours.
// (30k dam break, t = 2.42 s: a drop running down the wall at 9 m/s lands
// beside it, one particle carries 18 times the 99.9th percentile's pressure,
// its warm start raises the fluid's kinetic energy by 13 % in one substep and
// sends a neighbour off at 23.75 m/s; docs/fluid.md, "The warm start's cap".)
// So each particle's warm-start pressure is capped at SD_FLUID_WARM_CAP_HEADS
// times the hydrostatic pressure at the bottom of the fluid's pressed depth.
//
// The hydrostatic pressure (m/s, an impulse per substep) at depth d below the
// surface of a lattice at rest: a particle's pressures change its velocity by
// -sum_n g_n (lambda_i + lambda_n); with lambda = a (depth) that is a sum_n w
// dy^2 / r upward, which holds gravity when a = g dt / S, S = sum_n w_n dy_n^2
// / r_n over the lattice's neighbours (m; latticeHydrostaticSum). At rest the
// floor's and the corners' particles, whose lists are one-sided, carry up to
// 3.8 times a (depth) in 2D and 2.8 in 3D, the 99th percentile 2 to 2.3 times
// (sloshing tanks of FluidWaves, measured); 5 leaves those untouched.
SD_CONST float SD_FLUID_WARM_CAP_HEADS = 5.0f;
// No cap (m/s): without gravity there is no hydrostatic scale to cap at.
SD_CONST float SD_FLUID_NO_WARM_CAP = 3.0e38f;

// The cap (m/s) for gravity (m/s^2), a substep of dt (s), the pressed depth
// (m) and S (m, latticeHydrostaticSum).
SD_FN float fluidWarmCap(float gravity, float dt, float depth, float hydrostaticSum) {
    return gravity > 0.0f ? SD_FLUID_WARM_CAP_HEADS * gravity * dt * depth / hydrostaticSum : SD_FLUID_NO_WARM_CAP;
}
// A particle's last pressure (m/s) as its warm start reads it.
SD_FN float fluidCappedPressure(float pressure, float cap) {
    return min(pressure, cap);
}

// --- Static colliders ----------------------------------------------------------
// A fluid particle is a small rotationless body of radius r (slide 51); its
// contact with a collider is a velocity constraint solved after the fluid's.

struct FluidSurface {
    float distance;  // signed distance of the point to the surface (m), > 0 outside
    vec3 normal;     // unit, pointing out of the collider
};

SD_FN FluidSurface makeSurface(float distance, vec3 normal) {
    FluidSurface s;
    s.distance = distance;
    s.normal = normal;
    return s;
}

// Plane, sphere and oriented box of the world (types.glsl's ColliderParams).
// Other kinds are not fluid colliders: far away, never touched.
SD_FN FluidSurface fluidColliderSurface(SD_IN(ColliderParams) c, vec3 p) {
    if (c.kind == SD_COLLIDER_PLANE) {
        vec3 n = vec3(c.normal);
        SD_PRECISE float d = dot(p - vec3(c.position), n);
        return makeSurface(d, n);
    }
    if (c.kind == SD_COLLIDER_SPHERE) {
        SD_PRECISE vec3 offset = p - vec3(c.position);
        SD_PRECISE float len = length(offset);
        SD_PRECISE vec3 n = len > 0.0f ? offset / len : vec3(0.0f, 1.0f, 0.0f);
        return makeSurface(len - c.position.w, n);
    }
    if (c.kind == SD_COLLIDER_BOX) {
        SD_PRECISE vec3 offset = p - vec3(c.position);
        SD_PRECISE float qx = dot(offset, vec3(c.axisX));
        SD_PRECISE float qy = dot(offset, vec3(c.axisY));
        SD_PRECISE float qz = dot(offset, vec3(c.axisZ));
        vec3 q = vec3(qx, qy, qz);
        SD_PRECISE vec3 s = vec3(q.x >= 0.0f ? 1.0f : -1.0f, q.y >= 0.0f ? 1.0f : -1.0f, q.z >= 0.0f ? 1.0f : -1.0f);
        SD_PRECISE vec3 gap = abs(q) - vec3(c.halfExtents);  // > 0: outside that slab
        SD_PRECISE vec3 outside = max(gap, vec3(0.0f));
        SD_PRECISE float outsideLength = length(outside);
        SD_PRECISE vec3 local;
        SD_PRECISE float distance;
        if (outsideLength > 0.0f) {
            local = outside * s / outsideLength;
            distance = outsideLength;
        } else {
            // Inside: out through the nearest face.
            if (gap.x >= gap.y && gap.x >= gap.z) {
                local = vec3(s.x, 0.0f, 0.0f);
                distance = gap.x;
            } else if (gap.y >= gap.z) {
                local = vec3(0.0f, s.y, 0.0f);
                distance = gap.y;
            } else {
                local = vec3(0.0f, 0.0f, s.z);
                distance = gap.z;
            }
        }
        SD_PRECISE vec3 n = vec3(c.axisX) * local.x + vec3(c.axisY) * local.y + vec3(c.axisZ) * local.z;
        return makeSurface(distance, n);
    }
    return makeSurface(3.0e38f, vec3(0.0f, 1.0f, 0.0f));
}

SD_CONST uint SD_FLUID_MAX_POLYGON_VERTICES = 16u;

// A convex polygon in the xy plane, extruded along z; vertices counter-
// clockwise. 272 bytes.
struct FluidPolygon {
    vec4 vertices[16];  // xy (m); zw unused
    uint count;
    uint pad0, pad1, pad2;
};

// Signed distance in the xy plane: outside, the distance to the nearest edge;
// inside, minus the distance to the nearest edge line (the convex polygon is
// the intersection of its edges' half-planes).
SD_FN FluidSurface fluidPolygonSurface(SD_IN(FluidPolygon) poly, vec3 p) {
    SD_PRECISE vec2 x = vec2(p.x, p.y);
    SD_PRECISE float insideDistance = -3.0e38f;
    SD_PRECISE vec2 insideNormal = vec2(0.0f, 1.0f);
    SD_PRECISE float outsideSquared = 3.0e38f;
    SD_PRECISE vec2 outsideNormal = vec2(0.0f, 1.0f);
    bool outside = false;
    for (uint i = 0u; i < poly.count; ++i) {
        SD_PRECISE vec2 a = vec2(poly.vertices[i].x, poly.vertices[i].y);
        uint j = i + 1u == poly.count ? 0u : i + 1u;
        SD_PRECISE vec2 b = vec2(poly.vertices[j].x, poly.vertices[j].y);
        SD_PRECISE vec2 edge = b - a;
        SD_PRECISE float len = length(edge);
        // Counter-clockwise: the outward normal is the edge turned clockwise.
        SD_PRECISE vec2 n = len > 0.0f ? vec2(edge.y, -edge.x) / len : vec2(0.0f, 1.0f);
        SD_PRECISE float side = dot(x - a, n);
        if (side > 0.0f) {
            outside = true;
        }
        if (side > insideDistance) {
            insideDistance = side;
            insideNormal = n;
        }
        SD_PRECISE float t = len > 0.0f ? clamp(dot(x - a, edge) / (len * len), 0.0f, 1.0f) : 0.0f;
        SD_PRECISE vec2 closest = a + edge * t;
        SD_PRECISE vec2 away = x - closest;
        SD_PRECISE float d2 = dot(away, away);
        if (d2 < outsideSquared) {
            outsideSquared = d2;
            outsideNormal = d2 > 0.0f ? away / sqrt(d2) : n;
        }
    }
    if (outside) {
        return makeSurface(sqrt(outsideSquared), vec3(outsideNormal.x, outsideNormal.y, 0.0f));
    }
    return makeSurface(insideDistance, vec3(insideNormal.x, insideNormal.y, 0.0f));
}

// Fraction of an overlap removed per step (m per m) by a contact's push: a
// gentle push, so a particle that starts inside a wall does not shoot out.
SD_CONST float SD_FLUID_OVERLAP_PUSH = 0.2f;

// A 2D fluid's surface: a normal with a z part (a sphere's or a box's seen
// off-centre) is projected into the plane, so the fluid stays in it.
SD_FN FluidSurface fluidFlatSurface(FluidSurface s) {
    SD_PRECISE float len = sqrt(s.normal.x * s.normal.x + s.normal.y * s.normal.y);
    SD_PRECISE vec3 n = len > 0.0f ? vec3(s.normal.x / len, s.normal.y / len, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    s.normal = n;
    return s;
}

// The colliders' share of a particle's density at `distance` (m) from a
// surface: a table of `size` entries from `start` (m), `step` (m) apart
// (src/fluid/wall_density.cpp builds it), read linearly. The entry below the
// distance, or -1 beyond the table (and for NaN), and the fraction toward
// the next entry.
struct FluidWallPlace {
    int entry;
    float fraction;
};
SD_FN FluidWallPlace fluidWallPlace(float distance, float start, float step, int size) {
    SD_PRECISE float u = (distance - start) / step;
    FluidWallPlace w;
    w.entry = -1;
    w.fraction = 0.0f;
    if (!(u < float(size - 1))) {
        return w;
    }
    float c = u > 0.0f ? u : 0.0f;
    w.entry = int(c);
    SD_PRECISE float a = c - float(w.entry);
    w.fraction = a;
    return w;
}
SD_FN float fluidWallLerp(float below, float above, float fraction) {
    SD_PRECISE float r = below + (above - below) * fraction;
    return r;
}

// The contact of slide 51 as a speculative velocity constraint: with
// separation s = distance - radius, the normal velocity may not fall below
// -s / dt (the particle may close the gap in this step, not more). A particle
// already overlapping (s < 0) is pushed out at `push` of the overlap per step.
// Friction (Coulomb, mu) removes tangential velocity up to mu times the
// normal velocity change. Returns the new velocity.
SD_FN vec3 fluidContactVelocity(vec3 v, FluidSurface surface, float radius, float invDt, float push, float mu) {
    SD_PRECISE float separation = surface.distance - radius;
    SD_PRECISE float target = separation >= 0.0f ? -separation * invDt : -separation * push * invDt;
    SD_PRECISE float vn = dot(v, surface.normal);
    if (vn >= target) {
        return v;
    }
    SD_PRECISE float dvn = target - vn;
    SD_PRECISE vec3 out1 = v + surface.normal * dvn;
    if (mu > 0.0f) {
        SD_PRECISE vec3 tangent = out1 - surface.normal * dot(out1, surface.normal);
        SD_PRECISE float speed = length(tangent);
        if (speed > 0.0f) {
            SD_PRECISE float drop = min(speed, mu * dvn);
            out1 = out1 - tangent * (drop / speed);
        }
    }
    return out1;
}

// --- Integration (src/fluid/collide.cpp, integratePositions) -------------------
// Distance (m) a particle put back out of a collider keeps from its surface,
// so rounding does not leave it inside for the next substep.
SD_CONST float SD_FLUID_SKIN = 1e-5f;
// A sleeping particle wakes above this many times FluidDef::sleepSpeed.
SD_CONST float SD_FLUID_WAKE_FACTOR = 2.0f;
// The sleep circle's largest radius, in spacings.
SD_CONST float SD_FLUID_SLEEP_CIRCLE_SPACINGS = 0.5f;
// |x| <= this is false for NaN and both infinities.
SD_CONST float SD_FLUID_FLOAT_MAX = 3.40282347e38f;

// --- The step's statistics (the substep rule's inputs) ----------------------
// Particles are counted by the fastest closing speed of a neighbour (m/s), in
// bins SD_FLUID_APPROACH_BIN wide, the last one open-ended; a NaN counts in
// bin 0 (src/fluid/fluid_step.cpp, closingSpeed, reads the histogram; the
// bins are layout.glsl's, since the device's report holds them).
SD_FN uint fluidApproachBin(float speed) {
    float b = speed / SD_FLUID_APPROACH_BIN;
    return b > 0.0f ? uint(min(b, float(SD_FLUID_APPROACH_BINS - 1u))) : 0u;
}

// A float as a uint whose order is the float's, so that integer atomicMin and
// atomicMax reduce floats in any order to the same result (the device's
// statistics and box).
SD_FN uint fluidOrderKey(float f) {
    uint bits = floatBitsToUint(f);
    return (bits & 0x80000000u) != 0u ? ~bits : bits | 0x80000000u;
}

SD_FN bool fluidFinite(vec3 v) {
    return abs(v.x) <= SD_FLUID_FLOAT_MAX && abs(v.y) <= SD_FLUID_FLOAT_MAX && abs(v.z) <= SD_FLUID_FLOAT_MAX;
}
// A velocity the solver can square: contacts, speeds and the substep count
// take its length, which overflows above 1.8e19 m/s.
SD_FN bool fluidFiniteSpeed(vec3 v) {
    SD_PRECISE float xx = v.x * v.x;
    SD_PRECISE float yy = v.y * v.y;
    SD_PRECISE float zz = v.z * v.z;
    SD_PRECISE float squared = xx + yy + zz;
    return fluidFinite(v) && squared <= SD_FLUID_FLOAT_MAX;
}

// v with no part left into a surface of unit normal n: v - n min(dot(v, n),
// 0) (a particle put back on a collider or a body keeps only its tangential
// and outward motion).
SD_FN vec3 fluidWithoutInward(vec3 v, vec3 n) {
    SD_PRECISE float vn = dot(v, n);
    SD_PRECISE float inward = min(vn, 0.0f);
    SD_PRECISE vec3 out1 = v - n * inward;
    return out1;
}

SD_FN float fluidSquare(float a) {
    SD_PRECISE float squared = a * a;
    return squared;
}

// |v|^2, as fluidLength squares it. fluidLength does not call it: with
// that call, Debian 12's glslc ran out of memory on fluid_contacts.comp
// (13.7 GB in two minutes; the `precise` hang of layout.glsl's note).
SD_FN float fluidLengthSquared(vec3 v) {
    SD_PRECISE float xx = v.x * v.x;
    SD_PRECISE float yy = v.y * v.y;
    SD_PRECISE float zz = v.z * v.z;
    SD_PRECISE float squared = xx + yy + zz;
    return squared;
}

// Length of v (z 0 in 2D: the same number as the 2D length).
SD_FN float fluidLength(vec3 v) {
    SD_PRECISE float xx = v.x * v.x;
    SD_PRECISE float yy = v.y * v.y;
    SD_PRECISE float zz = v.z * v.z;
    SD_PRECISE float squared = xx + yy + zz;
    SD_PRECISE float len = sqrt(squared);
    return len;
}

// The sleep circle's radius (m): sleepSpeed x sleepTime, at most half a
// spacing. A standing wave's particles swing around a point, and near each
// turning point they stay within a small circle for a good part of a period:
// with the radius sleepSpeed x sleepTime alone (2.5 cm by default), a 4 cm
// slosh in a 1.6 m tank at 2 cm spacing (period 1.65 s) fell asleep at its
// first turn and froze with its surface 4.6 cm higher at one end than at the
// other. At half a spacing it swings on until each end is within about half
// a spacing of level (test FluidWaves; docs/fluid.md, "Sleeping and waves").
SD_FN float fluidSleepDrift(float sleepSpeed, float sleepTime, float spacing) {
    SD_PRECISE float byTime = sleepSpeed * sleepTime;
    SD_PRECISE float bySpacing = SD_FLUID_SLEEP_CIRCLE_SPACINGS * spacing;
    return min(byTime, bySpacing);
}

// One substep of a particle's sleep (as Box2D's bodies and FleX's particles):
// a particle that has not left a circle of `drift` (m) around its anchor for
// sleepTime (s) holds still until the solver gives it more than `wakeSpeed`
// (m/s). Displacement, not speed, decides: a resting tank's particles jitter
// at several cm/s (the pressure of a disordered packing cannot cancel
// gravity exactly) but go nowhere, while a flow as slow as sleepSpeed leaves
// the circle and stays awake. x, v, anchor: z 0 in 2D.
struct FluidSleep {
    bool asleep;    // this substep: velocity 0, position held
    float still;    // s, time within the circle
    vec3 anchor;    // m, the circle's centre
};
SD_FN FluidSleep fluidSleepStep(vec3 x, vec3 v, vec3 anchor, float still, float dt, float sleepTime, float wakeSpeed,
                               float drift) {
    FluidSleep s;
    s.asleep = false;
    s.still = still;
    s.anchor = anchor;
    if (still >= sleepTime) {
        if (fluidLength(v) < wakeSpeed) {
            s.asleep = true;
            return s;
        }
        s.still = 0.0f;
        s.anchor = x;
    } else if (fluidLengthSquared(x - anchor) > fluidSquare(drift)) {  // no root: the test of every moving particle
        s.still = 0.0f;
        s.anchor = x;
    } else {
        SD_PRECISE float longer = still + dt;
        s.still = longer;
        s.asleep = longer >= sleepTime;
    }
    return s;
}

// --- Rigid bodies (Box2D fixtures, src/coupling/) --------------------------------
// A fixture of a body as the 2D fluid sees it, in world coordinates at the
// body's pose of the current substep (slide 50: a separate representation
// for fluid collision). A convex polygon is the intersection of its edges'
// half-planes (fluidPolygonSurface); an edge (and each segment of a chain) is
// two-sided; a circle is a centre and radius.

SD_CONST uint SD_BODY_SHAPE_CIRCLE = 0u;
SD_CONST uint SD_BODY_SHAPE_POLYGON = 1u;
SD_CONST uint SD_BODY_SHAPE_SEGMENT = 2u;

// 304 bytes.
struct FluidBodyShape {
    FluidPolygon polygon;  // POLYGON: counter-clockwise vertices (m)
    vec4 geometry;         // SEGMENT: end points a.xy, b.xy (m); CIRCLE: centre.xy, radius (m), unused
    uint kind;             // SD_BODY_SHAPE_*
    uint body;             // index of its body in the step's body list
    uint pad0, pad1;
};

SD_FN FluidSurface fluidSegmentSurface(vec2 a, vec2 b, vec3 p) {
    vec2 x = vec2(p.x, p.y);
    vec2 edge = b - a;
    float len2 = dot(edge, edge);
    float t = len2 > 0.0f ? clamp(dot(x - a, edge) / len2, 0.0f, 1.0f) : 0.0f;
    vec2 away = x - (a + edge * t);
    float d = length(away);
    // On the segment itself: the side is undefined; take the edge's left normal.
    vec2 n = d > 0.0f ? away / d : (len2 > 0.0f ? vec2(-edge.y, edge.x) / sqrt(len2) : vec2(0.0f, 1.0f));
    return makeSurface(d, vec3(n.x, n.y, 0.0f));
}

SD_FN FluidSurface fluidBodyShapeSurface(SD_IN(FluidBodyShape) s, vec3 p) {
    if (s.kind == SD_BODY_SHAPE_CIRCLE) {
        vec2 offset = vec2(p.x, p.y) - vec2(s.geometry.x, s.geometry.y);
        float len = length(offset);
        vec2 n = len > 0.0f ? offset / len : vec2(0.0f, 1.0f);
        return makeSurface(len - s.geometry.z, vec3(n.x, n.y, 0.0f));
    }
    if (s.kind == SD_BODY_SHAPE_SEGMENT) {
        return fluidSegmentSurface(vec2(s.geometry.x, s.geometry.y), vec2(s.geometry.z, s.geometry.w), p);
    }
    return fluidPolygonSurface(s.polygon, p);
}

// Particle-body contact (slide 51, two-way): the particle a rotationless body
// of mass m_p, the rigid body of mass m_b and inertia I_b about its centre of
// mass, r from that centre to the contact point. The normal mass
// 1 / (1/m_p + 1/m_b + (r x n)^2 / I_b) is in kg; inverse masses of 0 stand
// for a static or kinematic body.
SD_FN float fluidBodyNormalMass(float particleInvMass, float bodyInvMass, float bodyInvInertia, vec2 r, vec2 n) {
    float rn = r.x * n.y - r.y * n.x;
    float k = particleInvMass + bodyInvMass + rn * rn * bodyInvInertia;
    return k > 0.0f ? 1.0f / k : 0.0f;
}

// Velocity (m/s) of the body's material point at r: v + w x r.
SD_FN vec2 fluidBodyPointVelocity(vec2 v, float w, vec2 r) {
    return v + vec2(-w * r.y, w * r.x);
}

// One visit of a particle-body contact along its normal: vn the relative
// normal velocity (particle minus body point, m/s), target the least vn the
// contact allows (m/s, -separation / dt: close the gap, no more), normalMass
// in kg; accumulated and delta are impulses (N s), the total clamped >= 0 so
// the body only ever pushes.
SD_FN FluidImpulse fluidBodyNormalImpulse(float vn, float target, float normalMass, float accumulated) {
    float lambda = (target - vn) * normalMass;
    float total = max(accumulated + lambda, 0.0f);
    FluidImpulse r;
    r.accumulated = total;
    r.delta = total - accumulated;
    return r;
}

// Coulomb friction along the tangent: vt the relative tangential velocity
// (m/s), the accumulated impulse (N s) kept within +-limit (mu times the
// normal impulse).
SD_FN FluidImpulse fluidBodyFrictionImpulse(float vt, float tangentMass, float accumulated, float limit) {
    float total = clamp(accumulated - vt * tangentMass, -limit, limit);
    FluidImpulse r;
    r.accumulated = total;
    r.delta = total - accumulated;
    return r;
}

// A body as the fluid's contacts see it during a substep (the CPU's StepBody,
// its motion part; 48 bytes on the device): centre of mass (m), velocity of
// the centre (m/s), angular velocity (rad/s), inverse mass (1/kg) and
// inertia (1/(kg m^2), 0 for a static or kinematic body), friction, and the
// impulses the fluid gave it this step (N s, N m s about the centre).
struct FluidBodyMotion {
    vec2 centre;
    vec2 velocity;
    float angularVelocity;
    float invMass;
    float invInertia;
    float friction;
    vec2 linearImpulse;
    float angularImpulse;
    float pad0;
};

// A particle touching (or about to touch) a body shape this substep: the
// CPU's BodyContact and a slot of the device's contacts. 48 bytes.
struct FluidBodyContact {
    vec2 normal;           // unit, out of the body
    vec2 r;                // m, centre of mass to the contact point
    float separation;      // m, surface distance minus the particle radius
    float normalMass;      // kg
    float tangentMass;     // kg
    float normalImpulse;   // N s, accumulated
    float tangentImpulse;  // N s, accumulated
    uint particle;
    uint body;             // index in the step's body list
    uint pad0;
};

// What a particle at x moving at v finds at a body shape whose surface at x
// is `surface`: a contact when it touches the shape or can within dt (its
// speed relative to the body's material point, plus a spacing for what the
// solve adds: speculative, as for colliders), and an impact when it reaches
// the surface this substep faster than kFluidImpactSpeed along the normal
// (one strike, one event: the solve then removes the approach).
struct FluidBodyFound {
    uint found;
    uint impact;
    float approach;  // m/s along the normal, toward the body
    FluidBodyContact contact;  // particle and body left to the caller
};

SD_FN FluidBodyFound fluidFindBodyContact(FluidSurface surface, vec2 x, vec2 v, SD_IN(FluidBodyMotion) b,
                                          float particleInvMass, float radius, float spacing, float dt,
                                          float impactSpeed) {
    FluidBodyFound f;
    f.found = 0u;
    f.impact = 0u;
    f.approach = 0.0f;
    vec2 n = vec2(surface.normal.x, surface.normal.y);
    SD_PRECISE vec2 onSurface = x - n * surface.distance;
    SD_PRECISE vec2 r = onSurface - b.centre;
    SD_PRECISE vec2 rel = v - fluidBodyPointVelocity(b.velocity, b.angularVelocity, r);
    SD_PRECISE float travel = fluidLength(vec3(rel.x, rel.y, 0.0f)) * dt;
    SD_PRECISE float reach = radius + travel + spacing;
    if (!(surface.distance < reach)) {
        return f;
    }
    f.found = 1u;
    f.contact.normal = n;
    f.contact.r = r;
    f.contact.separation = surface.distance - radius;
    f.contact.normalMass = fluidBodyNormalMass(particleInvMass, b.invMass, b.invInertia, r, n);
    f.contact.tangentMass = fluidBodyNormalMass(particleInvMass, b.invMass, b.invInertia, r, vec2(-n.y, n.x));
    f.contact.normalImpulse = 0.0f;
    f.contact.tangentImpulse = 0.0f;
    f.contact.particle = 0u;
    f.contact.body = 0u;
    f.contact.pad0 = 0u;
    SD_PRECISE float approach = -dot(rel, n);
    f.approach = approach;
    f.impact = approach > impactSpeed && f.contact.separation < approach * dt ? 1u : 0u;
    return f;
}

// One visit of a particle-body contact (slide 51): the particle's velocity
// vp and pseudo velocity (m/s) after it, the accumulated impulses, the
// impulse on the particle (N s) and its moment about the body's centre, and
// the body's velocities after the opposite impulse (a dynamic body's; a
// static or kinematic one keeps its own). Real velocity: close the gap, no
// more; an overlap is pushed out by the pseudo velocity when impulses are
// split (kinetic energy otherwise). With split impulses the particle's
// motion this substep, real plus pseudo, relative to the body may not enter
// it: position only, no momentum, no reaction on the body.
struct FluidBodyVisit {
    vec2 velocity;
    vec2 pseudo;
    float normalImpulse;
    float tangentImpulse;
    vec2 impulse;
    float angular;
    vec2 bodyVelocity;
    float bodyAngularVelocity;
};

SD_FN FluidBodyVisit fluidSolveBodyContact(SD_IN(FluidBodyContact) c, SD_IN(FluidBodyMotion) b, vec2 vp,
                                           vec2 pseudo, float particleInvMass, float invDt, float radius,
                                           float fluidFriction, bool split, bool dynamic) {
    FluidBodyVisit out1;
    vec2 n = c.normal;
    vec2 vb = fluidBodyPointVelocity(b.velocity, b.angularVelocity, c.r);
    SD_PRECISE float gap = -c.separation * invDt;
    SD_PRECISE float overlap = -c.separation * SD_FLUID_OVERLAP_PUSH * invDt;
    float target = c.separation >= 0.0f ? gap : (split ? 0.0f : overlap);
    FluidImpulse normal = fluidBodyNormalImpulse(dot(vp - vb, n), target, c.normalMass, c.normalImpulse);
    out1.normalImpulse = normal.accumulated;
    out1.tangentImpulse = c.tangentImpulse;
    SD_PRECISE vec2 impulse = n * normal.delta;  // N s, on the particle
    float mu = sqrt(fluidFriction * b.friction);
    if (mu > 0.0f) {
        vec2 t = vec2(-n.y, n.x);
        SD_PRECISE vec2 vAfter = vp + impulse * particleInvMass;
        vec2 vbAfter = vb;
        if (dynamic) {
            SD_PRECISE float turn = c.r.x * impulse.y - c.r.y * impulse.x;
            SD_PRECISE vec2 bv = b.velocity - impulse * b.invMass;
            SD_PRECISE float bw = b.angularVelocity - turn * b.invInertia;
            vbAfter = fluidBodyPointVelocity(bv, bw, c.r);
        }
        FluidImpulse friction =
            fluidBodyFrictionImpulse(dot(vAfter - vbAfter, t), c.tangentMass, c.tangentImpulse, mu * normal.accumulated);
        out1.tangentImpulse = friction.accumulated;
        impulse = impulse + t * friction.delta;
    }
    out1.impulse = impulse;
    out1.angular = 0.0f;
    out1.bodyVelocity = b.velocity;
    out1.bodyAngularVelocity = b.angularVelocity;
    if (impulse.x != 0.0f || impulse.y != 0.0f) {
        SD_PRECISE vec2 moved = vp + impulse * particleInvMass;
        vp = moved;
        if (dynamic) {
            // Newton's third law: the body takes the opposite impulse, now
            // (its local velocity) and at the step's end (the caller's sum).
            SD_PRECISE float angular = c.r.x * impulse.y - c.r.y * impulse.x;
            SD_PRECISE vec2 bv = b.velocity - impulse * b.invMass;
            SD_PRECISE float bw = b.angularVelocity - angular * b.invInertia;
            out1.angular = angular;
            out1.bodyVelocity = bv;
            out1.bodyAngularVelocity = bw;
        }
    }
    out1.velocity = vp;
    out1.pseudo = pseudo;
    if (split) {
        vec2 vbNow = fluidBodyPointVelocity(out1.bodyVelocity, out1.bodyAngularVelocity, c.r);
        SD_PRECISE vec2 total = vp + pseudo;
        SD_PRECISE vec2 rel = total - vbNow;
        vec3 moved = fluidContactVelocity(vec3(rel.x, rel.y, 0.0f),
                                          makeSurface(c.separation + radius, vec3(n.x, n.y, 0.0f)), radius, invDt,
                                          SD_FLUID_OVERLAP_PUSH, 0.0f);
        SD_PRECISE vec2 change = vec2(moved.x, moved.y) - rel;
        SD_PRECISE vec2 p = pseudo + change;
        out1.pseudo = p;
    }
    return out1;
}

// A path x0 -> x1 stopped before the segment a-b if it crosses it (an end
// on the line counts): SD_FLUID_SKIN short of the crossing along the path
// and SD_FLUID_SKIN off the line on x0's side, so the end is strictly on
// x0's side of this segment and, at a corner where two segments join, of the
// other one too (the crossing point is then the shared vertex, and backing
// along the path goes back inside). A path that starts on the line has no
// side: left alone. A stopped particle also stops moving into the segment,
// as at a collider: its velocity v keeps no part toward the line.
struct FluidPathEnd {
    uint stopped;
    vec2 x1;
    vec2 v;
};

SD_FN float fluidCross2(vec2 a, vec2 b) {
    SD_PRECISE float ab = a.x * b.y;
    SD_PRECISE float ba = a.y * b.x;
    SD_PRECISE float c = ab - ba;
    return c;
}

SD_FN FluidPathEnd fluidStopBeforeSegment(vec2 a, vec2 b, vec2 x0, vec2 x1, vec2 v) {
    FluidPathEnd end;
    end.stopped = 0u;
    end.x1 = x1;
    end.v = v;
    vec2 edge = b - a;
    SD_PRECISE float len2 = dot(edge, edge);
    float s0 = fluidCross2(edge, x0 - a);
    float s1 = fluidCross2(edge, x1 - a);
    if (len2 <= 0.0f || s0 == 0.0f || (s0 > 0.0f ? s1 > 0.0f : s1 < 0.0f)) {
        return end;
    }
    SD_PRECISE float t = s0 / (s0 - s1);  // in (0, 1]: where the path meets the line
    SD_PRECISE vec2 path = x1 - x0;
    SD_PRECISE vec2 p = x0 + path * t;
    SD_PRECISE float u = dot(p - a, edge) / len2;
    SD_PRECISE float slack = SD_FLUID_SKIN / sqrt(len2);  // the vertices themselves stop a path
    if (u < -slack || u > 1.0f + slack) {
        return end;
    }
    SD_PRECISE vec2 side = vec2(-edge.y, edge.x) * ((s0 > 0.0f ? 1.0f : -1.0f) / sqrt(len2));
    SD_PRECISE float length1 = fluidLength(vec3(path.x, path.y, 0.0f));
    SD_PRECISE vec2 along = length1 > 0.0f ? path / length1 : vec2(0.0f);
    SD_PRECISE vec2 stop = p + side * SD_FLUID_SKIN - along * SD_FLUID_SKIN;
    end.stopped = 1u;
    end.x1 = stop;
    vec3 kept = fluidWithoutInward(vec3(v.x, v.y, 0.0f), vec3(side.x, side.y, 0.0f));
    end.v = vec2(kept.x, kept.y);
    return end;
}

// A path from -> to stopped before the edges of one still body shape it
// crosses (fluidStopBeforeSegment): a segment's two sides, and a polygon's
// edges that `from` lies outside of (counter-clockwise: outside is to the
// right), in vertex order; a circle stops nothing (a particle found inside
// is pushed out through the nearest surface instead).
SD_FN FluidPathEnd fluidStopBeforeShapeEdges(SD_IN(FluidBodyShape) shape, vec2 from, vec2 to, vec2 v) {
    FluidPathEnd end;
    end.stopped = 0u;
    end.x1 = to;
    end.v = v;
    if (shape.kind == SD_BODY_SHAPE_SEGMENT) {
        vec4 g = shape.geometry;
        return fluidStopBeforeSegment(vec2(g.x, g.y), vec2(g.z, g.w), from, to, v);
    }
    if (shape.kind != SD_BODY_SHAPE_POLYGON) {
        return end;
    }
    for (uint e = 0u; e < shape.polygon.count; ++e) {
        vec2 a = vec2(shape.polygon.vertices[e].x, shape.polygon.vertices[e].y);
        uint next = (e + 1u) % shape.polygon.count;
        vec2 c = vec2(shape.polygon.vertices[next].x, shape.polygon.vertices[next].y);
        if (fluidCross2(c - a, from - a) < 0.0f) {
            FluidPathEnd edge = fluidStopBeforeSegment(a, c, from, end.x1, end.v);
            end.x1 = edge.x1;
            end.v = edge.v;
            end.stopped = end.stopped | edge.stopped;
        }
    }
    return end;
}

// A point inside a body shape moved out through its nearest surface, to
// SD_FLUID_SKIN outside it; a point outside stays.
SD_FN vec2 fluidPushOutOfShape(SD_IN(FluidBodyShape) shape, vec2 x) {
    FluidSurface surface = fluidBodyShapeSurface(shape, vec3(x.x, x.y, 0.0f));
    if (surface.distance < 0.0f) {
        SD_PRECISE float depth = SD_FLUID_SKIN - surface.distance;
        SD_PRECISE vec2 out1 = x + vec2(surface.normal.x, surface.normal.y) * depth;
        return out1;
    }
    return x;
}

// Whether the grid cell of a 2D particle's key (fluidGridKey) lies in a body
// shape's cells, first.xy to last.xy inclusive (the cells the shape's box,
// grown by what can reach it this substep, covers): the shapes a particle
// tests are those of its cell, in shape order, on both backends.
SD_FN bool fluidCellInShapeCells(uint key, ivec4 shapeCells, int cellsX) {
    uint cell = key >> 2u;
    int cx = int(cell % uint(cellsX));
    int cy = int(cell / uint(cellsX));
    return cx >= shapeCells.x && cx <= shapeCells.z && cy >= shapeCells.y && cy <= shapeCells.w;
}

// One scalar velocity constraint of a joint between bodies a and b (the
// CPU's JointRow, src/fluid/body_joints.h; 48 bytes on the device):
// Cdot = n . (vB - vA) + sB wB - sA wA, driven to `bias` with an accumulated
// impulse kept within [lowerImpulse, upperImpulse] (N s).
struct FluidJointRow {
    uint a;
    uint b;
    vec2 n;
    float sA;
    float sB;
    float mass;          // 1 / (the row's inverse effective mass)
    float bias;          // m/s or rad/s
    float lowerImpulse;
    float upperImpulse;
    float impulse;
    float pad0;
};

// Passes over the joints' rows after each sweep of the body contacts: the
// rows are few (a handful per joint) and a chain of joints needs a few to
// pass a push along.
SD_CONST int SD_FLUID_JOINT_PASSES = 2;

// One visit of a joint row (Box2D 2.4's joints, b2_*_joint.cpp): the
// accumulated impulse after it and both bodies' velocities.
struct FluidJointVisit {
    float impulse;
    vec2 velocityA;
    float angularA;
    vec2 velocityB;
    float angularB;
};

SD_FN FluidJointVisit fluidSolveJointRow(SD_IN(FluidJointRow) r, SD_IN(FluidBodyMotion) a, SD_IN(FluidBodyMotion) b) {
    SD_PRECISE vec2 dv = b.velocity - a.velocity;
    SD_PRECISE float along = dot(r.n, dv);
    SD_PRECISE float spinB = r.sB * b.angularVelocity;
    SD_PRECISE float spinA = r.sA * a.angularVelocity;
    SD_PRECISE float cdot = along + spinB - spinA;
    SD_PRECISE float wanted = r.impulse + r.mass * (r.bias - cdot);
    float total = clamp(wanted, r.lowerImpulse, r.upperImpulse);
    SD_PRECISE float delta = total - r.impulse;
    FluidJointVisit v;
    v.impulse = total;
    SD_PRECISE vec2 va = a.velocity - r.n * (delta * a.invMass);
    SD_PRECISE float wa = a.angularVelocity - r.sA * delta * a.invInertia;
    SD_PRECISE vec2 vb = b.velocity + r.n * (delta * b.invMass);
    SD_PRECISE float wb = b.angularVelocity + r.sB * delta * b.invInertia;
    v.velocityA = va;
    v.angularA = wa;
    v.velocityB = vb;
    v.angularB = wb;
    return v;
}

SD_END
#endif
