// spindrift public API: the world that owns emitters, forces and colliders.
#pragma once

#include <spindrift/export.h>

#include <spindrift/bodies.h>
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
    /// Most collision and death events recorded per step (takeEvents); those
    /// beyond are dropped and counted, never written. 0: no events recorded.
    /// Events wait for takeEvents up to 32 steps' worth (32 x eventCapacity);
    /// past that the oldest are dropped and counted, down to 16 steps' worth,
    /// so a world whose events are never taken does not grow. Fires count
    /// every strike whatever this keeps.
    std::uint32_t eventCapacity = 4096;
    /// Vulkan backend: steps the GPU may run behind the CPU, 1 to 3. With 1,
    /// stepWorld waits for its step and reports its counts. With 2 (the
    /// default) or 3, stepWorld returns once the step is submitted, and the
    /// counts and events of a step arrive that many steps minus one later,
    /// without the CPU ever waiting on the GPU in the loop (see
    /// StepStats::countedSteps and flushWorld). The CPU backend ignores it.
    std::uint32_t framesInFlight = 2;
    /// m/s^2, gravity of the rigid bodies (bodies.h), each component within
    /// kMaxBodyGravity. Each fluid has its own (FluidDef::gravity), so a
    /// scene may float bodies without gravity.
    glm::vec2 bodyGravity{0.0f, -9.81f};
};

/// Shortest and longest step (s) stepWorld takes. Under a nanosecond the
/// square of a fluid substep leaves single precision's normal range (a step
/// of 1e-45 s made NaN grid cells); tests spawn particles without moving
/// them with 1e-9 s steps. Over a second births owed for the step and the
/// fluid's substeps stop meaning anything for a real-time engine.
inline constexpr double kMinStep = 1.0e-9;
inline constexpr double kMaxStep = 1.0;
/// Largest body gravity component (m/s^2), a thousand g: 3e38 turned the
/// bodies' bounds into infinities the fluid's grid could not bin.
inline constexpr float kMaxBodyGravity = 1.0e4f;

/// Collision events of one step, per collider.
struct ColliderStepStats {
    ColliderId collider;
    std::uint64_t hits = 0;
};

/// What a step reports. The counts (alive, born, died, collisions, clamped,
/// colliderHits) cover the `countedSteps` steps ending with `lastCountedStep`:
/// on the CPU backend and on Vulkan with one frame in flight that is exactly
/// the step just taken; with more frames in flight it is the step the GPU
/// finished meanwhile (none for the first steps; flushWorld returns the rest).
struct StepStats {
    std::uint64_t step = 0;       ///< index of the step just taken (0-based)
    double time = 0.0;            ///< s, simulated time at the end of the step
    std::uint32_t countedSteps = 0;
    std::uint64_t lastCountedStep = 0;
    std::uint64_t alive = 0;      ///< live state-preserving particles after the step
    std::uint64_t born = 0;
    std::uint64_t died = 0;
    std::uint64_t collisions = 0;
    /// Effect particles removed because a number of theirs became NaN or
    /// infinite in this step (an attractor 1e-7 m away with strength 1e30):
    /// taken out where it arises, not counted in `died`, never stored. Fluid
    /// particles: FluidStepStats::nonFinite.
    std::uint64_t nonFinite = 0;
    /// Rigid bodies frozen in this step because their pose or velocity became
    /// NaN or infinite: each is put back at its last finite pose, made static
    /// with zero velocity and stays so; the rest of the world goes on.
    std::vector<BodyId> frozenBodies;
    /// Births asked for beyond capacity in this step (spawn mode), dropped.
    /// They are counted, never stored: memory does not grow with the rate or
    /// dt. Saturates at the largest std::uint64_t (a rate of 3e38 per second).
    std::uint64_t clamped = 0;
    std::vector<ColliderStepStats> colliderHits;
    /// One entry per fluid, in id order.
    std::vector<FluidStepStats> fluids;
    double bodiesMs = 0.0;  ///< wall time of the Box2D step and the impulse exchange
    double milliseconds = 0.0;    ///< wall time of the step
    /// Vulkan: device time (ms) of the counted steps, from timestamps at the
    /// start and end of each step's submission; 0 on the CPU backend or where
    /// the device's queue has no timestamps.
    double deviceMilliseconds = 0.0;
};

enum class ParticleEventKind : std::uint32_t {
    Collision = 0,  ///< the particle hit `collider` (an impact, not a resting contact)
    Death = 1,      ///< the particle died: of age, or killed by a collision
};

/// One collision or death of a state-preserving particle, or a fluid
/// particle striking a rigid body (then `fluid` and `body` are set and
/// `emitter` and `collider` are 0).
struct ParticleEvent {
    ParticleEventKind kind = ParticleEventKind::Collision;
    std::uint64_t step = 0;  ///< step in which it happened
    EmitterId emitter;
    /// Fluid impacts: the fluid, and the body struck faster than
    /// kFluidImpactSpeed along its surface normal (a resting or sliding
    /// contact is not an impact). `birth` is then the particle's id.
    FluidId fluid;
    BodyId body;
    /// Collision: the collider hit. Death: the first collider hit in the same
    /// step (the killer, when collisions kill), or index 0 when none was.
    ColliderId collider;
    std::uint32_t birth = 0;  ///< birth serial of the particle in its emitter
    glm::vec3 position{0.0f}; ///< m, where the particle was at the end of the step
    /// m/s, the particle's speed at the start of the step (for a particle born
    /// in the step: at its end), e.g. to scale an impact sound.
    float speed = 0.0f;
};

/// Events handed to the application by takeEvents.
struct EventBatch {
    /// In step order. Within a step the CPU backend lists them in emitter and
    /// slot order; the GPU's order within a step is unspecified.
    std::vector<ParticleEvent> events;
    /// Events lost because a step had more than WorldDef::eventCapacity, or
    /// because more than 32 steps' worth waited for takeEvents (the oldest).
    std::uint64_t dropped = 0;
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
    /// Trail positions (EmitterDef::trail) of every particle in turn,
    /// `trailPoints` each, the newest (its current position) first; empty
    /// without a trail.
    std::vector<glm::vec3> trail;
    std::uint32_t trailPoints = 0;
    std::size_t count() const { return position.size(); }
};

SPINDRIFT_API WorldId createWorld(const WorldDef& def);
SPINDRIFT_API void destroyWorld(WorldId world);

SPINDRIFT_API EmitterId createEmitter(WorldId world, const EmitterDef& def);
SPINDRIFT_API ForceId createForce(WorldId world, const ForceDef& def);
SPINDRIFT_API ColliderId createCollider(WorldId world, const ColliderDef& def);
SPINDRIFT_API FlowFieldId createFlowField(WorldId world, const FlowFieldDef& def);

/// Advances every emitter by dt seconds (dt > 0).
SPINDRIFT_API StepStats stepWorld(WorldId world, float dt);

/// Events of the steps whose counts have been reported so far (see
/// StepStats), and those dropped; each is handed out once.
SPINDRIFT_API EventBatch takeEvents(WorldId world);

/// Waits until the GPU has finished every submitted step and returns the
/// counts not yet reported (countedSteps may be 0); their events become
/// available to takeEvents. The CPU backend has nothing pending.
SPINDRIFT_API StepStats flushWorld(WorldId world);

/// Live changes to a state-preserving emitter, from the next step on (the
/// viewer's panel). Only what acts at birth can change, so that particles
/// already alive are untouched and the CPU and Vulkan backends agree: the
/// spawn rate (particles per second, >= 0; ignored by recycle emitters) and
/// the launch speed range. The vulkan backend waits for the steps in flight
/// and re-uploads the emitter's parameters. Throws Error for a stateless
/// emitter (its closed form covers all time) or a value EmitterDef rejects;
/// nothing changes then.
SPINDRIFT_API void setEmitterRate(WorldId world, EmitterId emitter, float rate);
SPINDRIFT_API void setEmitterSpeed(WorldId world, EmitterId emitter, FloatRange speed);
/// Moves the emitter's spawn shape (its centre, m): where particles are born
/// from now on, as setEmitterRate. For an emitter riding a body
/// (EmitterDef::body) the centre is in the body's frame and takes effect at
/// the next step.
SPINDRIFT_API void setEmitterPosition(WorldId world, EmitterId emitter, glm::vec3 centre);

/// Approach speed (m/s) above which a fluid particle touching a body makes a
/// collision event.
inline constexpr float kFluidImpactSpeed = 0.5f;

/// Simulated time (s) of the world.
SPINDRIFT_API double worldTime(WorldId world);

SPINDRIFT_API std::uint32_t emitterCount(WorldId world);
SPINDRIFT_API const EmitterDef& emitterDef(WorldId world, EmitterId emitter);
SPINDRIFT_API std::uint32_t colliderCount(WorldId world);

/// Copies the live particles of a state-preserving emitter; for a stateless
/// emitter evaluates its closed form at the world's current time.
SPINDRIFT_API ParticleSnapshot readParticles(WorldId world, EmitterId emitter);

/// Live particles of a stateless emitter at time t (s), from the closed form.
SPINDRIFT_API ParticleSnapshot evaluateStateless(const EmitterDef& def, std::uint32_t seed,
                                                 std::uint32_t emitterIndex, float t);

/// Back-to-front order for alpha blending: indices into `positions`, the
/// farthest from the camera first, by view depth dot(p - eye, normalize(forward)).
/// Stable: equal depths (+0 and -0 included) keep index order; NaN depths come
/// last. Throws Error for a zero or non-finite `forward` or a non-finite `eye`.
/// Radix sort; each calling thread keeps 16 bytes of scratch per position
/// between calls.
SPINDRIFT_API std::vector<std::uint32_t> sortBackToFront(std::span<const glm::vec3> positions,
                                                         glm::vec3 eye, glm::vec3 forward);

/// Back-to-front order of one emitter's live particles: their slots
/// (ParticleSnapshot::slot of readParticles), farthest first. The order is
/// exactly sortBackToFront over readParticles' positions, mapped to slots:
/// ties in slot order, NaN depths last. On the vulkan backend the sort runs on
/// the device, over the positions there, and only the live count and the order
/// (4 bytes per live particle) are copied back; stateless emitters are sorted
/// on the CPU from their closed form. Throws Error as sortBackToFront does.
SPINDRIFT_API std::vector<std::uint32_t> sortEmitterBackToFront(WorldId world, EmitterId emitter,
                                                                glm::vec3 eye, glm::vec3 forward);

/// Bytes copied between host and device memory since the world was created.
/// A GPU world moves particle data only on creation and readParticles (and,
/// for a fluid on the device, a 336-byte report a substep, its particles
/// when readFluid reads them, and edits; a rendered frame reads back 16
/// bytes and 48 a particle that throws a splash); the CPU backend moves
/// nothing and returns zeros.
struct TransferStats {
    std::uint64_t bytesUploaded = 0;
    std::uint64_t bytesDownloaded = 0;
};
SPINDRIFT_API TransferStats transferStats(WorldId world);

/// Library version, "MAJOR.MINOR.PATCH".
SPINDRIFT_API const char* versionString();

}  // namespace spindrift
