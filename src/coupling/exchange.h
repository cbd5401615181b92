// The exchange of impulses between a fluid and the rigid bodies at the end of
// a fluid step (docs/design.md: coupling only at step boundaries, through explicit
// records): what the particles gave each body, applied with Box2D's public
// API on the calling thread.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace spindrift::fluid {
struct FluidBodyStep;
}

namespace spindrift::coupling {

struct BodyWorld;

/// The total impulse one fluid step gave one body. 16 bytes.
struct ExchangeRecord {
    std::uint32_t slot;         // index in BodyWorld::bodies
    glm::vec2 linearImpulse;    // N s, at the centre of mass
    float angularImpulse;       // N m s, about the centre of mass
};
static_assert(sizeof(ExchangeRecord) == 16);

/// One record per dynamic body the step touched, in creation order.
std::vector<ExchangeRecord> gatherExchange(const fluid::FluidBodyStep& step);
/// Applies the records to the Box2D bodies.
void applyExchange(BodyWorld& bodies, const std::vector<ExchangeRecord>& records);

}  // namespace spindrift::coupling
