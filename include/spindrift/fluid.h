// spindrift public API: constraint fluids (Sprinkle style). Each fluid particle
// is a velocity constraint that keeps the density around it at rest; fluids
// live in a world and stepWorld() steps them with the emitters. The solver runs
// on the CPU in either backend's world (a Vulkan world's fluids too), as the
// README says.
#pragma once

#include <spindrift/export.h>

#include <spindrift/bodies.h>
#include <spindrift/effects.h>

#include <cstdint>
#include <string>
#include <vector>

namespace spindrift {

struct FluidId { std::uint32_t index = 0; };

/// Where a fluid is solved (docs/fluid.md, "On the device").
enum class FluidBackend : std::uint32_t {
    /// The device in a Vulkan world on a hardware GPU (never lavapipe, which
    /// runs shaders on the CPU cores slower than the CPU solver) for the
    /// Parallel solver; else the CPU.
    Auto = 0,
    Cpu = 1,
    /// The device of a Vulkan world (WorldDef::backend), lavapipe included,
    /// rigid bodies coupled there too; the renderer draws it from the
    /// device's buffers. An Error in a CPU world and for the Sequential
    /// solver.
    Gpu = 2,
};

enum class FluidSolver : std::uint32_t {
    /// Gauss-Seidel over four (2D) or eight (3D) colour groups of grid cells,
    /// cells of one colour in parallel; bit-identical for any thread count.
    Parallel = 0,
    /// One thread, particles in grid order, exactly the slides' loop.
    Sequential = 1,
};

/// A box of fluid filled with particles on a lattice at the fluid's spacing:
/// the first particle half a spacing inside `min`, as many as fit before `max`.
/// In 2D the z coordinates are ignored.
struct FluidBlockDef {
    glm::vec3 min{0.0f};
    glm::vec3 max{1.0f};
    glm::vec3 velocity{0.0f};  ///< m/s, initial velocity of every particle
};

/// One key of a 2D jet's aim: `time` s after the jet opens it points `angle`
/// rad counter-clockwise from the x axis (the body's x axis when it rides one).
struct FluidJetAimKey {
    float time = 0.0f;   ///< s, >= 0
    float angle = 0.0f;  ///< rad
};

/// A nozzle that emits particles at `rate` per second with `speed` along
/// `direction`, spread over a segment (2D) or disk (3D) of `radius` across the
/// direction at the fluid's spacing.
struct FluidJetDef {
    glm::vec3 position{0.0f};
    glm::vec3 direction{1.0f, 0.0f, 0.0f};
    float speed = 2.0f;    ///< m/s, > 0
    float rate = 200.0f;   ///< particles/s, >= 0
    float radius = 0.0f;   ///< m; 0: a single stream
    float start = 0.0f;    ///< s, world time at which it opens
    float duration = -1.0f;///< s; < 0: never closes
    /// 2D only: the direction over time, linear between keys (times
    /// non-decreasing), held before the first and after the last; each
    /// particle leaves in the direction of its birth time. Empty: `direction`.
    std::vector<FluidJetAimKey> aim;
    /// 2D only: the body the nozzle rides on (index 0: none). Then `position`,
    /// `direction` and the aim are in the body's frame, particles leave with
    /// the body's velocity at the nozzle added, and the body takes the recoil
    /// (each particle's mass times its speed relative to the nozzle). A jet
    /// whose body is destroyed stops.
    BodyId body;
};

/// A convex polygon obstacle in the xy plane, extruded along z; vertices in
/// either winding (at most 16, not all on one line).
struct FluidPolygonDef {
    std::vector<glm::vec2> vertices;
};

/// Limits of a FluidDef, named once: validateFluidDef (and so createFluid,
/// setFluidSolver and the scene loader) checks them, the viewer's panel uses
/// them (src/fluid/fluid_rules.h).
inline constexpr std::uint32_t kFluidMinIterations = 1;
inline constexpr std::uint32_t kFluidMaxIterations = 16;
/// Bounds of FluidDef::relaxation: 1 is plain Gauss-Seidel; above about 1.25
/// the sweeps overshoot and the fluid settles expanded (docs/fluid.md).
inline constexpr float kFluidMinRelaxation = 1.0f;
inline constexpr float kFluidMaxRelaxation = 1.5f;
/// Least velocity steering (FluidDef::baumgarte). Below about this the
/// density drifts uncorrected and a crushed splash blows up: launches into a
/// tank gained up to 1e33 times their energy at 0, and once at 0.002 (none
/// of 144 at 0.005, 0.01 or the default; docs/fluid.md).
inline constexpr float kFluidMinBaumgarte = 0.01f;
/// Substeps per world step when given (0: automatic).
inline constexpr std::uint32_t kFluidMaxSubsteps = 16;
/// Neighbours kept per particle (FluidDef::maxNeighbours).
inline constexpr std::uint32_t kFluidMaxNeighbours = 1024;
/// Most particles a fluid may ask for (FluidDef::capacity), as an emitter.
inline constexpr std::uint32_t kFluidMaxCapacity = kEmitterMaxCapacity;

struct FluidDef {
    std::string name;
    /// 2: particles in the xy plane; 3: in space.
    std::uint32_t dimension = 2;
    /// Particle spacing (m) of blocks and jets; the particle's radius for
    /// collisions is half of it.
    float spacing = 0.02f;
    /// Smoothing length h (m); 0: 3.5 x spacing in 2D (about 36 neighbours;
    /// at 2 x spacing, 12 neighbours, a resting tank's density error is
    /// several times larger, see docs/performance.md), 2.5 x spacing in 3D.
    float smoothing = 0.0f;
    /// Solver iterations per substep, kFluidMinIterations (1) to kFluidMaxIterations (16).
    std::uint32_t iterations = 2;
    /// Over-relaxation of the iterations (successive over-relaxation: each
    /// visit applies this many times the impulse that would solve its own
    /// constraint alone), in [kFluidMinRelaxation (1), kFluidMaxRelaxation
    /// (1.5)]. 2 iterations at 1.2 hold a deep tank as 4 at 1 did, in 22 to
    /// 32 % less time a step (docs/fluid.md, "Over-relaxed sweeps"). With 1
    /// iteration it is not applied (the sweep is plain): no later sweep
    /// takes the overshoot back, and the fluid settles expanded.
    float relaxation = 1.2f;
    /// Velocity steering toward the rest density (slide 34): the bias is
    /// (rho0 - rho) x baumgarte x h / dt, in [kFluidMinBaumgarte (0.01), 1].
    float baumgarte = 0.05f;
    /// Fraction of the previous step's pressure applied before iterating
    /// (warm starting, in [0, 1]); lets few iterations carry a deep column.
    /// Under gravity each particle's carried pressure is capped at five
    /// times the hydrostatic pressure at the bottom of the fluid, so an
    /// impact's pressure is not applied twice (docs/fluid.md).
    float warmStart = 1.0f;
    /// Most neighbours kept per particle, at most kFluidMaxNeighbours (1024);
    /// more are counted as overflows and ignored. 0 (the default): no limit
    /// (the lists are compact and grow).
    std::uint32_t maxNeighbours = 0;
    FluidSolver solver = FluidSolver::Parallel;
    /// Where the fluid is solved; the device runs the Parallel order only.
    FluidBackend backend = FluidBackend::Auto;
    /// Solve most of the bias on a pseudo velocity that moves particles this
    /// step and is then dropped (split impulses), so correcting density errors
    /// adds little kinetic energy; false: the slides' bias in the velocity.
    bool splitImpulse = true;
    /// Substeps per world step, 1 to kFluidMaxSubsteps (16); 0: automatic (up
    /// to 16): enough that neighbours close in by at most 0.4 h per substep,
    /// that the deepest column is held up, and more after a step compressed
    /// over 1.5 % (two or three iterations; 1 % otherwise; docs/fluid.md).
    std::uint32_t substeps = 0;
    /// Sleeping, as Box2D's bodies and FleX's particles: a particle that
    /// stays within `sleepSpeed` x `sleepTime` (m), and within half a
    /// `spacing`, of where it was for `sleepTime` (s) stops (velocity 0,
    /// position held) until the solver gives it more than twice `sleepSpeed`.
    /// A tank at rest then rests; flow slower than about `sleepSpeed` (m/s)
    /// stops too, and so do waves whose particles swing by less than half a
    /// spacing. 0: never sleeps.
    float sleepSpeed = 0.05f;
    float sleepTime = 0.5f;  ///< s
    glm::vec3 gravity{0.0f, -9.81f, 0.0f};  ///< m/s^2
    /// Mass density of the fluid, for its exchange of momentum with rigid
    /// bodies: a particle's mass is density x spacing^dimension. 2D: kg/m^2,
    /// areal, like a body's density (1000: water in a slab 1 m thick); 3D:
    /// kg/m^3 (3D fluids do not touch bodies yet).
    float density = 1000.0f;
    /// Coulomb friction coefficient of particles against colliders (0:
    /// frictionless, as the slides' particle body); against a rigid body the
    /// coefficient is sqrt(this x the body's friction), as Box2D mixes them.
    float friction = 0.0f;
    /// Most particles at once, at most kFluidMaxCapacity; jets stop emitting
    /// when it is reached. 0: the blocks' particles plus 10,000 per jet.
    std::uint32_t capacity = 0;
    /// Rest density in units of the kernel sum (a lone particle has density
    /// 1); 0: that of an interior particle of a block at `spacing`, so a block
    /// starts at rest.
    float restDensity = 0.0f;
    std::vector<FluidBlockDef> blocks;
    std::vector<FluidJetDef> jets;
    /// Obstacles for this fluid only; the world's plane, sphere and box
    /// colliders act on every fluid too.
    std::vector<FluidPolygonDef> polygons;
};

/// What one step of one fluid did. Densities are measured at the start of the
/// step's solve; the error of a particle is rho / rho0 - 1.
struct FluidStepStats {
    FluidId fluid;
    std::uint64_t particles = 0;
    std::uint64_t born = 0;             ///< particles emitted by jets this step
    /// Mean over particles of max(rho / rho0 - 1, 0): compression only, since a
    /// free surface is under-dense by nature and the constraint never pulls.
    double meanDensityError = 0.0;
    double maxDensityError = 0.0;       ///< max of rho / rho0 - 1
    double meanNeighbours = 0.0;
    double maxSpeed = 0.0;              ///< m/s, after the step
    /// Neighbours dropped, all substeps: over maxNeighbours, or not read in a
    /// region crushed past 8 times the particles per area (volume) at rest,
    /// which bounds what a crushed fluid costs (docs/fluid.md).
    std::uint64_t neighbourOverflows = 0;
    std::uint32_t substeps = 1;         ///< substeps taken (density stats: the last one's)
    /// What each rule of the automatic count asked for this step (docs/fluid.md,
    /// "Substeps"); `substeps` is the most of them, 1 to 16. All 0 when
    /// FluidDef::substeps fixes the count. Speed: neighbours close in by at
    /// most 0.4 h a substep; depth: the columns under pressure; compression:
    /// the backstop on the last step's mean density error.
    std::uint32_t substepsForSpeed = 0, substepsForDepth = 0, substepsForCompression = 0;
    bool device = false;                ///< solved on the device (FluidBackend)
    std::uint64_t bodyContacts = 0;     ///< particle-body contacts, all substeps
    /// Particles removed because their position or velocity became NaN or
    /// infinite (all substeps), in the substep where it arose.
    std::uint64_t nonFinite = 0;
    /// Wall time (ms) of each pass, summed over the substeps: binning,
    /// neighbours and constraint setup, contact search, solver, integration.
    double gridMs = 0.0, setupMs = 0.0, contactsMs = 0.0, solveMs = 0.0, integrateMs = 0.0;
};

/// A copy of a fluid's particles, in creation order.
struct FluidSnapshot {
    std::vector<glm::vec3> position;  ///< m (z = 0 in 2D)
    std::vector<glm::vec3> velocity;  ///< m/s
    /// rho / rho0 at the start of the last step (1: rest density).
    std::vector<float> density;
    /// Accumulated constraint impulse of the last step (m/s, >= 0): the
    /// pressure, in velocity units.
    std::vector<float> pressure;
    std::vector<std::uint32_t> id;    ///< creation serial
    std::size_t count() const { return position.size(); }
};

/// Throws FieldError, naming the field as a scene file spells it ("iterations",
/// "jet[0].speed") and the rule it broke, for a definition createFluid rejects.
SPINDRIFT_API void validateFluidDef(const FluidDef& def);

/// Adds a fluid to a CPU world with its blocks, jets and polygons; throws Error
/// for a bad definition or a Vulkan world.
SPINDRIFT_API FluidId createFluid(WorldId world, const FluidDef& def);
/// Adds a block of particles now (at the world's current time).
SPINDRIFT_API void addFluidBlock(WorldId world, FluidId fluid, const FluidBlockDef& block);
/// Adds a jet; its start time is world time.
SPINDRIFT_API void addFluidJet(WorldId world, FluidId fluid, const FluidJetDef& jet);

/// Removes the particles within `radius` m of `centre` (2D: in the xy plane)
/// now, the viewer's eraser; returns how many. The others keep their ids, so
/// readFluid's ids may then skip values.
SPINDRIFT_API std::uint32_t removeFluid(WorldId world, FluidId fluid, glm::vec3 centre, float radius);
/// Adds particles now, moving at `velocity`, at the points within `radius` m
/// of `centre` of the lattice a block from the origin would fill, except
/// where a particle is nearer than one spacing: pouring where the fluid
/// already is adds nothing (the viewer's brush). Stops at the capacity.
/// Returns how many were added. Throws Error for a radius over 100 spacings.
SPINDRIFT_API std::uint32_t pourFluid(WorldId world, FluidId fluid, glm::vec3 centre, float radius,
                                      glm::vec3 velocity = glm::vec3(0.0f));

/// Changes a fluid's solver settings from the next step on (the viewer's
/// panel): iterations (kFluidMinIterations to kFluidMaxIterations) and
/// baumgarte (in [kFluidMinBaumgarte, 1]) as in FluidDef.
/// Throws Error, changing nothing, for values FluidDef rejects.
SPINDRIFT_API void setFluidSolver(WorldId world, FluidId fluid, std::uint32_t iterations, float baumgarte);

/// Where a 2D jet's nozzle is now (m, world) and the angle (rad) of the frame
/// its aim is measured in: its body's, or 0 without one.
struct FluidJetPose {
    glm::vec2 nozzle{0.0f};
    float frameAngle = 0.0f;
};
/// Points 2D jet `jet` (0-based, in definition order) at `angle` rad in its
/// frame, replacing its aim keys until releaseFluidJetAim (the viewer's mouse
/// aim). Throws Error for a 3D fluid, a jet it does not have or a non-finite angle.
SPINDRIFT_API void aimFluidJet(WorldId world, FluidId fluid, std::uint32_t jet, float angle);
SPINDRIFT_API void releaseFluidJetAim(WorldId world, FluidId fluid, std::uint32_t jet);
SPINDRIFT_API FluidJetPose fluidJetPose(WorldId world, FluidId fluid, std::uint32_t jet);

/// A solver-independent measure of compression, the number-density ratio:
/// for each particle, the number of particles (itself included) within a
/// fixed radius R, divided by that count at an interior point of a lattice at
/// the fluid's spacing (an untouched block reads 1 inside, less near its
/// surface; a fluid squeezed to 0.9 of its spacing in 2D reads about 1/0.81).
/// R is 3.78 spacings in 2D (reference 45) and 3.91 in 3D (reference 251): no
/// lattice shell lies within 2 % of R, and the reference equals the ball's
/// volume in particles, so a disordered fluid at rest reads about 1 as well
/// (src/fluid/number_density.cpp says why). Counted on its own grid, not the
/// solver's neighbour lists or kernel, so engines compare.
struct FluidNumberDensity {
    double median = 0.0;  ///< median ratio over particles (0: no particles)
    double p95 = 0.0;     ///< 95th percentile (nearest rank)
    std::uint32_t reference = 0;  ///< the lattice count the ratio divides by
    float radius = 0.0f;          ///< R, m
    std::uint64_t particles = 0;
};
/// Measures it now over the fluid's current particles: O(n log n), one
/// thread, on demand (not part of a step).
SPINDRIFT_API FluidNumberDensity measureFluidNumberDensity(WorldId world, FluidId fluid);

SPINDRIFT_API std::uint32_t fluidCount(WorldId world);
SPINDRIFT_API const FluidDef& fluidDef(WorldId world, FluidId fluid);
/// Rest density (kernel-sum units) the fluid uses, derived or given.
SPINDRIFT_API float fluidRestDensity(WorldId world, FluidId fluid);
SPINDRIFT_API FluidSnapshot readFluid(WorldId world, FluidId fluid);

}  // namespace spindrift
