// The body proxy: rigid bodies as the fluid solver sees them during one 2D
// fluid step (slides 50-51), as plain structs. src/coupling fills it from
// Box2D's broad phase on the calling thread (StepBody, LocalShape) and hands
// the impulses back at the end of the step (BodyLink in body_link.h); in
// between the worker threads read it and the contact solver here updates it,
// and nothing in src/fluid knows Box2D.
#pragma once

#include "core/parallel.h"
#include "fluid/body_joints.h"
#include "kernels/fluid.glsl"

#include <cstdint>
#include <span>
#include <vector>

namespace spindrift::fluid {

struct FluidState;
struct BodyEndPose;
template <int D> struct Grid;
template <int D> struct Particles;

/// One shape of a body in its frame relative to the body's origin (m):
/// boxes become polygons and chains their segments.
struct LocalShape {
    std::uint32_t kind = 0;  // kernels::SD_BODY_SHAPE_*
    std::vector<glm::vec2> vertices;  // polygon: counter-clockwise; segment: 2 points; circle: the centre
    float radius = 0.0f;              // circle (m)
};

/// A body's state as the fluid solver sees it during one fluid step: a local
/// copy, its velocity updated by every contact impulse so the water feels the
/// body respond within the step.
struct StepBody {
    std::uint32_t slot = 0;         // index in BodyWorld::bodies
    glm::vec2 centre{0.0f};         // m, centre of mass at the current substep
    float angle = 0.0f;             // rad
    glm::vec2 localCentre{0.0f};    // m, centre of mass in the body frame
    glm::vec2 velocity{0.0f};       // m/s
    float angularVelocity = 0.0f;   // rad/s
    float invMass = 0.0f;           // 1/kg; 0: static or kinematic
    float invInertia = 0.0f;        // 1/(kg m^2) about the centre of mass
    float friction = 0.0f;          // mixed with the fluid's
    // Exchange: the impulses the fluid gave the body this step.
    glm::vec2 linearImpulse{0.0f};  // N s
    float angularImpulse = 0.0f;    // N m s, about the centre of mass
};

/// A particle touching (or about to touch) a body shape this substep
/// (fluid.glsl; 48 bytes).
using BodyContact = kernels::FluidBodyContact;
static_assert(sizeof(BodyContact) == 48);

/// A particle that struck a body (approaching faster than kFluidImpactSpeed
/// along the normal, touching within the substep): one collision event.
struct BodyImpact {
    std::uint32_t particle;  // id (creation serial)
    std::uint32_t body;      // slot in BodyWorld::bodies
    glm::vec2 position;      // m
    float speed;             // m/s, approach speed along the normal
};

struct FluidBodyStep {
    std::vector<StepBody> bodies;
    // The joints between them, and their rows at the current substep.
    std::vector<StepJoint> joints;
    std::vector<JointRow> jointRows;
    std::vector<std::uint32_t> shapeBody;              // body of each candidate shape
    std::vector<const LocalShape*> shapeSource;        // its shape in the body frame
    std::vector<kernels::FluidBodyShape> shapes;       // world geometry at the current substep
    std::vector<glm::vec4> shapeBox;                   // lo.xy, hi.xy (m), grown by the reach
    // Shapes per grid cell (2h wide) of the current substep, CSR.
    std::vector<std::uint32_t> cellStart;
    std::vector<std::uint32_t> cellShapes;
    std::vector<std::uint32_t> cellFill;  // scratch of the counting sort
    // Contacts per chunk of particles: with static or kinematic bodies (solved
    // in parallel, they change no body) and with dynamic ones (solved in one
    // fixed order, see body_contacts.cpp).
    std::vector<std::vector<BodyContact>> fixedContacts;
    std::vector<std::vector<BodyContact>> dynamicContacts;
    float particleMass = 0.0f;     // kg
    float particleInvMass = 0.0f;  // 1/kg
    float maxParticleSpeed = 0.0f; // m/s, bound for the binning reach
    std::uint64_t contactCount = 0;
    /// Impacts of the whole fluid step, per chunk of particles (merged in
    /// chunk order: the same for any thread count).
    std::vector<std::vector<BodyImpact>> impacts;
};

/// Shapes at the bodies' current poses, binned into the substep's grid cells;
/// the joints' rows at those poses.
void beginSubstep(FluidBodyStep& s, const FluidState& f, const Grid<2>& grid, float dt);
/// Contacts of every particle with the shapes of its grid cell; a particle
/// touching a dynamic body is kept awake (FluidDef::sleepSpeed).
void findBodyContacts(WorkerPool& pool, FluidBodyStep& s, FluidState& f, const Grid<2>& grid,
                      float dt);
/// One sweep over the contacts (after each sweep of the fluid constraints),
/// then over the joints, which answer the contacts' push on the bodies.
void solveBodyContacts(WorkerPool& pool, FluidBodyStep& s, FluidState& f, float dt);
/// Moves the local poses on by dt with their velocities and updates the shapes.
void advanceBodies(FluidBodyStep& s, float dt);
/// After Box2D's step: a particle inside a dynamic body at the pose Box2D
/// left it (`s`: the bodies of f.bodiesAtEnd at their new poses, with their
/// shapes) moves with the body from where the fluid's copy ended
/// (f.bodiesAtEnd), which puts it back on the side it was on; if that is
/// still inside, out through the nearest surface. Never through a still
/// body's edge or a collider (`colliders`, the world's): such a particle
/// stays. Returns how many particles moved.
///
/// carryOutOfMovedBodies in parts, for the device's carry: the shapes placed
/// at Box2D's poses (s.shapes, s.shapeBox: their bounds) and each body's
/// pose at the end of the fluid's step (by index in s.bodies).
std::vector<BodyEndPose> placeMovedBodies(const FluidState& f, FluidBodyStep& s);
std::uint64_t carryOutOfMovedBodies(WorkerPool& pool, FluidState& f, FluidBodyStep& s,
                                    std::span<const kernels::ColliderParams> colliders);
/// Ends a path x0 -> x1 that crosses an edge of a still shape (edges and
/// chains have no inside to test) on x0's side of it, with no velocity v
/// left toward it; then puts an end point that lies inside a body shape back
/// on its surface, unless that crosses a still edge. binnedReach (m): the
/// distance from x0 within which the cell's shapes are all the shapes there
/// are.
glm::vec2 pushOutOfBodies(const FluidBodyStep& s, std::uint32_t cell, float binnedReach, glm::vec2 x0, glm::vec2 x1,
                          glm::vec2& v);
/// Grid cell (2h wide) of a point, clamped into the grid.
std::uint32_t cellOf(const Grid<2>& grid, glm::vec2 x);
/// The grid cells shape k's grown box covers this substep (after
/// beginSubstep): first x, y, last x, y, inclusive; the cells whose lists
/// hold it.
glm::ivec4 shapeCells(const FluidBodyStep& s, const Grid<2>& grid, std::size_t k);
/// The fluid's view of body b (fluid.glsl).
kernels::FluidBodyMotion bodyMotion(const StepBody& b);

}  // namespace spindrift::fluid
