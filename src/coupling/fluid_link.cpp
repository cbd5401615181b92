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

/// Gathers the bodies whose fixtures overlap the fluid's particles (grown by
/// what they can travel in dt) through b2World::QueryAABB. Calling thread
/// only. False when there are none (then the fluid ignores bodies this step).
bool gatherBodies(BodyWorld& world, const fluid::FluidState& f, float dt, fluid::FluidBodyStep& out) {
    out.bodies.clear();
    out.shapeBody.clear();
    out.shapeSource.clear();
    out.contactCount = 0;
    for (std::vector<fluid::BodyImpact>& chunk : out.impacts) chunk.clear();
    const std::vector<glm::vec2>& x = f.p2.position;
    if (f.def.dimension != 2 || world.alive == 0 || x.empty()) return false;
    glm::vec2 lo(x[0]), hi(x[0]);
    float fastest = 0.0f;
    for (std::size_t i = 0; i < x.size(); ++i) {
        lo = glm::min(lo, x[i]);
        hi = glm::max(hi, x[i]);
        fastest = std::max(fastest, glm::length(f.p2.velocity[i]));
    }
    // What a particle can travel this step (m/s): its speed plus the step's gravity.
    out.maxParticleSpeed = fastest + glm::length(glm::vec2(f.def.gravity)) * dt;
    const float margin = f.h + f.def.spacing + out.maxParticleSpeed * dt;
    b2AABB box;
    box.lowerBound = b2Vec2(lo.x - margin, lo.y - margin);
    box.upperBound = b2Vec2(hi.x + margin, hi.y + margin);
    SlotCollector query;
    world.world.QueryAABB(&query, box);
    if (query.slots.empty()) return false;
    // Creation order, whatever order the tree answered in.
    std::sort(query.slots.begin(), query.slots.end());
    query.slots.erase(std::unique(query.slots.begin(), query.slots.end()), query.slots.end());
    for (std::uint32_t slot1 : query.slots) {
        const BodySlot& slot = world.bodies[slot1 - 1];
        const b2Body& body = *slot.body;
        fluid::StepBody b;
        b.slot = slot1 - 1;
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
        const auto index = static_cast<std::uint32_t>(out.bodies.size());
        out.bodies.push_back(b);
        for (const LocalShape& s : slot.fluidShapes) {
            out.shapeBody.push_back(index);
            out.shapeSource.push_back(&s);
        }
    }
    out.particleMass = f.def.density * f.def.spacing * f.def.spacing;
    out.particleInvMass = 1.0f / out.particleMass;
    return true;
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

void FluidLink::exchange(const fluid::FluidBodyStep& step) { applyExchange(*bodies_, gatherExchange(step)); }

}  // namespace spindrift::coupling
