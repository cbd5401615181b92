#version 450
// The constraint fluid's contacts with static colliders on the device (the
// CPU's findContacts and solveContacts in src/fluid/collide.cpp; slide 51).
// Rigid bodies (2D; the CPU's findBodyContacts and solveBodyContacts in
// src/fluid/body_contacts.cpp) are found and solved here too, after the
// colliders.
// Passes (a specialization constant):
//   0 find:    each particle's surfaces within reach this substep
//              (speculative: what it could reach, plus a spacing for what
//              the solve adds), as one bit per surface, and the colliders'
//              share of its density and Jacobian (the motionless ghosts,
//              src/fluid/wall_density.cpp); its body contacts and strikes;
//   1 solve:   each particle's contacts, in surface order, then those with
//              bodies the fluid does not move, on the solve's working
//              velocities (fluid_solve.comp records it between sweeps);
//   4 count:   each particle's contacts with bodies the fluid moves, summed
//              in particle order within its workgroup (shared memory), and
//              the workgroup's total;
//   5 groups:  the workgroups' totals summed in order (one invocation over
//              the workgroups, a 64th of the particles);
//   2 order:   each particle writes its contacts with bodies the fluid
//              moves at its place so found: the list in the CPU's order;
//   3 dynamic: those solved in that order, then the joints' rows (one
//              invocation, after every solve pass).
// Surfaces are the world's planes, spheres and boxes in creation order, then
// the fluid's polygons, as on the CPU. The solve pass recomputes each
// surface at the particle's position instead of storing it: the same
// function of the same numbers, so the CPU's stored surface.
#include "fluid.glsl"
#include "layout.glsl"

layout(constant_id = 0) const uint PASS = 0u;

layout(local_size_x = SD_FLUID_CONTACTS_WORKGROUP) in;

layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_X) readonly buffer X { float xs[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_V) readonly buffer V { float vs[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_COLLIDERS) readonly buffer Colliders { ColliderParams colliders[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_POLYGONS) readonly buffer Polygons { FluidPolygon polygons[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_WALL_TABLE) readonly buffer WallTable { vec2 wallTable[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_WALL) writeonly buffer Wall { vec4 wall[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_MASK) buffer Mask { uint masks[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_MOTION) buffer Motion { float motion[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_SHAPES) readonly buffer Shapes { FluidBodyShape shapes[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_SHAPE_CELLS) readonly buffer ShapeCells { ivec4 shapeCells[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_BODIES) buffer Bodies { FluidBodyMotion bodies[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_BODY_CONTACTS) buffer BodyContacts { FluidBodyContact bodyContacts[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_BODY_COUNTS) buffer BodyCounts { uint bodyCounts[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_BODY_REPORT) buffer BodyReport {
    FluidBodyReport report;
    FluidBodyImpact impacts[];
};
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_ORDER) readonly buffer Order { uint order[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_IDS) readonly buffer Ids { uint ids[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_DYNAMIC) buffer Dynamic { uint dynamicList[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_JOINT_ROWS) buffer JointRows { FluidJointRow rows[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_STILLS) buffer Stills { float stills[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_DYNAMIC_STARTS) buffer DynamicStarts { uint dynamicStarts[]; };
layout(std430, set = 0, binding = SD_FLUID_CONTACTS_BINDING_GROUP_STARTS) buffer GroupStarts { uint groupStarts[]; };

shared uint groupCounts[SD_FLUID_CONTACTS_WORKGROUP];

layout(push_constant) uniform Contacts { FluidContactsPush args; };  // FluidContactsPush in layout.glsl

vec3 load(uint i, bool velocity) {
    uint d = args.dimension;
    if (velocity) return vec3(vs[d * i], vs[d * i + 1u], d == 3u ? vs[d * i + 2u] : 0.0f);
    return vec3(xs[d * i], xs[d * i + 1u], d == 3u ? xs[d * i + 2u] : 0.0f);
}

// Surface k at x: a collider's (projected into the plane in 2D), then the
// polygons'.
FluidSurface surfaceOf(uint k, vec3 x) {
    if (k < args.colliders) {
        FluidSurface s = fluidColliderSurface(colliders[k], x);
        return args.dimension == 2u ? fluidFlatSurface(s) : s;
    }
    return fluidPolygonSurface(polygons[k - args.colliders], x);
}

// The body shapes of the particle's grid cell, in shape order (the CPU's
// findBodyContacts): its contacts into its slots, counted (a count over the
// slots makes the host run the substep again with more), and its impacts
// appended (the host sorts them into the CPU's order).
void findBodies(uint i, vec3 x, vec3 v) {
    uint key = fluidGridKey(x, 2u, vec3(args.grid.x, args.grid.y, 0.0f), args.grid.z, ivec3(args.cells.x, args.cells.y, 1));
    uint slots = uint(args.cells.w);
    uint found = 0u;
    for (uint k = 0u; k < uint(args.cells.z); ++k) {
        if (!fluidCellInShapeCells(key, shapeCells[k], args.cells.x)) continue;
        FluidBodyShape shape = shapes[k];
        FluidSurface surface = fluidBodyShapeSurface(shape, x);
        FluidBodyFound f = fluidFindBodyContact(surface, vec2(x.x, x.y), vec2(v.x, v.y), bodies[shape.body], args.grid.w,
                                                args.radius, args.spacing, args.dt, args.impactSpeed);
        if (f.found == 0u) continue;
        // Water touching a body it moves does not fall asleep (the CPU's
        // findBodyContacts; docs/fluid.md, "Floating bodies").
        if (bodies[shape.body].invMass > 0.0f) stills[order[i]] = 0.0f;
        if (found < slots) {
            FluidBodyContact c = f.contact;
            c.particle = i;
            c.body = shape.body;
            bodyContacts[i * slots + found] = c;
        }
        found += 1u;
        if (f.impact != 0u) {
            uint at = atomicAdd(report.impacts, 1u);
            if (at < args.impactRoom) {
                FluidBodyImpact hit;
                hit.place = i;
                hit.shape = k;
                hit.id = ids[order[i]];
                hit.body = shape.body;
                hit.position = vec2(x.x, x.y);
                hit.approach = f.approach;
                hit.pad0 = 0u;
                impacts[at] = hit;
            }
        }
    }
    bodyCounts[i] = found;
    if (found > 0u) {
        atomicAdd(report.contacts, found);
        atomicMax(report.mostContacts, found);
    }
}

void find(uint i) {
    if (i >= args.count) {
        return;
    }
    uint d = args.dimension;
    vec3 x = load(i, false);
    vec3 v = load(i, true);
    precise float speed2x = v.x * v.x;
    precise float speed2y = v.y * v.y;
    precise float speed2 = speed2x + speed2y;
    if (d == 3u) {
        precise float speed2z = v.z * v.z;
        speed2 = speed2 + speed2z;
    }
    precise float travel = sqrt(speed2) * args.dt;
    precise float near = args.radius + travel;
    precise float reach = near + args.spacing;
    uint mask = 0u;
    precise float density = 0.0f;
    precise float gx = 0.0f;
    precise float gy = 0.0f;
    precise float gz = 0.0f;
    uint surfaces = args.colliders + args.polygons;
    for (uint k = 0u; k < surfaces; ++k) {
        FluidSurface s = surfaceOf(k, x);
        if (s.distance < reach) mask |= 1u << k;
        // The ghosts' direction from the particle is into the wall: -normal.
        FluidWallPlace place = fluidWallPlace(s.distance, args.tableStart, args.tableStep, int(args.tableSize));
        float lent = 0.0f;
        float push = 0.0f;
        if (place.entry >= 0) {
            vec2 below = wallTable[place.entry];
            vec2 above = wallTable[place.entry + 1];
            lent = fluidWallLerp(below.x, above.x, place.fraction);
            push = fluidWallLerp(below.y, above.y, place.fraction);
        }
        density = density + lent;
        precise float px = s.normal.x * push;
        precise float py = s.normal.y * push;
        precise float pz = s.normal.z * push;
        gx = gx - px;
        gy = gy - py;
        gz = gz - pz;
    }
    masks[i] = mask;
    wall[i] = vec4(density, gx, gy, gz);
    if (args.cells.z > 0) {
        findBodies(i, x, v);
    }
}

// The particle's body contacts after its colliders' (the CPU's
// solveBodyContacts for bodies the fluid does not move: each changes only
// its particle, so per particle in the find's order is the CPU's order).
void solveBodies(uint i) {
    uint slots = uint(args.cells.w);
    uint n = min(bodyCounts[i], slots);
    precise float invDt = 1.0f / args.dt;
    uint m = 4u * i;
    for (uint j = 0u; j < n; ++j) {
        FluidBodyContact c = bodyContacts[i * slots + j];
        if (bodies[c.body].invMass > 0.0f) continue;  // the DYNAMIC pass's
        vec2 vp = vec2(motion[m], motion[m + 1u]);
        vec2 pseudo = vec2(motion[m + 2u], motion[m + 3u]);
        FluidBodyVisit visit = fluidSolveBodyContact(c, bodies[c.body], vp, pseudo, args.grid.w, invDt, args.radius,
                                                     args.friction, args.split != 0u, false);
        bodyContacts[i * slots + j].normalImpulse = visit.normalImpulse;
        bodyContacts[i * slots + j].tangentImpulse = visit.tangentImpulse;
        motion[m] = visit.velocity.x;
        motion[m + 1u] = visit.velocity.y;
        motion[m + 2u] = visit.pseudo.x;
        motion[m + 3u] = visit.pseudo.y;
    }
}

void solveColliders(uint i) {
    uint mask = masks[i];
    if (mask == 0u) {
        return;
    }
    uint d = args.dimension;
    vec3 x = load(i, false);
    precise float invDt = 1.0f / args.dt;
    uint m = 2u * d * i;
    uint surfaces = args.colliders + args.polygons;
    for (uint k = 0u; k < surfaces; ++k) {
        if ((mask & (1u << k)) == 0u) continue;
        FluidSurface s = surfaceOf(k, x);
        vec3 v = vec3(motion[m], motion[m + 1u], d == 3u ? motion[m + 2u] : 0.0f);
        if (args.split == 0u) {
            vec3 out1 = fluidContactVelocity(v, s, args.radius, invDt, SD_FLUID_OVERLAP_PUSH, args.friction);
            motion[m] = out1.x;
            motion[m + 1u] = out1.y;
            if (d == 3u) motion[m + 2u] = out1.z;
            continue;
        }
        // Split impulses: the real velocity only stops at the surface (no
        // push out of an overlap, which would be kinetic energy); the
        // particle's motion this substep, real plus pseudo, also may not
        // enter the wall, and the pseudo part pushes an overlap out.
        vec3 real = fluidContactVelocity(v, s, args.radius, invDt, 0.0f, args.friction);
        vec3 pseudo = vec3(motion[m + d], motion[m + d + 1u], d == 3u ? motion[m + d + 2u] : 0.0f);
        precise vec3 total = real + pseudo;
        vec3 moved = fluidContactVelocity(total, s, args.radius, invDt, SD_FLUID_OVERLAP_PUSH, 0.0f);
        precise float cx = moved.x - total.x;
        precise float cy = moved.y - total.y;
        precise float cz = moved.z - total.z;
        precise float px = pseudo.x + cx;
        precise float py = pseudo.y + cy;
        precise float pz = pseudo.z + cz;
        motion[m] = real.x;
        motion[m + 1u] = real.y;
        motion[m + d] = px;
        motion[m + d + 1u] = py;
        if (d == 3u) {
            motion[m + 2u] = real.z;
            motion[m + d + 2u] = pz;
        }
    }
}

// The contacts with bodies the fluid moves, listed in the CPU's order:
// particles in grid order, each one's in shape order. A particle's place in
// the list is the count of such contacts before it: within its workgroup
// (COUNT), plus the workgroups' before it (GROUPS); ORDER writes them there.
// The host records the three only when there are shapes (bodies without
// shapes hold only joints, and the find then writes no counts).
bool movedBy(uint at) {
    return bodies[bodyContacts[at].body].invMass > 0.0f;
}

uint dynamicContacts(uint i) {
    if (i >= args.count) {
        return 0u;
    }
    uint slots = uint(args.cells.w);
    uint n = min(bodyCounts[i], slots);
    uint m = 0u;
    for (uint j = 0u; j < n; ++j) {
        if (movedBy(i * slots + j)) {
            m += 1u;
        }
    }
    return m;
}

void countDynamic(uint i) {
    uint local = gl_LocalInvocationID.x;
    groupCounts[local] = dynamicContacts(i);
    barrier();
    if (local == 0u) {
        uint sum = 0u;
        for (uint k = 0u; k < SD_FLUID_CONTACTS_WORKGROUP; ++k) {
            uint c = groupCounts[k];
            groupCounts[k] = sum;
            sum += c;
        }
        groupStarts[gl_WorkGroupID.x] = sum;
    }
    barrier();
    if (i < args.count) {
        dynamicStarts[i] = groupCounts[local];
    }
}

void sumGroups() {
    uint groups = (args.count + SD_FLUID_CONTACTS_WORKGROUP - 1u) / SD_FLUID_CONTACTS_WORKGROUP;
    uint sum = 0u;
    for (uint g = 0u; g < groups; ++g) {
        uint c = groupStarts[g];
        groupStarts[g] = sum;
        sum += c;
    }
    report.dynamic = sum;
}

void orderDynamic(uint i) {
    if (i >= args.count) {
        return;
    }
    uint slots = uint(args.cells.w);
    uint n = min(bodyCounts[i], slots);
    uint m = groupStarts[gl_WorkGroupID.x] + dynamicStarts[i];
    for (uint j = 0u; j < n; ++j) {
        if (movedBy(i * slots + j)) {
            dynamicList[m] = i * slots + j;
            m += 1u;
        }
    }
}

// The contacts with bodies the fluid moves in that order (Gauss-Seidel, a
// body's velocity changed by each, as on the CPU), then the joints' rows,
// which answer the contacts' push on the bodies (one invocation).
void solveDynamic() {
    precise float invDt = 1.0f / args.dt;
    for (uint k = 0u; k < report.dynamic; ++k) {
        uint at = dynamicList[k];
        FluidBodyContact c = bodyContacts[at];
        uint m = 4u * c.particle;
        vec2 vp = vec2(motion[m], motion[m + 1u]);
        vec2 pseudo = vec2(motion[m + 2u], motion[m + 3u]);
        FluidBodyVisit visit = fluidSolveBodyContact(c, bodies[c.body], vp, pseudo, args.grid.w, invDt, args.radius,
                                                     args.friction, args.split != 0u, true);
        bodyContacts[at].normalImpulse = visit.normalImpulse;
        bodyContacts[at].tangentImpulse = visit.tangentImpulse;
        motion[m] = visit.velocity.x;
        motion[m + 1u] = visit.velocity.y;
        motion[m + 2u] = visit.pseudo.x;
        motion[m + 3u] = visit.pseudo.y;
        if (visit.impulse.x != 0.0f || visit.impulse.y != 0.0f) {
            // Newton's third law: the body takes the opposite impulse, now
            // and in the step's sum.
            bodies[c.body].velocity = visit.bodyVelocity;
            bodies[c.body].angularVelocity = visit.bodyAngularVelocity;
            precise vec2 linear = bodies[c.body].linearImpulse - visit.impulse;
            precise float angular = bodies[c.body].angularImpulse - visit.angular;
            bodies[c.body].linearImpulse = linear;
            bodies[c.body].angularImpulse = angular;
        }
    }
    for (int pass = 0; pass < SD_FLUID_JOINT_PASSES; ++pass) {
        for (uint r = 0u; r < args.jointRows; ++r) {
            FluidJointRow row = rows[r];
            FluidJointVisit v = fluidSolveJointRow(row, bodies[row.a], bodies[row.b]);
            rows[r].impulse = v.impulse;
            bodies[row.a].velocity = v.velocityA;
            bodies[row.a].angularVelocity = v.angularA;
            bodies[row.b].velocity = v.velocityB;
            bodies[row.b].angularVelocity = v.angularB;
        }
    }
}

void solve(uint i) {
    if (i >= args.count) {
        return;
    }
    solveColliders(i);
    if (args.cells.z > 0) {
        solveBodies(i);
    }
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (PASS == SD_FLUID_CONTACTS_PASS_COUNT) {
        countDynamic(i);  // every invocation reaches its barriers
    } else if (PASS == SD_FLUID_CONTACTS_PASS_GROUPS || PASS == SD_FLUID_CONTACTS_PASS_DYNAMIC) {
        if (i == 0u) {
            if (PASS == SD_FLUID_CONTACTS_PASS_GROUPS) {
                sumGroups();
            } else {
                solveDynamic();
            }
        }
    } else if (PASS == SD_FLUID_CONTACTS_PASS_ORDER) {
        orderDynamic(i);
    } else if (PASS == SD_FLUID_CONTACTS_PASS_FIND) {
        find(i);
    } else {
        solve(i);
    }
}
