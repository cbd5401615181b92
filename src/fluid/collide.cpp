// Collisions of fluid particles with static colliders (slide 51): velocity
// constraints solved after the fluid's, the particle a small rotationless body
// of radius spacing / 2; then position integration, which puts back any
// particle whose path still crossed a collider, so none ever passes through.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "core/room.h"
#include "fluid/body_contacts.h"
#include "fluid/body_link.h"
#include "fluid/fluid_state.h"
#include "particles/cpu_kernels.h"

namespace spindrift::fluid {

bool isFluidCollider(const kernels::ColliderParams& c) {
    return c.kind == kernels::SD_COLLIDER_PLANE || c.kind == kernels::SD_COLLIDER_SPHERE ||
           c.kind == kernels::SD_COLLIDER_BOX;
}

namespace {

/// Fraction of an overlap removed per step (fluid.glsl).
constexpr float kOverlapPush = kernels::SD_FLUID_OVERLAP_PUSH;
/// Distance (m) a put-back particle keeps from the surface (fluid.glsl).
constexpr float kSkin = kernels::SD_FLUID_SKIN;


template <int D>
glm::vec3 to3(Vec<D> v) {
    if constexpr (D == 2) return glm::vec3(v.x, v.y, 0.0f); else return v;
}

template <int D>
Vec<D> from3(glm::vec3 v) {
    if constexpr (D == 2) return Vec<D>(v.x, v.y); else return v;
}

/// Where the path x0 -> x1 first meets collider c, if it does.
kernels::Hit pathHit(const kernels::ColliderParams& c, glm::vec3 x0, glm::vec3 x1) {
    return kernels::intersectCollider(kernels::KernelContext{}, c, x0, x1);  // a fluid collider: no map read
}

/// In 2D a surface's normal is projected into the plane (fluid.glsl).
template <int D>
kernels::FluidSurface flatten(kernels::FluidSurface s) {
    if constexpr (D == 2) {
        return kernels::fluidFlatSurface(s);
    }
    return s;
}

/// Particles culled against the colliders together (collidersNear): 32
/// consecutive ones in grid order, about one grid cell, so their box is
/// small and most planes of a tank are far from all of it.
constexpr std::size_t kCullBlock = 32;

/// The box around some particles' positions (m; z = 0 in 2D). A NaN
/// coordinate is passed over: such a particle meets no plane either way.
struct Bounds {
    glm::vec3 lo{3.0e38f};
    glm::vec3 hi{-3.0e38f};
    void add(glm::vec3 x) {
        lo = glm::min(lo, x);
        hi = glm::max(hi, x);
    }
};

/// A lower bound (m) of plane c's signed distance (planeDistance,
/// fluidColliderSurface) at every point of box b, with a margin far above
/// the float rounding of either (a few units in the last place of the
/// coordinates), so a plane it clears is one every particle's own test
/// clears too.
float planeDistanceBelow(const kernels::ColliderParams& c, const Bounds& b) {
    const glm::vec3 n(c.normal);
    const glm::vec3 offset = 0.5f * (b.lo + b.hi) - glm::vec3(c.position);
    const glm::vec3 half = 0.5f * (b.hi - b.lo);
    const float scale = glm::dot(glm::abs(offset) + half + glm::abs(glm::vec3(c.position)), glm::abs(n));
    return glm::dot(offset, n) - glm::dot(half, glm::abs(n)) - 1.0e-5f * (scale + 1.0f);
}

/// The fluid colliders that may matter to particles inside box b, in the
/// world's order (so contacts come out in the same order as from a test of
/// every collider): all but the planes at least `clear` (m) from every
/// point of b. Most particles of a tank are far from most of its walls:
/// tested per particle and plane, the contacts' pass was 5.7 % of a 10k
/// dam-break step and the positions' pass 7.7 %; per block, 4.0 % and 6.8 %
/// (docs/fluid.md, "The cost of a substep").
void collidersNear(std::span<const kernels::ColliderParams> colliders, const Bounds& b, float clear,
                   std::vector<const kernels::ColliderParams*>& out) {
    out.clear();
    for (const kernels::ColliderParams& c : colliders) {
        if (!isFluidCollider(c)) continue;
        if (c.kind == kernels::SD_COLLIDER_PLANE && planeDistanceBelow(c, b) >= clear) continue;
        out.push_back(&c);
    }
}

/// Calls fn(surface) for the surface at x of every collider of `near`
/// (collidersNear) and every polygon, but a plane's only where x is within
/// `reach` of it or its ghosts reach x (the wall table): farther, the
/// plane gives x neither a contact nor density, and its distance alone,
/// the same float as the surface's, says so without the flattened normal's
/// square root and divisions.
template <int D, class Fn>
void forEachSurface(std::span<const kernels::ColliderParams* const> near, const FluidState& f, glm::vec3 x, float reach,
                    Fn&& fn) {
    for (const kernels::ColliderParams* c : near) {
        const kernels::FluidSurface s = kernels::fluidColliderSurface(*c, x);
        if (c->kind == kernels::SD_COLLIDER_PLANE && !(s.distance < reach) && !wallReaches(f.wallTable, s.distance)) {
            continue;
        }
        fn(flatten<D>(s));
    }
    for (const kernels::FluidPolygon& poly : f.polygons) {
        fn(kernels::fluidPolygonSurface(poly, x));
    }
}

/// How far (m) from a particle moving at `speed` (m/s) a surface gives it a
/// contact this step: a surface it could reach, with a spacing to spare for
/// what the fluid adds while solving (speculative contacts).
float contactReach(const FluidState& f, float speed, float dt) { return f.radius + speed * dt + f.def.spacing; }

/// The largest length of some vectors from the largest squared length:
/// glm::length is the square root of the dot product, and the root is
/// monotone and correctly rounded, so this is the largest length exactly,
/// for one root instead of one per vector (as integratePositions' largest
/// speed). A NaN square is passed over, as std::max passes it.
template <int D>
struct LongestOf {
    float squared = 0.0f;
    void add(Vec<D> v) { squared = std::max(squared, glm::dot(v, v)); }
    float length() const { return std::sqrt(squared); }
};

/// collidersNear for the contacts of particles [begin, end)
/// (findContacts): the planes farther from the box of their positions than
/// the longest of their reaches and than the wall table reaches, which
/// give none of them a contact or density (forEachSurface's own test, for
/// all of them at once).
template <int D>
void contactCollidersNear(const Particles<D>& p, std::span<const kernels::ColliderParams> colliders,
                          const FluidState& f, float dt, std::size_t begin, std::size_t end,
                          std::vector<const kernels::ColliderParams*>& near) {
    Bounds box;
    LongestOf<D> fastest;
    for (std::size_t i = begin; i < end; ++i) {
        box.add(to3<D>(p.position[i]));
        fastest.add(p.velocity[i]);
    }
    // contactReach grows with the speed: the fastest's is the farthest.
    collidersNear(colliders, box, std::max(contactReach(f, fastest.length(), dt), wallBeyond(f.wallTable)), near);
}

/// collidersNear for the paths of particles [begin, end) this substep
/// (integratePositions): the planes that none of them can end behind,
/// those farther from the box of their starts than the longest path (a
/// NaN path is passed over: it is removed before the tests). A body's push
/// moves an end point by more than its path, so with bodies near
/// (`bodiesNear`) every plane is tested.
template <int D>
void pathCollidersNear(const Particles<D>& p, std::span<const kernels::ColliderParams> colliders, bool split, float dt,
                       bool bodiesNear, std::size_t begin, std::size_t end,
                       std::vector<const kernels::ColliderParams*>& near) {
    Bounds box;
    LongestOf<D> fastest;
    for (std::size_t i = begin; i < end; ++i) {
        box.add(to3<D>(p.position[i]));
        fastest.add(split ? p.velocity[i] + p.motion[i].pseudo : p.velocity[i]);
    }
    const float longest = fastest.length() * dt;
    box.lo -= glm::vec3(longest);
    box.hi += glm::vec3(longest);
    collidersNear(colliders, box, bodiesNear ? std::numeric_limits<float>::infinity() : 0.0f, near);
}

}  // namespace

template <int D>
void findContacts(WorkerPool& pool, FluidState& f, const StepContext& world, float dt) {
    Particles<D>& p = f.particles<D>();
    Constraints& c = f.constraints;
    f.contacts.resize(WorkerPool::chunkCount(p.size(), kParticleChunk));
    for (auto& list : f.contacts) list.clear();
    assignInRoom(c.wallDensity, p.size(), 0.0f);
    assignInRoom(c.wallGradient, p.size(), glm::vec3(0.0f));
    if (world.colliders.empty() && f.polygons.empty()) return;
    pool.forChunks(p.size(), kParticleChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        // The arrays as locals (as in integratePositions).
        std::vector<Contact>& out = f.contacts[chunk];
        const Vec<D>* position = p.position.data();
        const Vec<D>* velocity = p.velocity.data();
        float* wallDensity = c.wallDensity.data();
        glm::vec3* wallGradient = c.wallGradient.data();
        const float step = dt;
        std::vector<const kernels::ColliderParams*> near;
        near.reserve(world.colliders.size());
        for (std::size_t i = begin; i < end; ++i) {
            if ((i - begin) % kCullBlock == 0) {
                contactCollidersNear<D>(p, world.colliders, f, dt, i, std::min(end, i + kCullBlock), near);
            }
            const glm::vec3 x = to3<D>(position[i]);
            const float reach = contactReach(f, glm::length(velocity[i]), step);
            forEachSurface<D>(near, f, x, reach, [&](const kernels::FluidSurface& s) {
                if (s.distance < reach) out.push_back(Contact{s, static_cast<std::uint32_t>(i)});
                // The wall's ghost neighbours (wall_density.cpp): their
                // direction from the particle is into the wall, -normal.
                const WallTerm t = wallTerm(f.wallTable, s.distance);
                wallDensity[i] += t.density;
                wallGradient[i] -= s.normal * t.push;
            });
        }
    });
}

template <int D>
void solveContacts(WorkerPool& pool, FluidState& f, float dt) {
    Particles<D>& p = f.particles<D>();
    const float invDt = 1.0f / dt;
    const float radius = f.radius;
    const float mu = f.def.friction;
    const bool split = f.def.splitImpulse;
    pool.forChunks(f.contacts.size(), 1, [&](std::size_t chunk, std::size_t, std::size_t) {
        for (const Contact& c : f.contacts[chunk]) {
            Motion<D>& m = p.motion[c.particle];
            const glm::vec3 v = to3<D>(m.velocity);
            if (!split) {
                m.velocity = from3<D>(kernels::fluidContactVelocity(v, c.surface, radius, invDt, kOverlapPush, mu));
                continue;
            }
            // Split impulses: the real velocity only stops at the surface (no
            // push out of an overlap, which would be kinetic energy); the
            // particle's motion this step, real plus pseudo, also may not
            // enter the wall, and the pseudo part pushes an overlap out.
            const glm::vec3 real = kernels::fluidContactVelocity(v, c.surface, radius, invDt, 0.0f, mu);
            m.velocity = from3<D>(real);
            const glm::vec3 total = real + to3<D>(m.pseudo);
            const glm::vec3 moved = kernels::fluidContactVelocity(total, c.surface, radius, invDt, kOverlapPush, 0.0f);
            m.pseudo += from3<D>(moved - total);
        }
    });
    if constexpr (D == 2) {
        if (f.bodies != nullptr) solveBodyContacts(pool, *f.bodies, f, dt);
    }
}

template <int D>
void integratePositions(WorkerPool& pool, FluidState& f, const StepContext& world, float dt, FluidStepStats& stats) {
    Particles<D>& p = f.particles<D>();
    std::vector<float> maxSpeed(WorkerPool::chunkCount(p.size(), kParticleChunk), 0.0f);
    // Extent along gravity of the particles under pressure: the depth of
    // the columns the solver holds up (fluid_step.cpp's substeps).
    const float gravity = glm::length(f.def.gravity);
    const Vec<D> down = gravity > 0.0f ? Vec<D>(f.def.gravity / gravity) : Vec<D>(0.0f);
    std::vector<glm::vec2> pressed(maxSpeed.size(), glm::vec2(3.0e38f, -3.0e38f));
    const bool sleeps = f.def.sleepSpeed > 0.0f;
    const float wakeSpeed = kernels::SD_FLUID_WAKE_FACTOR * f.def.sleepSpeed;
    const float sleepTime = f.def.sleepTime;
    // The sleep circle's radius (m), at most half a spacing (fluid.glsl).
    const float drift = kernels::fluidSleepDrift(f.def.sleepSpeed, f.def.sleepTime, f.def.spacing);
    // Every body shape within this distance (m) of a particle is in its grid
    // cell's list (beginSubstep grows each shape's box by at least it).
    const float binnedReach = f.radius + f.def.spacing;
    // Particles whose numbers became NaN or infinite in this substep, or
    // whose squared speed did (a blow-up under extreme but legal values): marked with a NaN position
    // and removed below, before the next substep bins them or a cache
    // stores them (issue 14).
    std::vector<std::uint32_t> nonFinite(maxSpeed.size(), 0);
    const auto removeLater = [&](std::size_t chunk, std::size_t i) {
        p.position[i] = Vec<D>(std::numeric_limits<float>::quiet_NaN());
        nonFinite[chunk] += 1;
    };
    const bool split = f.def.splitImpulse;
    const FluidBodyStep* bodies = f.bodies;
    pool.forChunks(p.size(), kParticleChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        // The arrays and settings as locals: read through the captured
        // references, g++ reloaded them after every store of the loop
        // (as in neighbours.cpp's setup).
        Vec<D>* position = p.position.data();
        Vec<D>* velocity = p.velocity.data();
        Vec<D>* anchor = p.anchor.data();
        float* still = p.still.data();
        const float* pressure = p.pressure.data();
        const Motion<D>* moved = p.motion.data();
        const bool sleeping = sleeps;
        const bool splitting = split;
        const float step = dt;
        const float sleepAfter = sleepTime;
        const float wake = wakeSpeed;
        const float circle = drift;
        const Vec<D> downward = down;
        const std::span<const kernels::ColliderParams> colliders = world.colliders;
        const std::span<const kernels::FluidPolygon> polygons = f.polygons;
        // The largest squared speed: its root is the largest speed, exactly
        // (the square root is monotone and correctly rounded), for one root
        // a chunk instead of one a particle.
        float fastestSquared = 0.0f;
        glm::vec2 range(3.0e38f, -3.0e38f);
        std::vector<const kernels::ColliderParams*> near;
        near.reserve(colliders.size());
        for (std::size_t i = begin; i < end; ++i) {
            if ((i - begin) % kCullBlock == 0) {
                pathCollidersNear<D>(p, colliders, split, step, bodies != nullptr, i, std::min(end, i + kCullBlock),
                                     near);
            }
            if (pressure[i] > 0.0f) {
                const float along = glm::dot(position[i], downward);
                range = glm::vec2(std::min(range.x, along), std::max(range.y, along));
            }
            const glm::vec3 x0 = to3<D>(position[i]);
            glm::vec3 v = to3<D>(velocity[i]);
            // Sleeping (fluid.glsl, fluidSleepStep): displacement, not
            // speed, decides.
            if (sleeping) {
                const kernels::FluidSleep sleep =
                    kernels::fluidSleepStep(x0, v, to3<D>(anchor[i]), still[i], step, sleepAfter, wake, circle);
                still[i] = sleep.still;
                anchor[i] = from3<D>(sleep.anchor);
                if (sleep.asleep) {
                    velocity[i] = Vec<D>(0.0f);
                    continue;
                }
            }
            const glm::vec3 motion = splitting ? v + to3<D>(moved[i].pseudo) : v;
            glm::vec3 x1 = x0 + motion * step;
            if (!kernels::fluidFinite(x1) || !kernels::fluidFiniteSpeed(v)) {
                removeLater(chunk, i);
                continue;
            }
            if constexpr (D == 2) {
                // Rigid bodies (already at their end-of-substep poses): an end
                // point inside goes out through the nearest surface, a path
                // across a still edge stops before it, as at a collider, with
                // no velocity left into it. A moving body's push is position
                // only, so momentum stays with the contact impulses. Before
                // the colliders' tests, which then also stop a push out of a
                // crate that would cross them (world colliders do not stop
                // bodies).
                if (bodies != nullptr) {
                    glm::vec2 v2(v);
                    const glm::vec2 x =
                        pushOutOfBodies(*bodies, f.g2.key[i] >> 2, binnedReach, glm::vec2(x0), glm::vec2(x1), v2);
                    x1 = glm::vec3(x, 0.0f);
                    v = glm::vec3(v2, 0.0f);
                }
            }
            // Path tests (as the effects' collisions): a path that crosses a
            // plane, sphere or box ends at the contact, moving no further in.
            for (const kernels::ColliderParams* near_c : near) {
                const kernels::ColliderParams& c = *near_c;
                // Most paths end well inside a closed box's walls: the plane's
                // test of the end point alone clears them.
                if (c.kind == kernels::SD_COLLIDER_PLANE && kernels::planeKeepsClear(kernels::planeDistance(c, x1)))
                    continue;
                const kernels::Hit hit = pathHit(c, x0, x1);
                if (hit.hit != 0u) {
                    const glm::vec3 n = flatten<D>(kernels::makeSurface(0.0f, hit.normal)).normal;
                    x1 = hit.point + n * kSkin;
                    v = kernels::fluidWithoutInward(v, n);
                }
            }
            // Polygons: an end point inside goes out through the nearest edge.
            for (const kernels::FluidPolygon& poly : polygons) {
                const kernels::FluidSurface s = kernels::fluidPolygonSurface(poly, x1);
                if (s.distance < 0.0f) {
                    x1 += s.normal * (kSkin - s.distance);
                    v = kernels::fluidWithoutInward(v, s.normal);
                }
            }
            if (!kernels::fluidFinite(x1) || !kernels::fluidFiniteSpeed(v)) {
                removeLater(chunk, i);
                continue;
            }
            position[i] = from3<D>(x1);
            velocity[i] = from3<D>(v);
            const Vec<D> moving = from3<D>(v);
            fastestSquared = std::max(fastestSquared, glm::dot(moving, moving));
        }
        maxSpeed[chunk] = std::sqrt(fastestSquared);
        pressed[chunk] = range;
    });
    float fastest = 0.0f;
    for (float s : maxSpeed) fastest = std::max(fastest, s);
    stats.maxSpeed = fastest;
    glm::vec2 range(3.0e38f, -3.0e38f);
    for (glm::vec2 r : pressed) range = glm::vec2(std::min(range.x, r.x), std::max(range.y, r.y));
    f.pressedDepth = range.y > range.x ? range.y - range.x : 0.0f;
    std::uint64_t removed = 0;
    for (std::uint32_t n : nonFinite) removed += n;
    if (removed > 0) {
        p.keepIf([&](std::size_t i) { return kernels::fluidFinite(to3<D>(p.position[i])); });
        stats.nonFinite += removed;
    }
}

bool crossesCollider(std::span<const kernels::ColliderParams> colliders, const FluidState& f, glm::vec3 x0,
                     glm::vec3 x1) {
    for (const kernels::ColliderParams& c : colliders) {
        if (isFluidCollider(c) && pathHit(c, x0, x1).hit != 0u) return true;
    }
    for (const kernels::FluidPolygon& poly : f.polygons) {
        if (kernels::fluidPolygonSurface(poly, x1).distance < 0.0f) return true;
    }
    return false;
}

template void findContacts<2>(WorkerPool&, FluidState&, const StepContext&, float);
template void findContacts<3>(WorkerPool&, FluidState&, const StepContext&, float);
template void solveContacts<2>(WorkerPool&, FluidState&, float);
template void solveContacts<3>(WorkerPool&, FluidState&, float);
template void integratePositions<2>(WorkerPool&, FluidState&, const StepContext&, float, FluidStepStats&);
template void integratePositions<3>(WorkerPool&, FluidState&, const StepContext&, float, FluidStepStats&);

}  // namespace spindrift::fluid
