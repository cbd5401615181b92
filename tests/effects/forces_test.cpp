// Forces against closed forms.
#include "effects/effects_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace spindrift {
namespace {

using test::OneShot;
using test::ScopedWorld;

FlowFieldId uniformFlow(WorldId w, glm::vec3 velocity) {
    FlowFieldDef f;
    f.boundsMin = glm::vec3(-100.0f);
    f.boundsMax = glm::vec3(100.0f);
    f.nx = f.ny = f.nz = 2;
    f.velocities.assign(8, velocity);
    return createFlowField(w, f);
}

// Stokes drag F = 6 pi eta r (v_flow - v) with gravity reaches the terminal
// velocity v_flow + m g / (6 pi eta r) (docs/design.md). The relaxation time is
// m / k = 0.1 s here; after 3 s (30 time constants) the remaining transient is
// e^-30 of the start, so the only error is RK4's, far below the 1e-4 relative
// tolerance.
TEST(Forces, StokesDragReachesTerminalVelocity) {
    ScopedWorld w;
    const glm::vec3 flow(1.0f, 0.5f, -2.0f);
    const glm::vec3 g(0.0f, -9.81f, 0.0f);
    const float eta = 0.5f, size = 0.2f, mass = 0.0942478f;  // k = 6 pi 0.5 0.1 = 0.942478 kg/s
    createForce(w.id, test::gravity(g));
    ForceDef drag;
    drag.kind = ForceKind::FlowField;
    drag.flowField = uniformFlow(w.id, flow);
    drag.viscosity = eta;
    createForce(w.id, drag);
    OneShot o;
    o.size = size;
    o.mass = mass;
    o.integrator = Integrator::Rk4;
    EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
    ParticleSnapshot p = test::run(w.id, e, 0.01f, 300);
    ASSERT_EQ(p.count(), 1u);
    const float k = 6.0f * 3.14159265f * eta * 0.5f * size;
    const glm::vec3 terminal = flow + mass * g / k;
    EXPECT_NEAR(p.velocity[0].x, terminal.x, 1e-4f * glm::length(terminal));
    EXPECT_NEAR(p.velocity[0].y, terminal.y, 1e-4f * glm::length(terminal));
    EXPECT_NEAR(p.velocity[0].z, terminal.z, 1e-4f * glm::length(terminal));
}

// Damping is an exact exponential: the speed after 1 s is s0 exp(-k) whatever
// the step. Float rounding over up to 240 steps: 1e-5 relative.
TEST(Forces, DampingIsFrameRateIndependent) {
    for (int stepsPerSecond : {7, 30, 240}) {
        ScopedWorld w;
        ForceDef damping;
        damping.kind = ForceKind::Damping;
        damping.strength = 1.5f;
        createForce(w.id, damping);
        OneShot o;
        o.velocity = {3.0f, 4.0f, 0.0f};
        EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
        ParticleSnapshot p = test::run(w.id, e, 1.0f / static_cast<float>(stepsPerSecond), stepsPerSecond);
        ASSERT_EQ(p.count(), 1u);
        EXPECT_NEAR(glm::length(p.velocity[0]), 5.0f * std::exp(-1.5f), 1e-5f * 5.0f) << stepsPerSecond;
        // Direction kept.
        EXPECT_NEAR(p.velocity[0].x / p.velocity[0].y, 0.75f, 1e-5f);
    }
}

// Un-damping drives the speed toward the target: s(t) = T + (s0 - T) e^-kt,
// from below (a slow bee speeds up) and from above.
TEST(Forces, UndampingRelaxesSpeedTowardTarget) {
    for (float s0 : {0.5f, 8.0f}) {
        ScopedWorld w;
        ForceDef bee;
        bee.kind = ForceKind::Undamping;
        bee.strength = 2.0f;
        bee.targetSpeed = 3.0f;
        createForce(w.id, bee);
        OneShot o;
        o.velocity = {0.0f, 0.0f, s0};
        EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
        ParticleSnapshot p = test::run(w.id, e, 0.05f, 10);
        ASSERT_EQ(p.count(), 1u);
        float expected = 3.0f + (s0 - 3.0f) * std::exp(-2.0f * 0.5f);
        EXPECT_NEAR(glm::length(p.velocity[0]), expected, 1e-5f * expected) << s0;
    }
}

// Wind is linear drag toward the wind velocity: v(t) = w + (v0 - w) e^(-k t / m).
// The drag is solved exactly over each step, so the only error is float
// rounding over 500 steps: 1e-5 relative (it was 1e-3 when semi-implicit
// Euler's factor 1 - k dt / m stood in for the exponential).
TEST(Forces, WindDragsVelocityTowardWind) {
    ScopedWorld w;
    ForceDef wind;
    wind.kind = ForceKind::Wind;
    wind.vector = {5.0f, 0.0f, 0.0f};
    wind.strength = 0.5f;
    createForce(w.id, wind);
    OneShot o;
    o.mass = 2.0f;
    EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
    ParticleSnapshot p = test::run(w.id, e, 0.004f, 500);
    ASSERT_EQ(p.count(), 1u);
    float expected = 5.0f * (1.0f - std::exp(-0.5f * 2.0f / 2.0f));
    EXPECT_NEAR(p.velocity[0].x, expected, 1e-5f * expected);
}

const Integrator kIntegrators[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::Verlet,
                                   Integrator::Rk4};

ForceDef windForce(glm::vec3 velocity, float k) {
    ForceDef wind;
    wind.kind = ForceKind::Wind;
    wind.vector = velocity;
    wind.strength = k;
    return wind;
}

// Gravity and two winds: dv/dt = g + K (u - v) with K = (k1 + k2) / m and u the
// k-weighted wind velocity, so v(t) = T + (v0 - T) e^(-K t) with the terminal
// velocity T = u + g m / (k1 + k2). Every integrator solves the drag exactly
// and holds g and u (both constant here) exactly, so it is the closed form at
// every step, whatever K dt: from K dt = 0.05 to 5, which is the spark of issue
// 18 (mass 1 g in 0.3 N s/m of wind: explicit Euler used to multiply the
// velocity by 1 - 5 = -4 per step). Error: float rounding over at most 60
// steps, 1e-5 relative to the larger of |v0| and |T| (plus 1e-6 m/s where both
// terms cancel), far below what any wrong weight would give (the transient
// alone is e^-1 = 37 % after 1 s at K = 1).
TEST(Forces, DragWithGravityIsTheClosedFormForEveryIntegrator) {
    const glm::vec3 g(0.0f, -9.81f, 0.0f), v0(1.0f, 6.0f, -2.0f);
    const glm::vec3 u1(3.0f, 0.0f, 1.0f), u2(-1.0f, 0.5f, 0.0f);
    const float k1 = 0.2f, k2 = 0.1f;  // kg/s
    for (Integrator integrator : kIntegrators) {
        for (float mass : {1e-3f, 0.03f, 0.3f}) {
            for (float dt : {1.0f / 60.0f, 1.0f / 7.0f}) {
                SCOPED_TRACE(::testing::Message() << "integrator " << static_cast<int>(integrator) << " mass " << mass
                                                  << " dt " << dt);
                ScopedWorld w;
                createForce(w.id, test::gravity(g));
                createForce(w.id, windForce(u1, k1));
                createForce(w.id, windForce(u2, k2));
                OneShot o;
                o.velocity = v0;
                o.mass = mass;
                o.integrator = integrator;
                EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
                const int steps = dt < 0.1f ? 60 : 7;
                ParticleSnapshot p = test::run(w.id, e, dt, steps);
                ASSERT_EQ(p.count(), 1u);
                const double K = double(k1 + k2) / mass, t = double(dt) * steps;
                for (int c = 0; c < 3; ++c) {
                    const double terminal =
                        (double(k1) * u1[c] + double(k2) * u2[c]) / double(k1 + k2) + double(g[c]) * mass / (k1 + k2);
                    const double exact = terminal + (double(v0[c]) - terminal) * std::exp(-K * t);
                    const double scale = std::max(glm::length(v0), std::abs(float(terminal)));
                    EXPECT_NEAR(p.velocity[0][c], exact, 1e-5 * scale + 1e-6) << c;
                }
            }
        }
    }
}

// Verlet's position is the exact integral of the velocity for constant forces:
// p(t) = p0 + T t + (v0 - T) (1 - e^(-K t)) / K. Rounding over 60 steps of
// positions up to ~10 m: 1e-5 relative to the distance travelled.
TEST(Forces, VerletPositionUnderDragIsTheClosedForm) {
    const glm::vec3 g(0.0f, -9.81f, 0.0f), v0(1.0f, 6.0f, -2.0f), u(3.0f, 0.0f, 1.0f);
    for (float mass : {1e-3f, 0.3f}) {
        SCOPED_TRACE(mass);
        const float k = 0.3f, dt = 1.0f / 60.0f;
        ScopedWorld w;
        createForce(w.id, test::gravity(g));
        createForce(w.id, windForce(u, k));
        OneShot o;
        o.start = {0.5f, 2.0f, 0.0f};
        o.velocity = v0;
        o.mass = mass;
        o.integrator = Integrator::Verlet;
        EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
        ParticleSnapshot p = test::run(w.id, e, dt, 60);
        ASSERT_EQ(p.count(), 1u);
        const double K = double(k) / mass, t = double(dt) * 60;
        glm::dvec3 exact;
        for (int c = 0; c < 3; ++c) {
            const double terminal = double(u[c]) + double(g[c]) * mass / k;
            exact[c] = o.start[c] + terminal * t + (double(v0[c]) - terminal) * (-std::expm1(-K * t)) / K;
        }
        const double travelled = glm::length(exact - glm::dvec3(o.start));
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(p.position[0][c], exact[c], 1e-5 * travelled) << c;
        }
    }
}

// A stiff drag cannot make any integrator grow the velocity: 1 g in 100 N s/m
// of wind (K dt = 1667 at 60 steps per second) next to a spring attractor, so
// the forcing changes with position. Along x, m x'' = -s x + k (u - x') with
// s = 4 N/m: roots r = (-K +- sqrt(K^2 - 4 s / m)) / 2 of 1e5 and 0.04 1/s,
// so after the first step the particle creeps toward x = k u / s = 12.5 m at
// u - s x / k (0.46 m/s at the start). Checked: every step's speed stays
// below 0.6 m/s (the launch speed of 40 m/s is gone after one step), and the
// x velocity after 2 s is the closed form's to 1e-3 m/s (the integrators' own
// error on the slow mode, rate 0.04 1/s, is ~1e-5 m/s; explicit Euler's old
// amplification 1 - K dt = -1666 per step would overflow in 12 steps).
TEST(Forces, StiffDragStaysBoundedForEveryIntegrator) {
    const double K = 1e5, omega2 = 4000.0, ux = 0.5;  // 1/s, 1/s^2 (s / m), m/s
    const double root = std::sqrt(K * K - 4.0 * omega2);
    const double fast = -0.5 * (K + root), slow = omega2 / fast;  // r1 r2 = omega^2
    const double rest = K * ux / omega2, a = (1.0 - rest) * fast / (fast - slow), b = (1.0 - rest) - a;
    const double t = 2.0, vx = slow * a * std::exp(slow * t) + fast * b * std::exp(fast * t);
    for (Integrator integrator : kIntegrators) {
        SCOPED_TRACE(static_cast<int>(integrator));
        ScopedWorld w;
        ForceDef spring;
        spring.kind = ForceKind::Attractor;
        spring.position = glm::vec3(0.0f);
        spring.strength = 4.0f;  // N at 1 m
        spring.radius = 1.0f;
        spring.falloff = -1.0f;
        createForce(w.id, spring);
        createForce(w.id, windForce({static_cast<float>(ux), 0.0f, 0.0f}, 100.0f));
        OneShot o;
        o.start = {1.0f, 0.0f, 0.0f};
        o.velocity = {0.0f, 40.0f, 0.0f};
        o.mass = 1e-3f;
        o.integrator = integrator;
        EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
        float largest = 0.0f;
        for (int s = 0; s < 120; ++s) {
            stepWorld(w.id, 1.0f / 60.0f);
            ParticleSnapshot p = readParticles(w.id, e);
            ASSERT_EQ(p.count(), 1u) << "step " << s;
            largest = std::max(largest, glm::length(p.velocity[0]));
        }
        EXPECT_LT(largest, 0.6f);
        ParticleSnapshot p = readParticles(w.id, e);
        ASSERT_EQ(p.count(), 1u);
        EXPECT_NEAR(p.velocity[0].x, vx, 1e-3);
    }
}

// A damped oscillator (spring 4 N/m, wind drag 1 N s/m toward rest, 1 kg):
// x(t) = e^(-t/2) (cos(w t) + sin(w t) / (2 w)), w = sqrt(3.75) rad/s. With
// the drag solved exactly the integrators keep their orders on the rest:
// halving dt cuts the error by about 2, 4 and 16 (the bounds of the
// undamped tests in integrators_test.cpp). A wrong drag weight that is right
// only to first order would leave Verlet and RK4 at a ratio near 2.
double dampedOscillatorError(Integrator integrator, float dt) {
    ScopedWorld w;
    ForceDef spring;
    spring.kind = ForceKind::Attractor;
    spring.position = glm::vec3(0.0f);
    spring.strength = 4.0f;
    spring.radius = 1.0f;
    spring.falloff = -1.0f;
    createForce(w.id, spring);
    createForce(w.id, windForce(glm::vec3(0.0f), 1.0f));
    OneShot o;
    o.start = {1.0f, 0.0f, 0.0f};
    o.integrator = integrator;
    EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
    const float total = 2.0f;
    ParticleSnapshot p = test::run(w.id, e, dt, static_cast<int>(std::lround(total / dt)));
    EXPECT_EQ(p.count(), 1u);
    if (p.count() != 1u) {
        return NAN;
    }
    const double omega = std::sqrt(3.75);
    const double exact = std::exp(-0.5 * total) * (std::cos(omega * total) + std::sin(omega * total) / (2.0 * omega));
    return std::abs(static_cast<double>(p.position[0].x) - exact);
}

TEST(Forces, DampedOscillatorConvergesAtEachIntegratorsOrder) {
    const double euler = dampedOscillatorError(Integrator::SemiImplicitEuler, 0.01f) /
                         dampedOscillatorError(Integrator::SemiImplicitEuler, 0.005f);
    EXPECT_GT(euler, 1.6);
    EXPECT_LT(euler, 2.6);
    const double explicitEuler = dampedOscillatorError(Integrator::ExplicitEuler, 0.01f) /
                                 dampedOscillatorError(Integrator::ExplicitEuler, 0.005f);
    EXPECT_GT(explicitEuler, 1.6);
    EXPECT_LT(explicitEuler, 2.6);
    const double verlet =
        dampedOscillatorError(Integrator::Verlet, 0.04f) / dampedOscillatorError(Integrator::Verlet, 0.02f);
    EXPECT_GT(verlet, 3.2);
    EXPECT_LT(verlet, 4.8);
    const double rk4 = dampedOscillatorError(Integrator::Rk4, 0.2f) / dampedOscillatorError(Integrator::Rk4, 0.1f);
    EXPECT_GT(rk4, 11.0);
    EXPECT_LT(rk4, 22.0);
}

// Inverse-square attraction from rest is a radial Kepler fall, a cycloid:
// r = r0 (1 + cos eta) / 2, t = sqrt(r0^3 / (8 mu)) (eta + sin eta), with
// mu = strength radius^2 / m = 1 here. From r0 = 1, r = 0.5 at eta = pi / 2,
// t = sqrt(1/8) (pi/2 + 1) = 0.908921 s. RK4 at dt = 0.1 ms is accurate to far
// better than the 1 mm tolerance (the softening radius, 1 cm, is never reached).
TEST(Forces, InverseSquareAttractorMatchesRadialKeplerFall) {
    ScopedWorld w;
    ForceDef sun;
    sun.kind = ForceKind::Attractor;
    sun.position = glm::vec3(0.0f);
    sun.strength = 1.0f;
    sun.radius = 1.0f;
    sun.falloff = 2.0f;
    createForce(w.id, sun);
    OneShot o;
    o.start = {1.0f, 0.0f, 0.0f};
    o.integrator = Integrator::Rk4;
    EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
    // Cycloid: r = r0 (1 + cos eta) / 2, t = sqrt(r0^3 / (8 mu)) (eta + sin eta).
    // r = 0.5: eta = pi / 2, t = sqrt(1 / 8) (pi / 2 + 1) = 0.908921 s.
    const float dt = 1e-4f;
    ParticleSnapshot p = test::run(w.id, e, dt, 9089);
    ASSERT_EQ(p.count(), 1u);
    EXPECT_NEAR(p.position[0].x, 0.5f, 1e-3f);
}

// A vortex pushes tangentially: from rest at (1, 0, 0) around the y axis the
// first push is along +z (axis x radial), and never has a radial or axial part
// at the start.
TEST(Forces, VortexPushesTangentially) {
    ScopedWorld w;
    ForceDef swirl;
    swirl.kind = ForceKind::Vortex;
    swirl.axis = {0.0f, 1.0f, 0.0f};
    swirl.strength = 2.0f;
    swirl.falloff = 0.0f;
    createForce(w.id, swirl);
    OneShot o;
    o.start = {1.0f, 0.0f, 0.0f};
    o.integrator = Integrator::ExplicitEuler;
    EmitterId e = createEmitter(w.id, test::oneShotEmitter(o));
    ParticleSnapshot p = test::run(w.id, e, 0.01f, 1);
    ASSERT_EQ(p.count(), 1u);
    // cross(y, x) = -z; |F| = 2 N on 1 kg for 0.01 s.
    EXPECT_FLOAT_EQ(p.velocity[0].z, -0.02f);
    EXPECT_FLOAT_EQ(p.velocity[0].x, 0.0f);
    EXPECT_FLOAT_EQ(p.velocity[0].y, 0.0f);
}

}  // namespace
}  // namespace spindrift
