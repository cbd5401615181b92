// spindrift public API: the world that owns emitters, forces and colliders.
#pragma once

#include <spindrift/effects.h>
#include <spindrift/fluid.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace spindrift {

enum class Backend : std::uint32_t { Cpu = 0, Vulkan = 1, Auto = 2 };

struct WorldDef {
    Backend backend = Backend::Cpu;
    /// Worker threads for the CPU backend; 0 = all hardware threads. Results
    /// are bit-identical for every thread count.
    std::uint32_t threads = 0;
    /// Seed of the counter-based random streams.
    std::uint32_t seed = 1;
};

/// Collision events of one step, per collider.
struct ColliderStepStats {
    ColliderId collider;
    std::uint64_t hits = 0;
};

struct StepStats {
    std::uint64_t step = 0;       ///< index of the step just taken (0-based)
    double time = 0.0;            ///< s, simulated time at the end of the step
    std::uint64_t alive = 0;      ///< live state-preserving particles after the step
    std::uint64_t born = 0;
    std::uint64_t died = 0;
    std::uint64_t collisions = 0;
    /// Births asked for beyond capacity in this step (spawn mode), dropped.
    std::uint64_t clamped = 0;
    std::vector<ColliderStepStats> colliderHits;
    /// One entry per fluid, in id order.
    std::vector<FluidStepStats> fluids;
    double milliseconds = 0.0;    ///< wall time of the step
};

/// A read-back copy of one emitter's live particles, in slot order.
struct ParticleSnapshot {
    std::vector<glm::vec3> position;
    std::vector<glm::vec3> velocity;
    std::vector<float> age;
    std::vector<float> lifetime;
    std::vector<float> size;
    std::vector<float> rotation;
    std::vector<glm::vec4> color;
    /// Birth serial of each particle: the n-th particle the emitter made.
    std::vector<std::uint32_t> birth;
    std::vector<std::uint32_t> slot;
    std::size_t count() const { return position.size(); }
};

WorldId createWorld(const WorldDef& def);
void destroyWorld(WorldId world);

EmitterId createEmitter(WorldId world, const EmitterDef& def);
ForceId createForce(WorldId world, const ForceDef& def);
ColliderId createCollider(WorldId world, const ColliderDef& def);
FlowFieldId createFlowField(WorldId world, const FlowFieldDef& def);

/// Advances every emitter by dt seconds (dt > 0).
StepStats stepWorld(WorldId world, float dt);

/// Simulated time (s) of the world.
double worldTime(WorldId world);

std::uint32_t emitterCount(WorldId world);
const EmitterDef& emitterDef(WorldId world, EmitterId emitter);
std::uint32_t colliderCount(WorldId world);

/// Copies the live particles of a state-preserving emitter; for a stateless
/// emitter evaluates its closed form at the world's current time.
ParticleSnapshot readParticles(WorldId world, EmitterId emitter);

/// Live particles of a stateless emitter at time t (s), from the closed form.
ParticleSnapshot evaluateStateless(const EmitterDef& def, std::uint32_t seed,
                                   std::uint32_t emitterIndex, float t);

/// Back-to-front order for alpha blending: indices into `positions`, the
/// farthest from the camera first, by view depth dot(p - eye, normalize(forward)).
/// Stable: equal depths (+0 and -0 included) keep index order; NaN depths come
/// last. Throws Error for a zero or non-finite `forward` or a non-finite `eye`.
/// Radix sort; each calling thread keeps 16 bytes of scratch per position
/// between calls.
std::vector<std::uint32_t> sortBackToFront(std::span<const glm::vec3> positions,
                                           glm::vec3 eye, glm::vec3 forward);

/// Back-to-front order of one emitter's live particles: their slots
/// (ParticleSnapshot::slot of readParticles), farthest first. The order is
/// exactly sortBackToFront over readParticles' positions, mapped to slots:
/// ties in slot order, NaN depths last. On the vulkan backend the sort runs on
/// the device, over the positions there, and only the live count and the order
/// (4 bytes per live particle) are copied back; stateless emitters are sorted
/// on the CPU from their closed form. Throws Error as sortBackToFront does.
std::vector<std::uint32_t> sortEmitterBackToFront(WorldId world, EmitterId emitter,
                                                  glm::vec3 eye, glm::vec3 forward);

/// Bytes copied between host and device memory since the world was created.
/// A GPU world moves particle data only on creation and readParticles; the
/// CPU backend moves nothing and returns zeros.
struct TransferStats {
    std::uint64_t bytesUploaded = 0;
    std::uint64_t bytesDownloaded = 0;
};
TransferStats transferStats(WorldId world);

/// Library version, "MAJOR.MINOR.PATCH".
const char* versionString();

}  // namespace spindrift
