// The world's rigid bodies: a Box2D 2.4 world, our slots for bodies and
// joints (ids are 1-based creation serials, never reused), and each body's
// shapes as the fluid sees them. Box2D is only ever called from the thread
// that calls the public API (DESIGN.md: coupling only at step boundaries).
#pragma once

#include "coupling/body_contacts.h"
#include "effects/world_internal.h"

#include <spindrift/bodies.h>

#include <box2d/box2d.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace spindrift {
struct World;
namespace fluid {
struct JetMount;
}
}  // namespace spindrift

namespace spindrift::coupling {

/// One shape of a body in its frame relative to the body's origin (m):
/// boxes become polygons and chains their segments.
struct LocalShape {
    std::uint32_t kind = 0;  // kernels::SD_BODY_SHAPE_*
    std::vector<glm::vec2> vertices;  // polygon: counter-clockwise; segment: 2 points; circle: the centre
    float radius = 0.0f;              // circle (m)
};

struct BodySlot {
    b2Body* body = nullptr;  // null once destroyed
    BodyDef def;
    std::vector<LocalShape> fluidShapes;
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
    std::uint32_t alive = 0;
    /// Scratch of the fluid step being solved (one fluid at a time).
    FluidBodyStep fluidStep;
};

/// The body of `id`, or throws Error for one that does not exist.
BodySlot& bodyFromId(BodyWorld& bodies, BodyId id);

/// Before the fluids: dynamic bodies get this step's gravity (m/s^2 x dt).
void beginBodyStep(BodyWorld& bodies, float dt);
/// After the fluids: Box2D steps the bodies by dt (body contacts, joints,
/// integration of the velocities the water left them).
void stepBodies(BodyWorld& bodies, float dt);

/// Where a jet riding `body` is this step (index 0: fixed in the world; a
/// destroyed body: inactive).
fluid::JetMount jetMount(World& world, BodyId body);
/// Gives a jet's body the recoil of the particles it emitted.
void applyRecoil(World& world, BodyId body, const fluid::JetMount& mount);
/// Throws Error if a jet names a body the world does not have.
void checkJetBody(World& world, const FluidJetDef& jet);

}  // namespace spindrift::coupling
