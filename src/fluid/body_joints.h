// Joints as the fluid's body copies see them during one 2D fluid step. Box2D
// solves the joints in its own step, after the fluid's; without them here a
// body Box2D holds (a hinged gate on its limit, a shelf on a hinge) was a free
// body within the fluid's substeps, which the water drove where Box2D then did
// not let it go, and the particles that followed it ended the step inside the
// real body (docs/fluid.md, "Bodies that joints hold").
#pragma once

#include "kernels/fluid.glsl"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace spindrift::fluid {

struct StepBody;

enum class StepJointKind : std::uint32_t { Revolute, Prismatic, Weld };

/// One joint between two of FluidBodyStep::bodies (src/coupling copies it from
/// Box2D's joint; a partner far from the fluid is in the list too, with no
/// shapes and no mass, so it does not move).
struct StepJoint {
    StepJointKind kind = StepJointKind::Revolute;
    std::uint32_t bodyA = 0;          // index in FluidBodyStep::bodies
    std::uint32_t bodyB = 0;
    glm::vec2 anchorA{0.0f};          // m, from A's centre of mass, in A's frame
    glm::vec2 anchorB{0.0f};          // m, from B's centre of mass, in B's frame
    glm::vec2 axisA{1.0f, 0.0f};      // Prismatic: unit, in A's frame
    float referenceAngle = 0.0f;      // rad, B's angle minus A's at rest
    bool limit = false;
    float lower = 0.0f;               // rad (Revolute) or m (Prismatic)
    float upper = 0.0f;
    bool motor = false;
    float motorSpeed = 0.0f;          // rad/s or m/s
    float maxMotor = 0.0f;            // N m or N
};

/// One scalar velocity constraint between bodies a and b (fluid.glsl).
using JointRow = kernels::FluidJointRow;

/// The rows of every joint at the bodies' poses of this substep (dt, s).
void setUpJointRows(const std::vector<StepJoint>& joints, const std::vector<StepBody>& bodies, float dt,
                    std::vector<JointRow>& rows);
/// A few Gauss-Seidel passes over the rows, changing the bodies' velocities
/// only (Box2D's own step applies the joints' impulses to the real bodies).
void solveJointRows(std::vector<JointRow>& rows, std::vector<StepBody>& bodies);

}  // namespace spindrift::fluid
