// Integrators against closed forms (docs/design.md, "Checks that physics gives us").
#include "effects/effects_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

using test::OneShot;
using test::ScopedWorld;

glm::vec3 finalPosition(Integrator integrator, float dt, int steps, const std::vector<ForceDef>& forces,
                        glm::vec3 start, glm::vec3 velocity) {
    ScopedWorld w;
    for (const ForceDef& f : forces) {
        createForce(w.id, f);
    }
    OneShot o;
    o.start = start;
    o.velocity = velocity;
    o.integrator = integrator;
    EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
    ParticleSnapshot s = test::run(w.id, e, dt, steps);
    EXPECT_EQ(s.count(), 1u);
    return s.count() == 1 ? s.position[0] : glm::vec3(NAN);
}

// Under constant acceleration velocity Verlet and RK4 are exact: they
// integrate a quadratic without truncation error, so only float rounding
// remains. Tolerance: 2e-5 relative to the travelled distance (~100 steps of
// float rounding at ~6e-8 each, with margin).
TEST(Integrators, VerletAndRk4MatchConstantAccelerationClosedForm) {
    const glm::vec3 g(0.0f, -9.81f, 0.0f);
    const glm::vec3 p0(1.0f, 20.0f, -2.0f), v0(3.0f, 12.0f, 0.5f);
    const float dt = 1.0f / 60.0f;
    const int steps = 120;
    const float t = dt * steps;
    const glm::vec3 exact = p0 + v0 * t + 0.5f * g * t * t;
    for (Integrator integrator : {Integrator::Verlet, Integrator::Rk4}) {
        glm::vec3 p = finalPosition(integrator, dt, steps, {test::gravity(g)}, p0, v0);
        float scale = glm::length(exact - p0);
        EXPECT_NEAR(p.x, exact.x, 2e-5f * scale) << static_cast<int>(integrator);
        EXPECT_NEAR(p.y, exact.y, 2e-5f * scale) << static_cast<int>(integrator);
        EXPECT_NEAR(p.z, exact.z, 2e-5f * scale) << static_cast<int>(integrator);
    }
}

// Semi-implicit Euler under constant g is off by exactly g t dt / 2 per axis
// (sum of a geometric series), a closed form of its own: checks that the
// integrator is what it says, and that Euler is not accidentally exact.
TEST(Integrators, SemiImplicitEulerHasItsKnownConstantAccelerationError) {
    const glm::vec3 g(0.0f, -10.0f, 0.0f);
    const float dt = 0.01f;
    const int steps = 100;
    const float t = dt * steps;
    glm::vec3 p = finalPosition(Integrator::SemiImplicitEuler, dt, steps, {test::gravity(g)}, glm::vec3(0.0f),
                                glm::vec3(0.0f));
    // y_n = g dt^2 n (n + 1) / 2 = g t^2 / 2 + g t dt / 2.
    EXPECT_NEAR(p.y, 0.5f * g.y * t * t + 0.5f * g.y * t * dt, 1e-4f);
}

// A spring attractor (falloff -1: F = k x with k = strength / radius) makes a
// harmonic oscillator x(t) = x0 cos(w t), w = sqrt(k / m). Halving dt should
// cut the global error by 2^order: about 2 for Euler, 16 for RK4. Bounds are
// wide (1.6 to 2.6, and 11 to 22) because the ratio only tends to 2^order as
// dt -> 0, and float rounding floors RK4's error.
double oscillatorError(Integrator integrator, float dt) {
    ForceDef spring;
    spring.kind = ForceKind::Attractor;
    spring.position = glm::vec3(0.0f);
    spring.strength = 4.0f;  // N at 1 m: k = 4 N/m, m = 1 kg, w = 2 rad/s
    spring.radius = 1.0f;
    spring.falloff = -1.0f;
    const float total = 2.0f;
    auto steps = static_cast<int>(std::lround(total / dt));
    glm::vec3 p = finalPosition(integrator, dt, steps, {spring}, glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f));
    return std::abs(static_cast<double>(p.x) - std::cos(2.0 * total));
}

TEST(Integrators, ExplicitEulerConvergesAtFirstOrder) {
    double coarse = oscillatorError(Integrator::ExplicitEuler, 0.01f);
    double fine = oscillatorError(Integrator::ExplicitEuler, 0.005f);
    EXPECT_GT(coarse / fine, 1.6);
    EXPECT_LT(coarse / fine, 2.6);
}

TEST(Integrators, Rk4ConvergesAtFourthOrder) {
    double coarse = oscillatorError(Integrator::Rk4, 0.2f);
    double fine = oscillatorError(Integrator::Rk4, 0.1f);
    EXPECT_GT(coarse / fine, 11.0);
    EXPECT_LT(coarse / fine, 22.0);
}

TEST(Integrators, VerletConvergesAtSecondOrder) {
    double coarse = oscillatorError(Integrator::Verlet, 0.04f);
    double fine = oscillatorError(Integrator::Verlet, 0.02f);
    EXPECT_GT(coarse / fine, 3.2);
    EXPECT_LT(coarse / fine, 4.8);
}

}  // namespace
}  // namespace spindrift
