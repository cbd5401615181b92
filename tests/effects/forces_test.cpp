// Forces against closed forms.
#include "effects/effects_test_util.h"

#include <gtest/gtest.h>

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
// Semi-implicit Euler's per-step factor (1 - k dt / m) differs from the
// exponential by O(dt): with k dt / m = 0.001 the error after 2 s is < 0.1 %.
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
    EXPECT_NEAR(p.velocity[0].x, expected, 1e-3f * expected);
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
