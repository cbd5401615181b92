// The world's rigid bodies: a Box2D 2.4 world, our slots for bodies and
// joints (ids are 1-based creation serials, never reused), and each body's
// shapes as the fluid sees them (fluid::LocalShape). Box2D is only ever called
// from the thread that calls the public API (docs/design.md: coupling only at
// step boundaries). A null BodyWorld* is a world that has no bodies yet.
#pragma once

#include "fluid/body_contacts.h"
#include "fluid/fluid_state.h"

#include <spindrift/bodies.h>

#include <box2d/box2d.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace spindrift::coupling {

using fluid::LocalShape;

struct BodySlot {
    b2Body* body = nullptr;  // null once destroyed
    BodyDef def;
    std::vector<LocalShape> fluidShapes;
    /// Its pose before the step being taken: where a body whose numbers
    /// become NaN or infinite is frozen (stepBodies).
    b2Vec2 lastPosition{0.0f, 0.0f};
    float lastAngle = 0.0f;
};

struct JointSlot {
    b2Joint* joint = nullptr;  // null once destroyed (with its body or on its own)
    JointDef def;
};

struct BodyWorld {
    explicit BodyWorld(glm::vec2 gravity);
    /// Zero: the bodies' gravity (WorldDef::bodyGravity) is added to their
    /// velocities before the fluids solve (beginBodyStep), so the water's
    /// pressure answers this step's weight; Box2D then integrates it.
    b2World world{b2Vec2(0.0f, 0.0f)};
    glm::vec2 gravity;  // m/s^2
    std::vector<BodySlot> bodies;
    std::vector<JointSlot> joints;
    /// Grabs (Box2D mouse joints), null once destroyed, with their body or on
    /// their own; their fixed end is `ground`, a body without fixtures made
    /// with the first grab, so nothing collides with it or sees it.
    std::vector<b2MouseJoint*> grabs;
    b2Body* ground = nullptr;
    std::uint32_t alive = 0;
    /// Scratch of the fluid step being solved (one fluid at a time).
    fluid::FluidBodyStep fluidStep;
};

/// The body of `id`, or throws Error for one that does not exist.
BodySlot& bodyFromId(BodyWorld& bodies, BodyId id);

/// Before the fluids: dynamic bodies get this step's gravity (m/s^2 x dt).
void beginBodyStep(BodyWorld& bodies, float dt);
/// After the fluids: Box2D steps the bodies by dt (body contacts, joints,
/// integration of the velocities the water left them). A body whose pose or
/// velocity is NaN or infinite, before the step (the water's impulses) or
/// after it, is frozen: put back at its pose before the step, made static
/// with zero velocity; returns those frozen in this step.
std::vector<BodyId> stepBodies(BodyWorld& bodies, float dt);

/// Where a jet riding `body` is this step (index 0: fixed in the world; a
/// destroyed body: inactive).
fluid::JetMount jetMount(const BodyWorld* bodies, BodyId body);
/// Gives a jet's body the recoil of the particles it emitted.
void applyRecoil(BodyWorld* bodies, BodyId body, const fluid::JetMount& mount);
/// Throws Error if a jet names a body the world does not have.
void checkJetBody(BodyWorld* bodies, const FluidJetDef& jet);

// The public API of include/spindrift/bodies.h on one world's bodies (the
// wrappers by world id are src/world/body_api.cpp). Those taking a pointer
// throw Error naming the id when it is null (no bodies yet).
/// Adds a body from a validated definition (validateBodyDef).
BodyId createBody(BodyWorld& bodies, const BodyDef& def);
void destroyBody(BodyWorld* bodies, BodyId body);
JointId createJoint(BodyWorld* bodies, const JointDef& def);
void destroyJoint(BodyWorld* bodies, JointId joint);
void setBodyTransform(BodyWorld* bodies, BodyId body, glm::vec2 position, float angle);
void setBodyVelocity(BodyWorld* bodies, BodyId body, glm::vec2 linearVelocity, float angularVelocity);
void applyBodyImpulse(BodyWorld* bodies, BodyId body, glm::vec2 impulse, glm::vec2 point);
float bodyMass(BodyWorld* bodies, BodyId body);
GrabId createGrab(BodyWorld* bodies, const GrabDef& def);
void moveGrab(BodyWorld* bodies, GrabId grab, glm::vec2 target);
void destroyGrab(BodyWorld* bodies, GrabId grab);
BodyId bodyAt(const BodyWorld* bodies, glm::vec2 point);
std::uint32_t bodyCount(const BodyWorld* bodies);
std::vector<BodySnapshot> readBodies(const BodyWorld* bodies);

}  // namespace spindrift::coupling
