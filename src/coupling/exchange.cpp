// Impulse exchange: the contact solver summed, per body, the opposite of every
// impulse it gave a particle (body_contacts.cpp, in one fixed order, so the
// sums are the same for any thread count); here they become records and are
// handed to Box2D. The body's velocity then equals the local copy the fluid
// solved against, and total momentum is what it was, up to float rounding.
#include "coupling/exchange.h"

#include "coupling/body_world.h"

namespace spindrift::coupling {

std::vector<ExchangeRecord> gatherExchange(const fluid::FluidBodyStep& step) {
    std::vector<ExchangeRecord> records;
    for (const fluid::StepBody& b : step.bodies) {
        if (b.invMass > 0.0f && (b.linearImpulse != glm::vec2(0.0f) || b.angularImpulse != 0.0f)) {
            records.push_back({b.slot, b.linearImpulse, b.angularImpulse});
        }
    }
    return records;
}

void applyExchange(BodyWorld& bodies, const std::vector<ExchangeRecord>& records) {
    for (const ExchangeRecord& r : records) {
        b2Body* body = bodies.bodies[r.slot].body;
        body->ApplyLinearImpulseToCenter(b2Vec2(r.linearImpulse.x, r.linearImpulse.y), true);
        body->ApplyAngularImpulse(r.angularImpulse, true);
    }
}

}  // namespace spindrift::coupling
