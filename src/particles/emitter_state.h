// One emitter's particles as structure-of-arrays (hot data, one array per
// attribute) plus its cold definition and emission bookkeeping.
//
// Bytes per slot: position 12, velocity 12, age 4, lifetime 4, rotation 4,
// angular velocity 4, birth serial 4 = 44 B. Mass is one value per emitter
// (EmitterDef::mass), so it lives in the parameters, not here. Colour and size
// are not stored: they are pure functions of the emitter, the birth serial,
// the age and the velocity, restored where they are read
// (kernels::restoreLook, src/kernels/derived.glsl), as on the Vulkan backend.
#pragma once

#include "kernels/types.glsl"

#include <spindrift/effects.h>

#include <cstdint>
#include <vector>

namespace spindrift {

struct ParticleArrays {
    std::vector<glm::vec3> position;
    std::vector<glm::vec3> velocity;
    std::vector<float> age;  // < 0: unborn (recycle) or dead (spawn)
    std::vector<float> lifetime;
    std::vector<float> rotation;
    std::vector<float> angularVelocity;
    std::vector<std::uint32_t> birth;
    /// EmitterDef::trail's positions, points per slot (src/kernels/trail.glsl);
    /// empty without a trail. Not sized by resize.
    std::vector<glm::vec3> trail;

    void resize(std::size_t n);
};
inline constexpr std::size_t kBytesPerSlot = 12 + 12 + 4 * 5;
static_assert(kBytesPerSlot == 44);

struct EmitterState {
    EmitterDef def;
    kernels::EmitterParams params;
    ParticleArrays particles;
    /// Spawn mode: free slots, the next to use at the back.
    std::vector<std::uint32_t> freeSlots;
    /// Serial of the next particle born (spawn mode).
    std::uint32_t nextSerial = 0;
    /// Fraction of a particle owed by the rate, carried between steps.
    double emissionCarry = 0.0;
    std::uint64_t alive = 0;
    /// Sub-emitters following this emitter: bit k for event kind k
    /// (SD_SPAWN_ON_* of src/kernels/types.glsl).
    std::uint32_t requestKinds = 0;
    /// This step's spawn requests per kind, at most the capacity each, in slot
    /// order (CPU backend; the Vulkan backend keeps them on the device).
    std::vector<kernels::SpawnRequest> requests[kernels::SD_SPAWN_EVENT_KINDS];
    /// This step's requests per kind beyond the capacity: not kept, their
    /// births counted as clamped by the sub-emitter.
    std::uint64_t requestsDropped[kernels::SD_SPAWN_EVENT_KINDS] = {};
    /// Ring index of the trails' newest points (src/kernels/trail.glsl),
    /// advanced before each step by the world, for both backends.
    std::uint32_t trailHead = 0;
    /// An emitter riding a body (EmitterDef::body): its shape's centre and
    /// direction in the body's frame; `def` holds them placed in the world.
    glm::vec3 mountCentre{0.0f};
    glm::vec3 mountDirection{0.0f, 1.0f, 0.0f};
};

}  // namespace spindrift
