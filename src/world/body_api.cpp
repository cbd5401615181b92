// The public API of include/spindrift/bodies.h by world id: each call finds the
// world and hands its bodies (null until the first body) to src/coupling.
#include "coupling/body_world.h"
#include "world/world.h"

namespace spindrift {

BodyId createBody(WorldId id, const BodyDef& def) {
    World& w = worldFromId(id);
    validateBodyDef(def);
    // The Box2D world is made with the first body.
    if (!w.bodies) w.bodies.reset(new coupling::BodyWorld(w.def.bodyGravity));
    return coupling::createBody(*w.bodies, def);
}

void destroyBody(WorldId id, BodyId body) { coupling::destroyBody(worldFromId(id).bodies.get(), body); }

JointId createJoint(WorldId id, const JointDef& def) {
    return coupling::createJoint(worldFromId(id).bodies.get(), def);
}

void destroyJoint(WorldId id, JointId joint) { coupling::destroyJoint(worldFromId(id).bodies.get(), joint); }

void setBodyTransform(WorldId id, BodyId body, glm::vec2 position, float angle) {
    coupling::setBodyTransform(worldFromId(id).bodies.get(), body, position, angle);
}

void setBodyVelocity(WorldId id, BodyId body, glm::vec2 linearVelocity, float angularVelocity) {
    coupling::setBodyVelocity(worldFromId(id).bodies.get(), body, linearVelocity, angularVelocity);
}

void applyBodyImpulse(WorldId id, BodyId body, glm::vec2 impulse, glm::vec2 point) {
    coupling::applyBodyImpulse(worldFromId(id).bodies.get(), body, impulse, point);
}

float bodyMass(WorldId id, BodyId body) { return coupling::bodyMass(worldFromId(id).bodies.get(), body); }

GrabId createGrab(WorldId id, const GrabDef& def) { return coupling::createGrab(worldFromId(id).bodies.get(), def); }

void moveGrab(WorldId id, GrabId grab, glm::vec2 target) {
    coupling::moveGrab(worldFromId(id).bodies.get(), grab, target);
}

void destroyGrab(WorldId id, GrabId grab) { coupling::destroyGrab(worldFromId(id).bodies.get(), grab); }

BodyId bodyAt(WorldId id, glm::vec2 point) { return coupling::bodyAt(worldFromId(id).bodies.get(), point); }

std::uint32_t bodyCount(WorldId id) { return coupling::bodyCount(worldFromId(id).bodies.get()); }

std::vector<BodySnapshot> readBodies(WorldId id) { return coupling::readBodies(worldFromId(id).bodies.get()); }

}  // namespace spindrift
