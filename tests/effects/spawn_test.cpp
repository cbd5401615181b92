// Spawn shapes and launch directions: every particle born where its shape says,
// with statistics matching the uniform distributions.
#include "effects/effects_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

ParticleSnapshot bornFrom(const SpawnShapeDef& shape, std::uint32_t count = 4000) {
    test::ScopedWorld w;
    EmitterDef e;
    e.capacity = count;
    e.rate = 0.0f;
    e.bursts = {{0.0f, count}};
    e.shape = shape;
    e.speed = {1.0f, 1.0f};
    e.lifetime = {100.0f, 100.0f};
    EmitterId id = createEmitter(w.id, e);
    // A step of 1 ns: positions are the birth positions to ~1e-9 m.
    stepWorld(w.id, 1e-9f);
    return readParticles(w.id, id);
}

// Uniform in a ball of radius R: E[r] = 3R/4; on the sphere: r = R exactly.
// 4000 samples: the standard error of the mean radius is ~0.15 R / sqrt(4000)
// = 0.0024 R; tolerance 0.01 R.
TEST(Spawn, SphereVolumeAndSurface) {
    SpawnShapeDef s;
    s.kind = SpawnShapeKind::Sphere;
    s.center = {1.0f, 2.0f, 3.0f};
    s.radius = 2.0f;
    ParticleSnapshot volume = bornFrom(s);
    double mean = 0.0;
    for (glm::vec3 p : volume.position) {
        float r = glm::length(p - s.center);
        EXPECT_LE(r, 2.0f + 1e-5f);
        mean += r;
    }
    EXPECT_NEAR(mean / volume.count(), 1.5, 0.02);
    s.surface = true;
    for (glm::vec3 p : bornFrom(s).position) {
        EXPECT_NEAR(glm::length(p - s.center), 2.0f, 1e-5f);
    }
}

TEST(Spawn, BoxVolumeAndSurface) {
    SpawnShapeDef s;
    s.kind = SpawnShapeKind::Box;
    s.halfExtents = {1.0f, 2.0f, 0.5f};
    for (bool surface : {false, true}) {
        s.surface = surface;
        for (glm::vec3 p : bornFrom(s).position) {
            glm::vec3 q = glm::abs(p) - s.halfExtents;
            EXPECT_LE(std::max({q.x, q.y, q.z}), 1e-5f);
            if (surface) {
                EXPECT_NEAR(std::max({q.x, q.y, q.z}), 0.0f, 1e-5f);  // on a face
            }
        }
    }
}

// Disk: in the plane through the centre normal to the direction; uniform in
// area, so E[r] = 2R/3.
TEST(Spawn, DiskIsFlatAndUniform) {
    SpawnShapeDef s;
    s.kind = SpawnShapeKind::Disk;
    s.radius = 3.0f;
    s.direction = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    double mean = 0.0;
    ParticleSnapshot p = bornFrom(s);
    for (glm::vec3 x : p.position) {
        EXPECT_NEAR(glm::dot(x, s.direction), 0.0f, 1e-5f);
        mean += glm::length(x);
    }
    EXPECT_NEAR(mean / p.count(), 2.0, 0.03);
}

// Spread: every launch direction within the half-angle of the axis, and the
// cap is covered uniformly (mean cos theta = (1 + cos a) / 2).
TEST(Spawn, DirectionsFillTheSpreadCone) {
    SpawnShapeDef s;
    s.kind = SpawnShapeKind::Point;
    s.direction = {0.0f, 0.0f, 1.0f};
    s.spreadAngle = 0.5f;
    ParticleSnapshot p = bornFrom(s);
    double meanCos = 0.0;
    for (glm::vec3 v : p.velocity) {
        float c = glm::dot(glm::normalize(v), s.direction);
        EXPECT_GE(c, std::cos(0.5f) - 1e-5f);
        meanCos += c;
    }
    EXPECT_NEAR(meanCos / p.count(), (1.0 + std::cos(0.5)) / 2.0, 0.002);
}

// Cone: born on the base disk, flying out at an angle that grows with the
// distance from the axis up to the spread at the rim.
TEST(Spawn, ConeDiverges) {
    SpawnShapeDef s;
    s.kind = SpawnShapeKind::Cone;
    s.radius = 1.0f;
    s.spreadAngle = 0.6f;
    ParticleSnapshot p = bornFrom(s);
    for (std::size_t i = 0; i < p.count(); ++i) {
        float r = glm::length(glm::vec2(p.position[i].x, p.position[i].z));
        float angle = std::acos(std::clamp(glm::normalize(p.velocity[i]).y, -1.0f, 1.0f));
        EXPECT_NEAR(angle, 0.6f * r, 1e-3f);
        if (r > 1e-3f) {
            // Outward: the horizontal velocity points away from the axis.
            EXPECT_GT(p.position[i].x * p.velocity[i].x + p.position[i].z * p.velocity[i].z, 0.0f);
        }
    }
}

}  // namespace
}  // namespace spindrift
