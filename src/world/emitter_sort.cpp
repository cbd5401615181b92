// sortEmitterBackToFront: one emitter's live particles in back-to-front
// order, on the backend that holds them (world.h). Its own file, so that the
// world and the sort stay apart.
#include "effects/sort.h"
#include "world/world.h"
#include "gpu/gpu_sort.h"
#include "gpu/gpu_world.h"

#include <spindrift/world.h>

#include <cmath>

namespace spindrift {

std::vector<std::uint32_t> sortEmitterBackToFront(WorldId id, EmitterId emitterId, glm::vec3 eye,
                                                  glm::vec3 forward) {
    World& w = worldFromId(id);
    EmitterState& e = emitterFromId(w, emitterId);
    if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z)) {
        throw Error("sortEmitterBackToFront: eye must be finite");
    }
    const glm::vec3 unitForward = normalizeViewDirection(forward);
    if (w.gpu && !e.def.stateless) {
        return gpu::sortEmitterSlots(*w.gpu, emitterId.index - 1, eye, unitForward);
    }
    // The CPU holds the particles (or evaluates them): the live ones' positions
    // in slot order, as readParticles lists them.
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> slots;
    if (e.def.stateless) {
        ParticleSnapshot s = readParticles(id, emitterId);
        positions = std::move(s.position);
        slots = std::move(s.slot);
    } else {
        const ParticleArrays& p = e.particles;
        for (std::uint32_t i = 0; i < e.def.capacity; ++i) {
            if (p.age[i] >= 0.0f) {
                positions.push_back(p.position[i]);
                slots.push_back(i);
            }
        }
    }
    std::vector<std::uint32_t> order = sortBackToFront(positions, eye, forward);
    for (std::uint32_t& i : order) {
        i = slots[i];
    }
    return order;
}

}  // namespace spindrift
