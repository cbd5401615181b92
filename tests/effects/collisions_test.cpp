// Collisions: the bounce law, no tunnelling at any speed, and the collision
// options (kill, life loss, per-collider counts).
#include "effects/effects_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace spindrift {
namespace {

using test::OneShot;
using test::ScopedWorld;

// A ball dropped from h onto a plane with resilience e leaves it at e times the
// impact speed, so it rises to e^2 h (energy). Velocity Verlet is exact in free
// fall and the response uses the velocity at the moment of contact, so the only
// error is float rounding and the part of a step spent at the contact point:
// the apex is sampled every dt, missing it by at most g dt^2 / 8 = 3e-6 m at
// dt = 1/600. Tolerance 0.5 % of h.
TEST(Collisions, DroppedBallBouncesToResilienceSquaredTimesHeight) {
    const float h = 2.0f;
    for (float e : {0.3f, 0.5f, 0.8f}) {
        ScopedWorld w;
        createForce(w.id, test::gravity({0.0f, -9.81f, 0.0f}));
        createCollider(w.id, test::groundPlane(e));
        OneShot o;
        o.start = {0.0f, h, 0.0f};
        o.integrator = Integrator::Verlet;
        EmitterId em = createEmitter(w.id, test::oneShotEmitter(o));
        const float dt = 1.0f / 600.0f;
        bool bounced = false;
        float apex = 0.0f;
        for (int i = 0; i < 2000; ++i) {
            StepStats s = stepWorld(w.id, dt);
            ParticleSnapshot p = readParticles(w.id, em);
            ASSERT_EQ(p.count(), 1u);
            bounced = bounced || s.collisions > 0;
            if (bounced) {
                apex = std::max(apex, p.position[0].y);
                if (p.velocity[0].y < 0.0f && apex > 0.0f) {
                    break;  // past the first apex
                }
            }
        }
        ASSERT_TRUE(bounced);
        EXPECT_NEAR(apex, e * e * h, 0.005f * h) << "e = " << e;
    }
}

// Friction mu removes that fraction of the tangential velocity at a hit.
TEST(Collisions, FrictionScalesTangentialVelocityAndResilienceTheNormal) {
    ScopedWorld w;
    createCollider(w.id, test::groundPlane(0.5f, 0.25f));
    OneShot o;
    o.start = {0.0f, 0.05f, 0.0f};
    o.velocity = {4.0f, -10.0f, 0.0f};
    o.integrator = Integrator::ExplicitEuler;  // no forces: velocity constant until the hit
    EmitterId em = createEmitter(w.id, test::oneShotEmitter(o));
    ParticleSnapshot p = test::run(w.id, em, 0.01f, 1);
    ASSERT_EQ(p.count(), 1u);
    EXPECT_FLOAT_EQ(p.velocity[0].x, 4.0f * 0.75f);
    EXPECT_FLOAT_EQ(p.velocity[0].y, 10.0f * 0.5f);
    EXPECT_GE(p.position[0].y, 0.0f);
}

ColliderDef sphereCollider() {
    ColliderDef c;
    c.kind = ColliderKind::Sphere;
    c.position = {0.0f, 0.0f, 0.0f};
    c.radius = 1.0f;
    return c;
}

ColliderDef boxCollider() {
    ColliderDef c;
    c.kind = ColliderKind::Box;
    c.position = {0.0f, 0.0f, 0.0f};
    c.halfExtents = {0.5f, 0.2f, 0.7f};
    c.rotationDegrees = {10.0f, 35.0f, -20.0f};
    return c;
}

ColliderDef terrainCollider() {
    // A ridge: heights rise to 1 m in the middle of a 10 m square.
    ColliderDef c;
    c.kind = ColliderKind::Terrain;
    c.position = {-5.0f, 0.0f, -5.0f};
    c.terrainNx = 33;
    c.terrainNz = 33;
    c.terrainSizeX = 10.0f;
    c.terrainSizeZ = 10.0f;
    for (std::uint32_t z = 0; z < c.terrainNz; ++z) {
        for (std::uint32_t x = 0; x < c.terrainNx; ++x) {
            float u = static_cast<float>(x) / 32.0f;
            c.heights.push_back(std::sin(3.14159f * u));
        }
    }
    return c;
}

ColliderDef cubeMapSphere(float radius) {
    ColliderDef c;
    c.kind = ColliderKind::CubeMap;
    c.position = {0.0f, 0.0f, 0.0f};
    c.cubeResolution = 16;
    c.cubeDepths.assign(6 * 16 * 16, radius);
    return c;
}

// Signed "outside" test, independent of the kernels: which side of each shape
// a point is on, from the shape's definition.
bool outside(const ColliderDef& c, glm::vec3 p) {
    switch (c.kind) {
        case ColliderKind::Plane: return glm::dot(p - c.position, glm::normalize(c.normal)) >= 0.0f;
        case ColliderKind::Sphere: return glm::length(p - c.position) >= c.radius * (1.0f - 1e-5f);
        case ColliderKind::CubeMap: return glm::length(p - c.position) >= c.cubeDepths[0] * (1.0f - 1e-5f);
        case ColliderKind::Terrain: {
            // Outside its square the terrain continues at its edge height (clamp to edge).
            float u = std::clamp((p.x - c.position.x) / c.terrainSizeX, 0.0f, 1.0f);
            return p.y >= std::sin(3.14159f * u) - 2e-3f;  // bilinear vs sine: < 2 mm on this grid
        }
        case ColliderKind::Box: {
            // Back to the box frame with the inverse of R = Rz Ry Rx.
            glm::vec3 r = glm::radians(c.rotationDegrees);
            glm::mat3 rx(1, 0, 0, 0, std::cos(r.x), std::sin(r.x), 0, -std::sin(r.x), std::cos(r.x));
            glm::mat3 ry(std::cos(r.y), 0, -std::sin(r.y), 0, 1, 0, std::sin(r.y), 0, std::cos(r.y));
            glm::mat3 rz(std::cos(r.z), std::sin(r.z), 0, -std::sin(r.z), std::cos(r.z), 0, 0, 0, 1);
            glm::vec3 q = glm::transpose(rz * ry * rx) * (p - c.position);
            glm::vec3 h = c.halfExtents * (1.0f - 1e-5f);
            return std::abs(q.x) >= h.x || std::abs(q.y) >= h.y || std::abs(q.z) >= h.z;
        }
    }
    return false;
}

// A 1000 m/s particle moves 16.7 m per 60 Hz step, far more than any of these
// colliders is thick, yet must end every step outside. 24 particles start on a
// shell of radius 3 m (above the plane and terrain) and are aimed at points
// near the shape's centre, so each crosses the shape within its first step.
TEST(Collisions, ThousandMetresPerSecondNeverPassesAnyCollider) {
    const ColliderDef colliders[] = {test::groundPlane(0.5f), sphereCollider(), boxCollider(), terrainCollider(),
                                     cubeMapSphere(1.0f)};
    for (const ColliderDef& c : colliders) {
        ScopedWorld w;
        createCollider(w.id, c);
        const bool ground = c.kind == ColliderKind::Plane || c.kind == ColliderKind::Terrain;
        std::vector<EmitterId> probes;
        for (int k = 0; k < 24; ++k) {
            float a = 0.7f * static_cast<float>(k), b = 0.37f * static_cast<float>(k);
            glm::vec3 dir(std::cos(a) * std::sin(1.0f + b), std::cos(1.0f + b), std::sin(a) * std::sin(1.0f + b));
            if (ground) {
                dir.y = std::abs(dir.y) + 0.3f;  // from above
            }
            dir = glm::normalize(dir);
            OneShot o;
            o.start = (ground ? glm::vec3(0.0f, 1.5f, 0.0f) : glm::vec3(0.0f)) + dir * 3.0f;
            glm::vec3 aim(0.2f * std::sin(3.0f * a), 0.1f * std::cos(2.0f * b), 0.2f * std::cos(a));
            o.velocity = glm::normalize(aim - o.start) * 1000.0f;
            o.lifetime = 10.0f;
            probes.push_back(createEmitter(w.id, test::oneShotEmitter(o)));
        }
        std::uint64_t hits = 0;
        for (int step = 0; step < 30; ++step) {
            hits += stepWorld(w.id, 1.0f / 60.0f).collisions;
            for (EmitterId e : probes) {
                ParticleSnapshot p = readParticles(w.id, e);
                ASSERT_EQ(p.count(), 1u);
                ASSERT_TRUE(outside(c, p.position[0]))
                    << "collider kind " << static_cast<int>(c.kind) << " probe " << e.index << " step " << step
                    << " at " << p.position[0].x << ", " << p.position[0].y << ", " << p.position[0].z;
            }
        }
        // Every probe was aimed through the shape: each hit it at least once.
        EXPECT_GE(hits, probes.size()) << "collider kind " << static_cast<int>(c.kind);
    }
}

TEST(Collisions, KillOnCollisionAndLifeLossAndPerColliderCounts) {
    ScopedWorld w;
    ColliderDef floor = test::groundPlane(0.5f);
    ColliderDef wall;
    wall.kind = ColliderKind::Plane;
    wall.position = {10.0f, 0.0f, 0.0f};
    wall.normal = {-1.0f, 0.0f, 0.0f};
    ColliderId floorId = createCollider(w.id, floor);
    createCollider(w.id, wall);
    OneShot o;
    o.start = {0.0f, 1.0f, 0.0f};
    o.velocity = {0.0f, -100.0f, 0.0f};
    o.count = 5;
    EmitterDef killer = test::oneShotEmitter(o);
    killer.collision.killOnCollision = true;
    EmitterId k = createEmitter(w.id, killer);
    EmitterDef aging = test::oneShotEmitter(o);
    aging.lifetime = {10.0f, 10.0f};
    aging.collision.lifeLossOnCollision = 0.5f;
    aging.collision.colliders = {floorId};
    EmitterId a = createEmitter(w.id, aging);
    StepStats s = stepWorld(w.id, 0.1f);
    EXPECT_EQ(s.colliderHits.size(), 2u);
    EXPECT_EQ(s.colliderHits[0].hits, 10u);  // both emitters hit the floor
    EXPECT_EQ(s.colliderHits[1].hits, 0u);
    EXPECT_EQ(s.died, 5u);
    EXPECT_EQ(readParticles(w.id, k).count(), 0u);
    ParticleSnapshot p = readParticles(w.id, a);
    ASSERT_EQ(p.count(), 5u);
    // Age 0.1 s at the hit, half the remaining 9.9 s lost: 0.1 + 4.95.
    EXPECT_NEAR(p.age[0], 0.1f + 0.5f * 9.9f, 1e-4f);
}

}  // namespace
}  // namespace spindrift

namespace spindrift {
namespace {

// A particle resting on the ground is pushed out every step (gravity moves it
// g dt^2 into the plane), but approaches at only g dt = 0.16 m/s per step,
// below the rest speed: no hits are counted after it settles, and life loss on
// collision does not drain a resting particle.
TEST(Collisions, RestingContactIsNotAnImpact) {
    test::ScopedWorld w;
    createForce(w.id, test::gravity({0.0f, -9.81f, 0.0f}));
    ColliderDef floor = test::groundPlane(0.0f);
    floor.restSpeed = 0.5f;
    createCollider(w.id, floor);
    test::OneShot o;
    o.start = {0.0f, 0.5f, 0.0f};
    o.lifetime = 100.0f;
    EmitterDef e = test::oneShotEmitter(o);
    e.collision.lifeLossOnCollision = 0.5f;
    EmitterId id = createEmitter(w.id, e);
    std::uint64_t hits = 0;
    for (int i = 0; i < 120; ++i) {
        hits += stepWorld(w.id, 1.0f / 60.0f).collisions;
    }
    EXPECT_EQ(hits, 1u);  // the landing at 3.1 m/s, then rest
    std::uint64_t restingHits = 0;
    for (int i = 0; i < 120; ++i) {
        restingHits += stepWorld(w.id, 1.0f / 60.0f).collisions;
    }
    EXPECT_EQ(restingHits, 0u);
    ParticleSnapshot p = readParticles(w.id, id);
    ASSERT_EQ(p.count(), 1u);
    EXPECT_NEAR(p.position[0].y, 0.0f, 1e-3f);  // on the ground
    // One impact at age ~0.32 s took half of the remaining ~99.7 s; nothing since.
    EXPECT_NEAR(p.age[0], 4.0f + 0.5f * 99.68f, 0.05f);
}

}  // namespace
}  // namespace spindrift
