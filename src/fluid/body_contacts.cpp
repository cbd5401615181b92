// Particle-body contacts (slides 50-51): src/coupling gathers the bodies near
// the fluid once per fluid step (BodyLink::gather, through Box2D's broad
// phase); every substep their shapes are placed at the bodies' local poses and binned into the fluid's grid cells
// (slide 50: reuse the binning grid), each particle tests the shapes of its
// cell, and the contacts are solved as velocity constraints after each sweep
// of the fluid constraints, the particle a small rotationless body.
//
// Order and threads: contacts with static and kinematic bodies change only
// their particle, so chunks of particles solve them in parallel. Contacts with
// dynamic bodies also change the body's local velocity, and a body is touched
// by particles of many chunks; they are solved on the calling thread in one
// fixed order (chunk by chunk, particles in grid order), which is
// Gauss-Seidel like the rest of the solver and the same for any thread count.
// (A parallel Jacobi sweep over chunks overshoots a light body touched from
// several chunks.) They are few: a body's surface, not its volume.
#include "fluid/body_contacts.h"

#include "core/room.h"
#include "fluid/fluid_state.h"

#include <spindrift/world.h>

#include <algorithm>
#include <cmath>

namespace spindrift::fluid {
namespace {

glm::vec2 rotate(float angle, glm::vec2 v) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}


/// World geometry of one local shape at its body's pose.
kernels::FluidBodyShape place(const LocalShape& local, const StepBody& b, std::uint32_t bodyIndex) {
    const glm::vec2 origin = b.centre - rotate(b.angle, b.localCentre);
    auto toWorld = [&](glm::vec2 p) { return origin + rotate(b.angle, p); };
    kernels::FluidBodyShape s{};
    s.kind = local.kind;
    s.body = bodyIndex;
    if (local.kind == kernels::SD_BODY_SHAPE_CIRCLE) {
        const glm::vec2 c = toWorld(local.vertices[0]);
        s.geometry = glm::vec4(c, local.radius, 0.0f);
    } else if (local.kind == kernels::SD_BODY_SHAPE_SEGMENT) {
        s.geometry = glm::vec4(toWorld(local.vertices[0]), toWorld(local.vertices[1]));
    } else {
        s.polygon.count = static_cast<std::uint32_t>(local.vertices.size());
        for (std::size_t i = 0; i < local.vertices.size(); ++i) {
            s.polygon.vertices[i] = glm::vec4(toWorld(local.vertices[i]), 0.0f, 0.0f);
        }
    }
    return s;
}

/// Bounding box (lo.xy, hi.xy) of a placed shape (m).
glm::vec4 boundsOf(const kernels::FluidBodyShape& s) {
    if (s.kind == kernels::SD_BODY_SHAPE_CIRCLE) {
        return glm::vec4(s.geometry.x - s.geometry.z, s.geometry.y - s.geometry.z, s.geometry.x + s.geometry.z,
                         s.geometry.y + s.geometry.z);
    }
    if (s.kind == kernels::SD_BODY_SHAPE_SEGMENT) {
        return glm::vec4(std::min(s.geometry.x, s.geometry.z), std::min(s.geometry.y, s.geometry.w),
                         std::max(s.geometry.x, s.geometry.z), std::max(s.geometry.y, s.geometry.w));
    }
    glm::vec2 lo(s.polygon.vertices[0]), hi(s.polygon.vertices[0]);
    for (std::uint32_t i = 1; i < s.polygon.count; ++i) {
        lo = glm::min(lo, glm::vec2(s.polygon.vertices[i]));
        hi = glm::max(hi, glm::vec2(s.polygon.vertices[i]));
    }
    return glm::vec4(lo, hi);
}

/// Every shape at its body's current pose, with its bounding box (m).
void placeShapes(FluidBodyStep& s) {
    const std::size_t count = s.shapeBody.size();
    s.shapes.resize(count);
    s.shapeBox.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
        s.shapes[k] = place(*s.shapeSource[k], s.bodies[s.shapeBody[k]], s.shapeBody[k]);
        s.shapeBox[k] = boundsOf(s.shapes[k]);
    }
}

/// A coordinate clamped into [0, cells - 1]; NaN goes to 0 (std::clamp
/// passes NaN through, and casting it to int is undefined: a body with
/// infinite bounds overflowed the cell arrays).
int clampCell(float c, int cells) {
    return c >= 0.0f ? static_cast<int>(std::min(c, static_cast<float>(cells - 1))) : 0;
}

glm::ivec2 cellCoords(const Grid<2>& g, glm::vec2 x) {
    const float inv = 0.5f / g.h;  // cells are 2h wide
    const glm::vec2 c = glm::floor((x - g.origin) * inv);
    return {clampCell(c.x, g.cells[0]), clampCell(c.y, g.cells[1])};
}

/// One visit of a contact (see the file comment for who calls it how).
template <bool Dynamic>
void solveContact(BodyContact& c, StepBody& b, Particles<2>& p, const FluidBodyStep& s, float invDt,
                  float radius, float fluidFriction, bool split) {
    Motion<2>& m = p.motion[c.particle];
    const kernels::FluidBodyVisit visit = kernels::fluidSolveBodyContact(
        c, bodyMotion(b), m.velocity, m.pseudo, s.particleInvMass, invDt, radius, fluidFriction, split, Dynamic);
    c.normalImpulse = visit.normalImpulse;
    c.tangentImpulse = visit.tangentImpulse;
    m.velocity = visit.velocity;
    m.pseudo = visit.pseudo;
    if constexpr (Dynamic) {
        if (visit.impulse.x != 0.0f || visit.impulse.y != 0.0f) {
            b.velocity = visit.bodyVelocity;
            b.angularVelocity = visit.bodyAngularVelocity;
            b.linearImpulse -= visit.impulse;
            b.angularImpulse -= visit.angular;
        }
    }
}

}  // namespace

kernels::FluidBodyMotion bodyMotion(const StepBody& b) {
    kernels::FluidBodyMotion m;
    m.centre = b.centre;
    m.velocity = b.velocity;
    m.angularVelocity = b.angularVelocity;
    m.invMass = b.invMass;
    m.invInertia = b.invInertia;
    m.friction = b.friction;
    m.linearImpulse = b.linearImpulse;
    m.angularImpulse = b.angularImpulse;
    m.pad0 = 0.0f;
    return m;
}

glm::ivec4 shapeCells(const FluidBodyStep& s, const Grid<2>& g, std::size_t k) {
    const glm::ivec2 a = cellCoords(g, glm::vec2(s.shapeBox[k].x, s.shapeBox[k].y));
    const glm::ivec2 b = cellCoords(g, glm::vec2(s.shapeBox[k].z, s.shapeBox[k].w));
    return {a, b};
}

std::uint32_t cellOf(const Grid<2>& g, glm::vec2 x) {
    const glm::ivec2 c = cellCoords(g, x);
    return static_cast<std::uint32_t>(c.y * g.cells[0] + c.x);
}

void beginSubstep(FluidBodyStep& s, const FluidState& f, const Grid<2>& g, float dt) {
    placeShapes(s);
    const std::size_t count = s.shapeBody.size();
    for (std::size_t k = 0; k < count; ++k) {
        const StepBody& b = s.bodies[s.shapeBody[k]];
        const glm::vec4 box = s.shapeBox[k];
        // Reach: a particle this far from the shape can touch it within the
        // substep (its speed and the body's, the rotation's at the box's far
        // corner), plus a spacing for what the solve adds.
        const float arm = glm::length(glm::max(glm::abs(glm::vec2(box.x, box.y) - b.centre),
                                               glm::abs(glm::vec2(box.z, box.w) - b.centre)));
        const float speed = s.maxParticleSpeed + glm::length(b.velocity) + std::abs(b.angularVelocity) * arm;
        const float reach = f.radius + f.def.spacing + speed * dt;
        s.shapeBox[k] = box + glm::vec4(-reach, -reach, reach, reach);
    }
    // Counting sort of the shapes into the cells their grown boxes cover.
    const std::size_t cells = static_cast<std::size_t>(g.cells[0]) * static_cast<std::size_t>(g.cells[1]);
    assignInRoom(s.cellStart, cells + 1, 0u);
    auto forCells = [&](std::size_t k, auto&& fn) {
        const glm::ivec4 r = shapeCells(s, g, k);
        for (int y = r.y; y <= r.w; ++y) {
            for (int x = r.x; x <= r.z; ++x) fn(static_cast<std::size_t>(y) * g.cells[0] + x);
        }
    };
    for (std::size_t k = 0; k < count; ++k) forCells(k, [&](std::size_t c) { s.cellStart[c + 1] += 1; });
    for (std::size_t c = 0; c < cells; ++c) s.cellStart[c + 1] += s.cellStart[c];
    s.cellShapes.resize(s.cellStart[cells]);
    std::vector<std::uint32_t>& fill = s.cellFill;
    assignInRoom(fill, s.cellStart.begin(), s.cellStart.end() - 1);
    for (std::size_t k = 0; k < count; ++k) {
        forCells(k, [&](std::size_t c) { s.cellShapes[fill[c]++] = static_cast<std::uint32_t>(k); });
    }
    setUpJointRows(s.joints, s.bodies, dt, s.jointRows);
}

void findBodyContacts(WorkerPool& pool, FluidBodyStep& s, FluidState& f, const Grid<2>& g,
                      float dt) {
    const Particles<2>& p = f.p2;
    const std::size_t chunks = WorkerPool::chunkCount(p.size(), kParticleChunk);
    s.fixedContacts.resize(chunks);
    s.dynamicContacts.resize(chunks);
    s.impacts.resize(std::max(s.impacts.size(), chunks));
    const float radius = f.radius;
    pool.forChunks(p.size(), kParticleChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        std::vector<BodyContact>& fixed = s.fixedContacts[chunk];
        std::vector<BodyContact>& dynamic = s.dynamicContacts[chunk];
        fixed.clear();
        dynamic.clear();
        for (std::size_t i = begin; i < end; ++i) {
            const std::uint32_t cell = g.key[i] >> 2;  // key = cell * 4 + quadrant
            const glm::vec2 x = p.position[i];
            for (std::uint32_t k = s.cellStart[cell]; k < s.cellStart[cell + 1]; ++k) {
                const kernels::FluidBodyShape& shape = s.shapes[s.cellShapes[k]];
                const kernels::FluidSurface surface = kernels::fluidBodyShapeSurface(shape, glm::vec3(x, 0.0f));
                const StepBody& b = s.bodies[shape.body];
                const kernels::FluidBodyFound found =
                    kernels::fluidFindBodyContact(surface, x, p.velocity[i], bodyMotion(b), s.particleInvMass, radius,
                                                  f.def.spacing, dt, kFluidImpactSpeed);
                if (found.found == 0u) continue;
                BodyContact c = found.contact;
                c.particle = static_cast<std::uint32_t>(i);
                c.body = shape.body;
                (b.invMass > 0.0f ? dynamic : fixed).push_back(c);
                // Water touching a dynamic body does not fall asleep: a box
                // floating on sleeping water rocked by 2 to 3 cm/s, reversing
                // its velocity every step (each step it pressed water whose
                // solved velocity stayed under the wake speed and was zeroed;
                // docs/fluid.md).
                if (b.invMass > 0.0f) f.p2.still[i] = 0.0f;
                if (found.impact != 0u) s.impacts[chunk].push_back({p.id[i], b.slot, x, found.approach});
            }
        }
    });
    for (std::size_t c = 0; c < chunks; ++c) s.contactCount += s.fixedContacts[c].size() + s.dynamicContacts[c].size();
}

void solveBodyContacts(WorkerPool& pool, FluidBodyStep& s, FluidState& f, float dt) {
    Particles<2>& p = f.p2;
    const float invDt = 1.0f / dt;
    pool.forChunks(s.fixedContacts.size(), 1, [&](std::size_t chunk, std::size_t, std::size_t) {
        for (BodyContact& c : s.fixedContacts[chunk]) {
            solveContact<false>(c, s.bodies[c.body], p, s, invDt, f.radius, f.def.friction, f.def.splitImpulse);
        }
    });
    for (std::vector<BodyContact>& list : s.dynamicContacts) {
        for (BodyContact& c : list) {
            solveContact<true>(c, s.bodies[c.body], p, s, invDt, f.radius, f.def.friction, f.def.splitImpulse);
        }
    }
    solveJointRows(s.jointRows, s.bodies);
}

void advanceBodies(FluidBodyStep& s, float dt) {
    for (StepBody& b : s.bodies) {
        b.centre += b.velocity * dt;
        b.angle += b.angularVelocity * dt;
    }
    for (std::size_t k = 0; k < s.shapes.size(); ++k) {
        s.shapes[k] = place(*s.shapeSource[k], s.bodies[s.shapeBody[k]], s.shapeBody[k]);
    }
}

namespace {

/// The path from -> to stopped before the edges and segments of still shapes
/// it crosses. The cell lists the shapes within binnedReach of origin; a path
/// that leaves that disc (the solver can throw a particle at a corner far
/// faster than the step began with) may cross any of them, so it tests them
/// all. A polygon thinner than a path is crossed whole, with both ends outside
/// it: a tank of 10 cm static boxes let a block launched at 100 m/s out from
/// its second step. Its edges stop only a path that starts on their outer
/// side (a particle found inside is pushed out by pushOutOfBodies). Each pass
/// stops the path before the crossings it finds; a few passes settle a corner
/// of joined segments (the end moved off one line may sit across the other).
/// Calls fn for each shape the cell lists (those within binnedReach of its
/// particles), or for every shape when `everyShape`.
template <class Fn>
void forShapesNear(const FluidBodyStep& s, std::uint32_t cell, bool everyShape, Fn&& fn) {
    const std::uint32_t first = everyShape ? 0u : s.cellStart[cell];
    const std::uint32_t last = everyShape ? static_cast<std::uint32_t>(s.shapes.size()) : s.cellStart[cell + 1];
    for (std::uint32_t k = first; k < last; ++k) fn(s.shapes[everyShape ? k : s.cellShapes[k]]);
}

glm::vec2 stopBeforeStillEdges(const FluidBodyStep& s, std::uint32_t cell, float binnedReach, glm::vec2 origin,
                               glm::vec2 from, glm::vec2 to, glm::vec2& v) {
    const bool everyShape = glm::distance(origin, from) > binnedReach || glm::distance(origin, to) > binnedReach;
    for (int pass = 0; pass < 3; ++pass) {
        bool crossed = false;
        forShapesNear(s, cell, everyShape, [&](const kernels::FluidBodyShape& shape) {
            if (shape.kind == kernels::SD_BODY_SHAPE_CIRCLE) return;
            // Still shapes only: from is where the particle was against the
            // shape's pose at the start of the substep, and a moving one is
            // at its end pose here (the contacts keep those out).
            const StepBody& b = s.bodies[shape.body];
            if (b.velocity != glm::vec2(0.0f) || b.angularVelocity != 0.0f) return;
            const kernels::FluidPathEnd end = kernels::fluidStopBeforeShapeEdges(shape, from, to, v);
            to = end.x1;
            v = end.v;
            crossed = crossed || end.stopped != 0u;
        });
        if (!crossed) break;
    }
    return to;
}

}  // namespace

glm::vec2 pushOutOfBodies(const FluidBodyStep& s, std::uint32_t cell, float binnedReach, glm::vec2 x0, glm::vec2 x1,
                          glm::vec2& v) {
    // Segments and polygon edges first, against the path.
    x1 = stopBeforeStillEdges(s, cell, binnedReach, x0, x0, x1, v);
    // An end point inside a shape goes out through its nearest surface.
    const glm::vec2 stopped = x1;
    forShapesNear(s, cell, glm::distance(x0, x1) > binnedReach, [&](const kernels::FluidBodyShape& shape) {
        x1 = kernels::fluidPushOutOfShape(shape, x1);
    });
    // That push may not cross a still wall either: a particle wedged
    // between a crate and a tank's wall of edges was pushed out of the crate
    // through the wall (launches into tanks with two crates: 10 of 24 into
    // a tank of edges let particles out, 8 of 24 into boxes). Left inside the
    // crate instead, it is pushed out by the contacts' pseudo velocity once
    // there is room.
    return x1 == stopped ? x1 : stopBeforeStillEdges(s, cell, binnedReach, x0, stopped, x1, v);
}

namespace {

/// Whether moving a particle from x0 to x1 outside the fluid's step would
/// pass through a wall: a still body's edge (of `s`, every shape tested) or
/// a collider.
bool blocked(const FluidBodyStep& s, std::span<const kernels::ColliderParams> colliders, const FluidState& f,
             glm::vec2 x0, glm::vec2 x1) {
    if (x0 == x1) return false;
    glm::vec2 v(0.0f);  // binned reach 0: a path that moves at all tests every shape (no cell lists here)
    return stopBeforeStillEdges(s, 0, 0.0f, x0, x0, x1, v) != x1 ||
           crossesCollider(colliders, f, glm::vec3(x0, 0.0f), glm::vec3(x1, 0.0f));
}

}  // namespace

std::vector<BodyEndPose> placeMovedBodies(const FluidState& f, FluidBodyStep& s) {
    placeShapes(s);
    // Each body's pose at the end of the fluid's step (bodiesAtEnd is by slot).
    std::vector<BodyEndPose> was(s.bodies.size());
    for (std::size_t b = 0; b < s.bodies.size(); ++b) {
        const auto it = std::lower_bound(f.bodiesAtEnd.begin(), f.bodiesAtEnd.end(), s.bodies[b].slot,
                                         [](const BodyEndPose& e, std::uint32_t slot) { return e.slot < slot; });
        was[b] = it != f.bodiesAtEnd.end() && it->slot == s.bodies[b].slot
                     ? *it
                     : BodyEndPose{s.bodies[b].slot, s.bodies[b].centre, s.bodies[b].angle};
    }
    return was;
}

std::uint64_t carryOutOfMovedBodies(WorkerPool& pool, FluidState& f, FluidBodyStep& s,
                                    std::span<const kernels::ColliderParams> colliders) {
    const std::vector<BodyEndPose> was = placeMovedBodies(f, s);
    // Only a dynamic body's shapes hold particles to carry.
    std::vector<std::uint32_t> moving;
    for (std::uint32_t k = 0; k < s.shapes.size(); ++k) {
        if (s.bodies[s.shapes[k].body].invMass > 0.0f) moving.push_back(k);
    }
    if (moving.empty()) return 0;
    Particles<2>& p = f.p2;
    std::vector<std::uint64_t> carried(WorkerPool::chunkCount(p.size(), kParticleChunk), 0);
    pool.forChunks(p.size(), kParticleChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const glm::vec2 x = p.position[i];
            for (std::uint32_t k : moving) {
                const glm::vec4 box = s.shapeBox[k];
                const kernels::FluidBodyShape& shape = s.shapes[k];
                if (x.x < box.x || x.y < box.y || x.x > box.z || x.y > box.w ||
                    kernels::fluidBodyShapeSurface(shape, glm::vec3(x, 0.0f)).distance >= 0.0f) {
                    continue;
                }
                // With the body, from where its copy ended to where Box2D put
                // it; then, if that is still inside, out through the nearest
                // surface. Neither through a wall: a particle wedged between a
                // crate and a wall stays in the crate, and the contacts push
                // it out once there is room (as pushOutOfBodies does).
                const StepBody& now = s.bodies[shape.body];
                const BodyEndPose& then = was[shape.body];
                glm::vec2 to = now.centre + rotate(now.angle - then.angle, x - then.centre);
                if (blocked(s, colliders, f, x, to)) break;
                const glm::vec2 pushed = kernels::fluidPushOutOfShape(shape, to);  // `to` when outside
                if (pushed != to && !blocked(s, colliders, f, to, pushed)) to = pushed;
                carried[chunk] += p.position[i] != to ? 1u : 0u;
                p.position[i] = to;
                break;
            }
        }
    });
    std::uint64_t moved = 0;
    for (std::uint64_t c : carried) moved += c;
    return moved;
}

}  // namespace spindrift::fluid
