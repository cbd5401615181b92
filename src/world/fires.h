// Fires (include/spindrift/fires.h): the state the world keeps per fire and
// the update after each step.
#pragma once

#include <spindrift/fires.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <vector>

namespace spindrift {

struct World;

struct FireState {
    FireDef def;
    std::uint64_t strikes = 0;
    float flamesRate = 0.0f, smokeRate = 0.0f;  // the emitters' rates at creation (particles/s)
    // Flame and smoke shape centres in the body's frame at creation (m).
    glm::vec2 flamesOffset{0.0f}, smokeOffset{0.0f};
    float flamesZ = 0.0f, smokeZ = 0.0f;
};

/// After a step: the step's fluid strikes (EventQueue::stepStrikes) douse
/// each fire; its emitters' rates and positions follow (step length dt, s).
void updateFires(World& w, WorldId id, float dt);

}  // namespace spindrift
