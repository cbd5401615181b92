// The Box2D side of a fluid step: gathers the bodies near a fluid into the
// fluid's body proxy (fluid/body_contacts.h), and hands the impulses the step
// gave them back to Box2D (exchange.h), through the interface the fluid
// defines (fluid::BodyLink).
#pragma once

#include "fluid/body_link.h"

namespace spindrift::coupling {

struct BodyWorld;

/// The link of a world's bodies (null: none yet) for its fluid steps. Lives
/// for the hub's fluids stage; the proxy it fills is BodyWorld::fluidStep.
class FluidLink final : public fluid::BodyLink {
public:
    explicit FluidLink(BodyWorld* bodies) : bodies_(bodies) {}
    fluid::JetMount jetMount(BodyId body) override;
    void applyRecoil(BodyId body, const fluid::JetMount& mount) override;
    fluid::FluidBodyStep* gather(const fluid::FluidState& f, float dt) override;
    void exchange(const fluid::FluidBodyStep& step) override;
    /// After Box2D's step: the bodies of f.bodiesAtEnd at the poses Box2D
    /// left them, with their shapes (for fluid::carryOutOfMovedBodies), or
    /// null when there are none. Calling thread only.
    fluid::FluidBodyStep* gatherMoved(const fluid::FluidState& f);
    /// gather for 2D fluid `f` whose particles lie in [lo, hi] (m) and move
    /// at most `fastest` (m/s): the same box and query, for a fluid whose
    /// particles are on the device (its last report's box and speed).
    fluid::FluidBodyStep* gatherNear(const fluid::FluidState& f, glm::vec2 lo, glm::vec2 hi, float fastest, float dt);

private:
    BodyWorld* bodies_;
};

}  // namespace spindrift::coupling
