// The animated curl-noise force (src/kernels/noise.glsl): divergence-free at
// every instant, animated at speed > 0 and static at speed 0, rms speed equal
// to `strength`, continuous across noise slices; and a world that uses it.
#include "effects/effects_test_util.h"
#include "particles/cpu_kernels.h"
#include "particles/params.h"

#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace spindrift {
namespace {

kernels::ForceParams noise(float strength, float frequency, float speed, std::uint32_t octaves, std::uint32_t seed) {
    ForceDef d;
    d.kind = ForceKind::CurlNoise;
    d.strength = strength;
    d.frequency = frequency;
    d.speed = speed;
    d.octaves = octaves;
    d.seed = seed;
    return makeForceParams(d, nullptr, 0);
}

glm::vec3 velocity(const kernels::ForceParams& f, glm::vec3 p, float t) {
    return kernels::curlNoiseVelocity(f, p, t);
}

std::vector<glm::vec3> randomPoints(std::size_t n, float half, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-half, half);
    std::vector<glm::vec3> points(n);
    for (glm::vec3& p : points) {
        p = glm::vec3(u(rng), u(rng), u(rng));
    }
    return points;
}

// Central differences of v at p with step h (m), in double from the float
// velocities: row i is d v / d x_i.
glm::dmat3 jacobian(const kernels::ForceParams& f, glm::vec3 p, float t, float h) {
    glm::dmat3 j(0.0);
    for (int i = 0; i < 3; ++i) {
        glm::vec3 e(0.0f);
        e[i] = h;
        // The step actually taken after rounding p +- e to float.
        const double step = static_cast<double>((p + e)[i]) - static_cast<double>((p - e)[i]);
        const glm::dvec3 d = (glm::dvec3(velocity(f, p + e, t)) - glm::dvec3(velocity(f, p - e, t))) / step;
        j[i] = d;
    }
    return j;
}

// div v = 0 to the differences' error, measured as |div v| / |grad v| (the
// Jacobian's Frobenius norm) at each point. With frequency 1 (1 m cells) the
// central difference's truncation error grows as h^2 and the float rounding of
// v (and of p +- h) divided by 2h as 1/h; h = 3e-3 m balances them: seen
// 4.6e-4 at worst over these 1200 points (1.8e-3 at h = 1e-3, 2.9e-3 at
// h = 1e-2). Bound 5e-3, 10x that; a field that is not a curl has a ratio of
// order 1 (next test).
TEST(CurlNoise, DivergenceFreeAtEveryInstant) {
    const kernels::ForceParams f = noise(1.5f, 1.0f, 0.8f, 2, 9);
    const float h = 3e-3f;
    double worst = 0.0;
    double gradientSum = 0.0;
    int n = 0;
    // Times at a slice (phase 0, w = 0), a quarter and half way between.
    for (float t : {0.0f, 0.3125f, 0.625f, 3.1f}) {
        for (glm::vec3 p : randomPoints(300, 20.0f, 4u)) {
            const glm::dmat3 j = jacobian(f, p, t, h);
            const double divergence = j[0][0] + j[1][1] + j[2][2];
            double frobenius = 0.0;
            for (int a = 0; a < 3; ++a) {
                for (int b = 0; b < 3; ++b) {
                    frobenius += j[a][b] * j[a][b];
                }
            }
            gradientSum += std::sqrt(frobenius);
            worst = std::max(worst, std::abs(divergence) / std::sqrt(frobenius));
            ++n;
        }
    }
    std::printf("curl noise: |div v| / |grad v| at most %.2e over %d points; mean |grad v| %.2f 1/s\n", worst, n,
                gradientSum / n);
    EXPECT_LT(worst, 5e-3);
    EXPECT_GT(gradientSum / n, 1.0);  // not vacuous: |grad v| ~ 8 strength frequency (12 1/s seen)
}

// The same measure on a field that is not divergence-free shows the test above
// can fail: v' = (v_y, v_z, v_x), the same velocities with the components
// permuted, is generally not solenoidal.
TEST(CurlNoise, DivergenceMeasureSeesANonSolenoidalField) {
    const kernels::ForceParams f = noise(1.5f, 1.0f, 0.8f, 2, 9);
    const float h = 3e-3f;
    double sum = 0.0;
    int n = 0;
    for (glm::vec3 p : randomPoints(200, 20.0f, 5u)) {
        const glm::dmat3 j = jacobian(f, p, 0.3f, h);
        // d v_y / dx + d v_z / dy + d v_x / dz: the divergence of (v_y, v_z, v_x).
        const double divergence = j[0][1] + j[1][2] + j[2][0];
        double frobenius = 0.0;
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                frobenius += j[a][b] * j[a][b];
            }
        }
        sum += std::abs(divergence) / std::sqrt(frobenius);
        ++n;
    }
    EXPECT_GT(sum / n, 0.1);
}

// rms |v| = strength: the kernel scales the curl by the root of its expected
// square, 2 octaves E|grad n|^2 ((1 - w)^2 + w^2). Estimated from 20000 points
// spread over 200 noise cells per axis (practically independent samples):
// for a roughly Gaussian 3-vector, Var |v|^2 / (E |v|^2)^2 ~ 2/3, so the
// mean square's relative standard error is ~0.8 / sqrt(20000) = 0.6 % and the
// rms's 0.3 %. Bound 3 % (10 standard errors; the gradients' hash is not
// perfectly independent and 2^32 is not a multiple of 12).
TEST(CurlNoise, RmsSpeedIsTheStrength) {
    const std::vector<glm::vec3> points = randomPoints(20000, 100.0f, 6u);
    for (std::uint32_t octaves : {1u, 3u}) {
        const kernels::ForceParams f = noise(2.0f, 1.0f, 1.0f, octaves, 17);
        // Phase fractions 0 (one slice) and 0.5 (an equal blend of two).
        for (float t : {4.0f, 4.5f}) {
            double sumSquares = 0.0;
            for (glm::vec3 p : points) {
                const glm::vec3 v = velocity(f, p, t);
                sumSquares += static_cast<double>(glm::dot(v, v));
            }
            const double rms = std::sqrt(sumSquares / static_cast<double>(points.size()));
            std::printf("curl noise: octaves %u, t %.1f s: rms speed %.4f m/s (strength 2)\n", octaves, t, rms);
            EXPECT_NEAR(rms, 2.0, 0.06) << "octaves " << octaves << " t " << t;
        }
    }
}

TEST(CurlNoise, FrequencyScalesTheFieldInSpace) {
    // v at frequency 2 and point p is v at frequency 1 and 2 p: the strength
    // does not depend on the frequency (the curl is normalised).
    const kernels::ForceParams f1 = noise(1.0f, 1.0f, 0.0f, 1, 2);
    const kernels::ForceParams f2 = noise(1.0f, 2.0f, 0.0f, 1, 2);
    for (glm::vec3 p : randomPoints(50, 10.0f, 7u)) {
        const glm::vec3 a = velocity(f2, p, 0.0f);
        const glm::vec3 b = velocity(f1, p * 2.0f, 0.0f);
        EXPECT_NEAR(a.x, b.x, 1e-5f);
        EXPECT_NEAR(a.y, b.y, 1e-5f);
        EXPECT_NEAR(a.z, b.z, 1e-5f);
    }
}

TEST(CurlNoise, StaticAtSpeedZero) {
    const kernels::ForceParams f = noise(1.0f, 0.7f, 0.0f, 2, 5);
    for (glm::vec3 p : randomPoints(100, 10.0f, 8u)) {
        const glm::vec3 a = velocity(f, p, 0.0f);
        const glm::vec3 b = velocity(f, p, 123.4f);
        EXPECT_EQ(a.x, b.x);
        EXPECT_EQ(a.y, b.y);
        EXPECT_EQ(a.z, b.z);
    }
}

// At speed 0.5 the field after 1.3 s (0.65 slices) is a different field: the
// mean |v(t1) - v(t0)| is of the order of the rms speed, far from 0. Two
// independent fields of rms s differ by rms s sqrt(2); here the field is 35 %
// of the way from slice 0 to slice 1 (w = fade(0.65)), so a fair share of that.
TEST(CurlNoise, ChangesOverTime) {
    const kernels::ForceParams f = noise(1.0f, 0.7f, 0.5f, 2, 5);
    double sum = 0.0;
    const std::vector<glm::vec3> points = randomPoints(500, 10.0f, 9u);
    for (glm::vec3 p : points) {
        sum += static_cast<double>(glm::length(velocity(f, p, 1.3f) - velocity(f, p, 0.0f)));
    }
    EXPECT_GT(sum / static_cast<double>(points.size()), 0.3);
}

// Across a slice boundary (phase 1 at t = 2 s with speed 0.5) the blend ends
// on slice 1 and the next interval starts on it: the field is continuous, and
// with the fade's zero slope at the ends, v(t + e) - v(t - e) is O(e^3):
// tiny for e = 1e-3 s (9e-7 m/s seen, float rounding), while the same
// interval in mid-slice (t = 1 s) moves v by O(e): 7e-3 m/s seen. A seed that
// did not carry over from one interval to the next would jump by ~1 m/s.
TEST(CurlNoise, ContinuousAcrossSlices) {
    const kernels::ForceParams f = noise(1.0f, 0.7f, 0.5f, 1, 5);
    const float e = 1e-3f;
    float worst = 0.0f;
    for (glm::vec3 p : randomPoints(200, 10.0f, 10u)) {
        const glm::vec3 d = velocity(f, p, 2.0f + e) - velocity(f, p, 2.0f - e);
        worst = std::max({worst, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    }
    EXPECT_LT(worst, 1e-5f);
}

// In a world: a particle of strong Stokes drag (thick medium) and no other
// force moves with the noise. Rate k / m = 6 pi eta r / m = 6 pi 1 0.05 / 1e-3
// = 942 1/s; over a step of 1/120 s the exact drag leaves e^-7.85 = 4e-4 of
// the difference between the particle's velocity and the noise's at the
// step's start (position and time), which changes by ~0.03 m/s a step. So
// after the last step the velocity is that noise velocity within ~1e-5 m/s;
// bound 1e-3 m/s. The step's start is the time before it (119 dt) and, with
// the semi-implicit Euler step p' = p + v' dt, the position p' - v' dt.
TEST(CurlNoise, ALightParticleFollowsTheNoise) {
    test::ScopedWorld w(1, 3);
    ForceDef d;
    d.kind = ForceKind::CurlNoise;
    d.strength = 2.0f;
    d.frequency = 0.7f;
    d.speed = 0.5f;
    d.octaves = 1;
    d.seed = 4;
    d.viscosity = 1.0f;
    createForce(w.id, d);
    EmitterDef e;
    e.lifecycle = Lifecycle::Spawn;
    e.capacity = 4;
    e.rate = 0.0f;
    e.bursts = {{0.0f, 1}};
    e.lifetime = {10.0f, 10.0f};
    e.speed = {0.0f, 0.0f};
    e.size = {0.1f, 0.1f};
    e.mass = 1e-3f;
    e.integrator = Integrator::SemiImplicitEuler;
    const EmitterId id = createEmitter(w.id, e);
    const float dt = 1.0f / 120.0f;
    for (int i = 0; i < 120; ++i) {
        stepWorld(w.id, dt);
    }
    const ParticleSnapshot s = readParticles(w.id, id);
    ASSERT_EQ(s.count(), 1u);
    const glm::vec3 start = s.position[0] - s.velocity[0] * dt;
    const glm::vec3 expected = velocity(noise(2.0f, 0.7f, 0.5f, 1, 4), start, static_cast<float>(119.0 * dt));
    EXPECT_GT(glm::length(expected), 0.1f);
    EXPECT_LT(glm::length(s.velocity[0] - expected), 1e-3f)
        << "velocity " << s.velocity[0].x << " " << s.velocity[0].y << " " << s.velocity[0].z;
}

}  // namespace
}  // namespace spindrift
