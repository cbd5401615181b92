// Gathering bodies into the fluid's proxy through Box2D's broad phase, and
// the link the hub hands a fluid step (see fluid_link.h).
#include "coupling/fluid_link.h"

#include "coupling/body_world.h"
#include "coupling/exchange.h"

#include <algorithm>

namespace spindrift::coupling {
namespace {

/// Broad-phase answer: the 1-based slots of the bodies whose fixtures overlap.
class SlotCollector : public b2QueryCallback {
public:
    bool ReportFixture(b2Fixture* fixture) override {
        slots.push_back(static_cast<std::uint32_t>(fixture->GetBody()->GetUserData().pointer));
        return true;
    }
    std::vector<std::uint32_t> slots;
};

/// Marks a body slot that is not in the fluid step's list.
constexpr std::uint32_t kNotGathered = ~0u;

/// A body as the fluid step's local copy starts it: Box2D's pose and velocity.
fluid::StepBody stepBodyOf(const BodySlot& slot, std::uint32_t slotIndex) {
    const b2Body& body = *slot.body;
    fluid::StepBody b;
    b.slot = slotIndex;
    b.centre = glm::vec2(body.GetWorldCenter().x, body.GetWorldCenter().y);
    b.angle = body.GetAngle();
    b.localCentre = glm::vec2(body.GetLocalCenter().x, body.GetLocalCenter().y);
    b.velocity = glm::vec2(body.GetLinearVelocity().x, body.GetLinearVelocity().y);
    b.angularVelocity = body.GetAngularVelocity();
    b.friction = slot.def.friction;
    if (body.GetType() == b2_dynamicBody && body.GetMass() > 0.0f) {
        b.invMass = 1.0f / body.GetMass();
        // Box2D's inertia is about the body origin; ours about the centre of mass.
        const float inertia = body.GetInertia() - body.GetMass() * glm::dot(b.localCentre, b.localCentre);
        b.invInertia = inertia > 0.0f ? 1.0f / inertia : 0.0f;
    }
    return b;
}

glm::vec2 toGlm(const b2Vec2& v) { return {v.x, v.y}; }

/// The fluid's copy of one of Box2D's joints (the kinds JointDef makes), its
/// anchors measured from the bodies' centres of mass.
fluid::StepJoint stepJointOf(const JointSlot& slot, const fluid::FluidBodyStep& out, std::uint32_t a,
                             std::uint32_t b) {
    fluid::StepJoint j;
    j.bodyA = a;
    j.bodyB = b;
    // Box2D's revolute, prismatic and weld joints spell these alike.
    auto anchors = [&](const auto& joint, fluid::StepJointKind kind) {
        j.kind = kind;
        j.anchorA = toGlm(joint.GetLocalAnchorA()) - out.bodies[a].localCentre;
        j.anchorB = toGlm(joint.GetLocalAnchorB()) - out.bodies[b].localCentre;
        j.referenceAngle = joint.GetReferenceAngle();
    };
    auto limitAndMotor = [&](const auto& joint, float maxMotor) {
        j.limit = joint.IsLimitEnabled();
        j.lower = joint.GetLowerLimit();
        j.upper = joint.GetUpperLimit();
        j.motor = joint.IsMotorEnabled();
        j.motorSpeed = joint.GetMotorSpeed();
        j.maxMotor = maxMotor;
    };
    switch (slot.def.kind) {
    case JointKind::Revolute: {
        const auto& r = static_cast<const b2RevoluteJoint&>(*slot.joint);
        anchors(r, fluid::StepJointKind::Revolute);
        limitAndMotor(r, r.GetMaxMotorTorque());
        break;
    }
    case JointKind::Prismatic: {
        const auto& p = static_cast<const b2PrismaticJoint&>(*slot.joint);
        anchors(p, fluid::StepJointKind::Prismatic);
        j.axisA = toGlm(p.GetLocalAxisA());
        limitAndMotor(p, p.GetMaxMotorForce());
        break;
    }
    case JointKind::Weld:
        anchors(static_cast<const b2WeldJoint&>(*slot.joint), fluid::StepJointKind::Weld);
        break;
    }
    return j;
}

/// Appends the body of `slotIndex` and its shapes to the fluid step's lists;
/// returns its index there.
std::uint32_t addBody(const BodyWorld& world, std::uint32_t slotIndex, fluid::FluidBodyStep& out) {
    const BodySlot& slot = world.bodies[slotIndex];
    const auto index = static_cast<std::uint32_t>(out.bodies.size());
    out.bodies.push_back(stepBodyOf(slot, slotIndex));
    for (const LocalShape& s : slot.fluidShapes) {
        out.shapeBody.push_back(index);
        out.shapeSource.push_back(&s);
    }
    return index;
}

/// The body slot of a Box2D body (BodyDef user data: the 1-based slot).
std::uint32_t slotOf(b2Body* body) { return static_cast<std::uint32_t>(body->GetUserData().pointer) - 1; }

/// The index of `slot` among out.bodies; a body not gathered (far from the
/// fluid) joins as an immovable body without shapes (its velocity kept: a
/// kinematic partner still moves), so what ties it to a gathered body holds
/// that one where Box2D would.
std::uint32_t indexOfPartner(const BodyWorld& world, std::uint32_t slot, std::vector<std::uint32_t>& indexOfSlot,
                             fluid::FluidBodyStep& out) {
    if (indexOfSlot[slot] == kNotGathered) {
        fluid::StepBody partner = stepBodyOf(world.bodies[slot], slot);
        partner.invMass = 0.0f;
        partner.invInertia = 0.0f;
        indexOfSlot[slot] = static_cast<std::uint32_t>(out.bodies.size());
        out.bodies.push_back(partner);
    }
    return indexOfSlot[slot];
}

/// The joints with a gathered body at either end, in creation order; a grab
/// (mouse joint) is left to Box2D. Calling thread only.
void gatherJoints(const BodyWorld& world, std::vector<std::uint32_t>& indexOfSlot, fluid::FluidBodyStep& out) {
    for (const JointSlot& slot : world.joints) {
        if (slot.joint == nullptr) continue;
        const std::uint32_t slotA = slotOf(slot.joint->GetBodyA()), slotB = slotOf(slot.joint->GetBodyB());
        if (indexOfSlot[slotA] == kNotGathered && indexOfSlot[slotB] == kNotGathered) continue;
        const std::uint32_t a = indexOfPartner(world, slotA, indexOfSlot, out);
        const std::uint32_t b = indexOfPartner(world, slotB, indexOfSlot, out);
        out.joints.push_back(stepJointOf(slot, out, a, b));
    }
}

/// What a particle of `f` moving at `fastest` can travel in a step of dt,
/// as a speed (m/s): its speed plus the step's gravity.
float reachSpeed(const fluid::FluidState& f, float fastest, float dt) {
    return fastest + glm::length(glm::vec2(f.def.gravity)) * dt;
}

/// The bodies near a 2D fluid whose particles lie in [lo, hi] and reach at
/// most `maxParticleSpeed` (reachSpeed): the 1-based slots, in creation
/// order, of those whose fixtures overlap the box grown by what a particle
/// travels in dt, h and a spacing. Calling thread only.
std::vector<std::uint32_t> slotsNear(BodyWorld& world, const fluid::FluidState& f, glm::vec2 lo, glm::vec2 hi,
                                     float maxParticleSpeed, float dt) {
    const float margin = f.h + f.def.spacing + maxParticleSpeed * dt;
    b2AABB box;
    box.lowerBound = b2Vec2(lo.x - margin, lo.y - margin);
    box.upperBound = b2Vec2(hi.x + margin, hi.y + margin);
    SlotCollector query;
    world.world.QueryAABB(&query, box);
    // Creation order, whatever order the tree answered in.
    std::sort(query.slots.begin(), query.slots.end());
    query.slots.erase(std::unique(query.slots.begin(), query.slots.end()), query.slots.end());
    return query.slots;
}

/// A fluid step's proxy emptied: no bodies, joints, shapes, contacts or impacts.
void clearStep(fluid::FluidBodyStep& out) {
    out.bodies.clear();
    out.joints.clear();
    out.shapeBody.clear();
    out.shapeSource.clear();
    out.contactCount = 0;
    for (std::vector<fluid::BodyImpact>& chunk : out.impacts) chunk.clear();
}

/// Gathers into `out` the bodies near a 2D fluid whose particles lie in
/// [lo, hi] and move at most `fastest` (m/s) (slotsNear). Calling thread
/// only. False when there are none (then the fluid ignores bodies this step).
bool gatherBodiesIn(BodyWorld& world, const fluid::FluidState& f, glm::vec2 lo, glm::vec2 hi, float fastest, float dt,
                    fluid::FluidBodyStep& out) {
    clearStep(out);
    if (f.def.dimension != 2 || world.alive == 0) return false;
    out.maxParticleSpeed = reachSpeed(f, fastest, dt);
    const std::vector<std::uint32_t> slots = slotsNear(world, f, lo, hi, out.maxParticleSpeed, dt);
    if (slots.empty()) return false;
    std::vector<std::uint32_t> indexOfSlot(world.bodies.size(), kNotGathered);
    for (std::uint32_t slot1 : slots) indexOfSlot[slot1 - 1] = addBody(world, slot1 - 1, out);
    gatherJoints(world, indexOfSlot, out);
    out.particleMass = f.def.density * f.def.spacing * f.def.spacing;
    out.particleInvMass = 1.0f / out.particleMass;
    return true;
}

/// gatherBodiesIn for the fluid's particles (their box and largest speed).
bool gatherBodies(BodyWorld& world, const fluid::FluidState& f, float dt, fluid::FluidBodyStep& out) {
    const std::vector<glm::vec2>& x = f.p2.position;
    if (f.def.dimension != 2 || x.empty()) {
        clearStep(out);
        return false;
    }
    glm::vec2 lo(x[0]), hi(x[0]);
    float fastest = 0.0f;
    for (std::size_t i = 0; i < x.size(); ++i) {
        lo = glm::min(lo, x[i]);
        hi = glm::max(hi, x[i]);
        fastest = std::max(fastest, glm::length(f.p2.velocity[i]));
    }
    return gatherBodiesIn(world, f, lo, hi, fastest, dt, out);
}

}  // namespace

fluid::JetMount FluidLink::jetMount(BodyId body) { return coupling::jetMount(bodies_, body); }

void FluidLink::applyRecoil(BodyId body, const fluid::JetMount& mount) {
    coupling::applyRecoil(bodies_, body, mount);
}

fluid::FluidBodyStep* FluidLink::gather(const fluid::FluidState& f, float dt) {
    if (bodies_ == nullptr || !gatherBodies(*bodies_, f, dt, bodies_->fluidStep)) return nullptr;
    return &bodies_->fluidStep;
}

fluid::FluidBodyStep* FluidLink::gatherNear(const fluid::FluidState& f, glm::vec2 lo, glm::vec2 hi, float fastest,
                                             float dt) {
    if (bodies_ == nullptr || !gatherBodiesIn(*bodies_, f, lo, hi, fastest, dt, bodies_->fluidStep)) return nullptr;
    return &bodies_->fluidStep;
}

fluid::FluidBodyStep* FluidLink::gatherMoved(const fluid::FluidState& f) {
    if (bodies_ == nullptr || f.bodiesAtEnd.empty()) return nullptr;
    fluid::FluidBodyStep& out = bodies_->fluidStep;
    out.bodies.clear();
    out.joints.clear();
    out.shapeBody.clear();
    out.shapeSource.clear();
    for (const fluid::BodyEndPose& end : f.bodiesAtEnd) {
        if (bodies_->bodies[end.slot].body != nullptr) addBody(*bodies_, end.slot, out);
    }
    return out.bodies.empty() ? nullptr : &out;
}

void FluidLink::exchange(const fluid::FluidBodyStep& step) { applyExchange(*bodies_, gatherExchange(step)); }

}  // namespace spindrift::coupling
