// The joints of the fluid's body copies as velocity rows (body_joints.h), in
// the form of Box2D 2.4's revolute, prismatic and weld joints (b2_*_joint.cpp:
// the same Jacobians, speculative limits), solved after each sweep of the
// particle-body contacts so that a contact's push on a held body answers with
// what holds it.
#include "fluid/body_joints.h"

#include "fluid/body_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace spindrift::fluid {
namespace {

/// Fraction of a joint's position error removed per substep (Box2D's
/// b2_baumgarte). The copies start each fluid step at Box2D's poses, so the
/// error is what the substeps themselves drift.
constexpr float kJointBaumgarte = 0.2f;
constexpr float kUnbounded = std::numeric_limits<float>::infinity();

glm::vec2 rotate(float angle, glm::vec2 v) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

float cross(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

struct RowBuilder {
    const StepJoint& joint;
    const StepBody& bodyA;
    const StepBody& bodyB;
    float invDt;
    std::vector<JointRow>& rows;

    /// A row whose position error is `error` (m or rad, 0 when satisfied):
    /// an equality is pulled back by kJointBaumgarte of it per substep.
    void equality(glm::vec2 n, float sA, float sB, float error) {
        add(n, sA, sB, -kJointBaumgarte * error * invDt, -kUnbounded, kUnbounded);
    }
    /// A limit: `gap` (m or rad) is how far the joint is from it, >= 0 allowed.
    /// Speculative while open (it may close the gap within the substep, no
    /// more), pulled back when past it (Box2D 2.4's limits).
    void limit(glm::vec2 n, float sA, float sB, float gap) {
        add(n, sA, sB, gap > 0.0f ? -gap * invDt : -kJointBaumgarte * gap * invDt, 0.0f, kUnbounded);
    }
    /// A motor: the speed `speed` with at most `maxImpulse` (N s or N m s).
    void motor(glm::vec2 n, float sA, float sB, float speed, float maxImpulse) {
        add(n, sA, sB, speed, -maxImpulse, maxImpulse);
    }
    void add(glm::vec2 n, float sA, float sB, float bias, float lo, float hi) {
        const float k = (bodyA.invMass + bodyB.invMass) * glm::dot(n, n) + bodyA.invInertia * sA * sA +
                        bodyB.invInertia * sB * sB;
        if (!(k > 0.0f)) return;  // neither body can move along it
        JointRow r{};
        r.a = joint.bodyA;
        r.b = joint.bodyB;
        r.n = n;
        r.sA = sA;
        r.sB = sB;
        r.mass = 1.0f / k;
        r.bias = bias;
        r.lowerImpulse = lo;
        r.upperImpulse = hi;
        rows.push_back(r);
    }
};

void addRows(RowBuilder& rb, float dt) {
    const StepJoint& j = rb.joint;
    const StepBody& a = rb.bodyA;
    const StepBody& b = rb.bodyB;
    const glm::vec2 rA = rotate(a.angle, j.anchorA);
    const glm::vec2 rB = rotate(b.angle, j.anchorB);
    const glm::vec2 d = (b.centre + rB) - (a.centre + rA);
    const float angle = b.angle - a.angle - j.referenceAngle;
    if (j.kind == StepJointKind::Prismatic) {
        // Off the axis, no travel; along it, the limits and the motor.
        const glm::vec2 axis = rotate(a.angle, j.axisA);
        const glm::vec2 perp(-axis.y, axis.x);
        rb.equality(perp, cross(d + rA, perp), cross(rB, perp), glm::dot(perp, d));
        rb.equality(glm::vec2(0.0f), 1.0f, 1.0f, angle);
        const float sA = cross(d + rA, axis), sB = cross(rB, axis);
        const float travel = glm::dot(axis, d);
        if (j.limit) {
            rb.limit(axis, sA, sB, travel - j.lower);
            rb.limit(-axis, -sA, -sB, j.upper - travel);
        }
        if (j.motor) rb.motor(axis, sA, sB, j.motorSpeed, j.maxMotor * dt);
        return;
    }
    // Revolute and weld: the anchors stay together.
    rb.equality(glm::vec2(1.0f, 0.0f), cross(rA, glm::vec2(1.0f, 0.0f)), cross(rB, glm::vec2(1.0f, 0.0f)), d.x);
    rb.equality(glm::vec2(0.0f, 1.0f), cross(rA, glm::vec2(0.0f, 1.0f)), cross(rB, glm::vec2(0.0f, 1.0f)), d.y);
    if (j.kind == StepJointKind::Weld) {
        rb.equality(glm::vec2(0.0f), 1.0f, 1.0f, angle);
        return;
    }
    if (j.limit) {
        rb.limit(glm::vec2(0.0f), 1.0f, 1.0f, angle - j.lower);
        rb.limit(glm::vec2(0.0f), -1.0f, -1.0f, j.upper - angle);
    }
    if (j.motor) rb.motor(glm::vec2(0.0f), 1.0f, 1.0f, j.motorSpeed, j.maxMotor * dt);
}

/// Passes over the rows per call (fluid.glsl).
constexpr int kJointPasses = kernels::SD_FLUID_JOINT_PASSES;

}  // namespace

void setUpJointRows(const std::vector<StepJoint>& joints, const std::vector<StepBody>& bodies, float dt,
                    std::vector<JointRow>& rows) {
    rows.clear();
    for (const StepJoint& j : joints) {
        RowBuilder rb{j, bodies[j.bodyA], bodies[j.bodyB], 1.0f / dt, rows};
        addRows(rb, dt);
    }
}

void solveJointRows(std::vector<JointRow>& rows, std::vector<StepBody>& bodies) {
    for (int pass = 0; pass < kJointPasses; ++pass) {
        for (JointRow& r : rows) {
            StepBody& a = bodies[r.a];
            StepBody& b = bodies[r.b];
            const kernels::FluidJointVisit v = kernels::fluidSolveJointRow(r, bodyMotion(a), bodyMotion(b));
            r.impulse = v.impulse;
            a.velocity = v.velocityA;
            a.angularVelocity = v.angularA;
            b.velocity = v.velocityB;
            b.angularVelocity = v.angularB;
        }
    }
}

}  // namespace spindrift::fluid
