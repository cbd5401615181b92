// The CPU constraint fluid: particle arrays, grid and neighbour lists of one
// fluid, and the passes of its step (fluid_step.cpp lists them in order). One
// source serves 2D and 3D: everything hot is a template on the dimension D.
#pragma once

#include "core/parallel.h"
#include "kernels/fluid.glsl"

#include <spindrift/fluid.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace spindrift::fluid {
struct FluidBodyStep;

/// A body's pose as a fluid step's copy of it ended the step.
struct BodyEndPose {
    std::uint32_t slot = 0;   // index in the world's bodies
    glm::vec2 centre{0.0f};   // m, centre of mass
    float angle = 0.0f;       // rad
};
struct StepContext;
}

namespace spindrift::fluid {

template <int D>
using Vec = glm::vec<D, float, glm::defaultp>;

/// Particles per chunk of the per-particle passes: fixed, so per-chunk sums
/// are combined in the same order for any thread count (determinism). 512,
/// not 2048: a 10k fluid then has 20 chunks, not 5, and with two threads
/// the setup's load was uneven (three chunks against two): 7.77 to 7.15 ms
/// a step on the 10k dam break, one thread unchanged (docs/performance.md).
inline constexpr std::size_t kParticleChunk = 512;
/// Grid cells per chunk of one colour of the parallel solver. 4, not 8: a
/// 10k fluid's colour then has about 18 chunks, not 9, and the slower of
/// two threads waits less at each colour's end (10k dam break, two
/// threads: 7.80 against 8.21 and 6.27 against 6.50 ms a step, medians of
/// alternating runs; one thread and 30k unchanged; 2 was no better). The
/// results do not depend on it: cells of one colour share no particle.
inline constexpr std::size_t kCellChunk = 4;

/// A particle's velocity and, with split impulses, its pseudo velocity (m/s,
/// solver.cpp), side by side: a sweep reads and writes both of a neighbour
/// with one load and one store (in 2D, 16 bytes: one SIMD register).
template <int D>
struct Motion {
    Vec<D> velocity;
    Vec<D> pseudo;
};
static_assert(sizeof(Motion<2>) == 16 && sizeof(Motion<3>) == 24);

/// Hot per-particle data, one array per attribute, kept in grid order (sorted
/// by cell every step so neighbours are close in memory).
template <int D>
struct Particles {
    std::vector<Vec<D>> position;  // m
    std::vector<Vec<D>> velocity;  // m/s
    std::vector<float> pressure;   // accumulated impulse (m/s), warm start of the next step
    std::vector<float> density;    // rho / rho0 at the last setup
    std::vector<std::uint32_t> id; // creation serial
    /// Sleeping (integratePositions): where the particle has stayed within
    /// the sleep circle's radius of (collide.cpp), and for how long (s); at
    /// sleepTime and above it sleeps.
    std::vector<Vec<D>> anchor;
    std::vector<float> still;
    /// The solve's working copy of the velocities (solver.cpp): filled from
    /// `velocity` when the solve starts and copied back when it ends; the
    /// contacts solved between its sweeps read and write it too. With split
    /// impulses its pseudo part is this substep's position-correction
    /// velocity (m/s), which the positions' pass then reads; it starts at
    /// zero every substep, so it is not kept in grid order.
    std::vector<Motion<D>> motion;

    std::size_t size() const { return position.size(); }
    /// Calls fn(array) for every array kept in particle order (all but
    /// motion), so a pass that reorders or removes particles misses none.
    template <class Fn>
    void forEachKept(Fn&& fn) {
        fn(position);
        fn(velocity);
        fn(pressure);
        fn(density);
        fn(id);
        fn(anchor);
        fn(still);
    }
    /// Keeps the particles for which keep(i) is true, in their order, and
    /// returns how many were removed (motion is only resized: it is refilled
    /// every substep).
    template <class Keep>
    std::size_t keepIf(Keep&& keep) {
        std::vector<std::uint8_t> kept(size());
        std::size_t n = 0;
        for (std::size_t i = 0; i < kept.size(); ++i) {
            kept[i] = keep(i) ? 1 : 0;
            n += kept[i];
        }
        forEachKept([&](auto& array) {
            std::size_t to = 0;
            for (std::size_t i = 0; i < kept.size(); ++i) {
                if (kept[i]) array[to++] = array[i];
            }
            array.resize(n);
        });
        if (motion.size() > n) motion.resize(n);
        return kept.size() - n;
    }
    void push(Vec<D> x, Vec<D> v, std::uint32_t serial) {
        position.push_back(x);
        velocity.push_back(v);
        pressure.push_back(0.0f);
        density.push_back(1.0f);
        id.push_back(serial);
        anchor.push_back(x);
        still.push_back(0.0f);
    }
};

/// One neighbour as the solver reads it (slide 52: stored with the particle so
/// the solver walks memory linearly): g = w * unit direction from the particle
/// to the neighbour, and the neighbour's index. 12 bytes in 2D, 16 in 3D.
template <int D>
struct Neighbour {
    Vec<D> g;
    std::uint32_t index;
};
static_assert(sizeof(Neighbour<2>) == 12 && sizeof(Neighbour<3>) == 16);

/// Uniform grid of cells 2h wide, each split into 2^D sub-cells ("quadrants",
/// slide 46-48) h wide. Particles are sorted by key = cell * 2^D + quadrant, so
/// every sub-cell is one contiguous range of particles: a particle searches
/// the 3^D sub-cells around its own, i.e. its own cell and only the quadrants
/// of the neighbouring cells that face its quadrant.
template <int D>
struct Grid {
    Vec<D> origin{0.0f};        // m, corner of sub-cell 0
    float h = 0.0f;             // sub-cell size (m)
    std::array<int, 3> cells{1, 1, 1};  // cells per axis (z = 1 in 2D)
    std::vector<std::uint32_t> keyStart;  // particles of key k: [keyStart[k], keyStart[k + 1])
    std::vector<std::uint32_t> key;       // per particle, in grid order
    /// Non-empty cells of each colour (cell coordinates' parities): cells of
    /// one colour are at least 2h apart, so their constraints share no
    /// particle and can be solved at the same time.
    std::array<std::vector<std::uint32_t>, 8> colourCells;
    std::vector<std::uint32_t> order;     // scratch: grid order -> previous index
    std::vector<std::uint32_t> counts;    // scratch
    // Scratch arrays of the gather into grid order, one for each particle
    // array of its type (swapped with the live ones).
    std::vector<std::vector<Vec<D>>> scratchVec;
    std::vector<std::vector<float>> scratchFloat;
    std::vector<std::vector<std::uint32_t>> scratchUint;
    std::vector<float> scratchMedian;  // medianAlong's
};

/// The colour of the cell at (cx, cy, cz) (Grid::colourCells): the parities
/// of its coordinates.
inline std::uint32_t colourOf(std::size_t cx, std::size_t cy, std::size_t cz) {
    return static_cast<std::uint32_t>((cx & 1) | ((cy & 1) << 1) | ((cz & 1) << 2));
}
/// The colour of cell `cell` (its index in the grid, x fastest).
template <int D>
inline std::uint32_t colourOfCell(const Grid<D>& g, std::size_t cell) {
    return colourOf(cell % g.cells[0], (cell / g.cells[0]) % g.cells[1],
                    cell / (static_cast<std::size_t>(g.cells[0]) * g.cells[1]));
}

/// Particles counted by the fastest closing speed of a neighbour (m/s, the rate at which their
/// distance shrinks; moving apart counts as 0), in bins kApproachBin wide,
/// the last one open-ended. Integer counts summed in chunk order, so the
/// substeps they pick are the same for any thread count.
inline constexpr float kApproachBin = kernels::SD_FLUID_APPROACH_BIN;
using ApproachHistogram = std::array<std::uint64_t, kernels::SD_FLUID_APPROACH_BINS>;
inline std::size_t approachBin(float speed) { return kernels::fluidApproachBin(speed); }

/// How crushed a sub-cell may be before the setup stops reading it, in
/// multiples of its particle count at rest. Far from any fluid the solver
/// holds (the 100k dam break's column, crushed before the compression rule,
/// reached a mean density of 1.41 times rest; the 10k dam break reads no
/// sub-cell past it, so its results are bit-identical), and it bounds the
/// pairs a crushed fluid costs to 3^D sub-cells of eight times the rest count
/// per particle (docs/fluid.md).
inline constexpr double kCrushedSubCell = 8.0;

/// The over-relaxation the sweeps apply (FluidDef::relaxation): the user's
/// with two iterations or more, 1 with one, where no later sweep takes an
/// over-relaxed visit's overshoot back. Over-relaxed, one iteration left the
/// 60-layer 2D tank standing 17 % above its fill line, and at h = 3.5
/// spacings the 2D resting tank still moving at 0.3 to 0.9 m/s after 3 s
/// (docs/fluid.md, "Eighth session of 2026-12-07"). Both backends read it.
inline float sweepRelaxation(const FluidDef& def) { return def.iterations >= 2 ? def.relaxation : 1.0f; }

/// Per-particle constraint data of one step (slide 35).
struct Constraints {
    std::vector<float> bias;      // m/s
    std::vector<float> invMass;   // 1 / A
    std::vector<std::uint32_t> count;  // neighbours stored
    std::vector<std::uint32_t> first;  // offset of the list in its chunk's array
    std::vector<std::uint32_t> listChunk;  // the array that holds the list (NeighbourChunks)
    /// Colliders' share (wall_density.cpp), found with the contacts: density
    /// (kernel-sum units) and g of the motionless ghost neighbours (w times
    /// the unit direction into the wall, summed).
    std::vector<float> wallDensity;
    std::vector<glm::vec3> wallGradient;
    /// Warm start (solver.cpp), gathered by the setup: the velocity change
    /// the previous pressure, scaled by warmFraction, gives each particle,
    /// and whether it could be gathered (every list symmetric: no overflow).
    std::vector<glm::vec3> warmVelocity;
    float warmFraction = 0.0f;
    bool warmGathered = false;
};

/// Neighbour lists of one step, compact (no fixed stride, so no overflow and
/// no memory for room that is rarely used): particle i's neighbours are
/// chunks[listChunk[i]][first[i] + k] for k < count[i] (Constraints).
/// One growable array per chunk of kParticleChunk particles and colour of
/// cell (Grid::colourCells; array chunk * 2^D + colour), so the setup fills
/// them in parallel without counting first, and a sweep, which visits the
/// cells colour by colour, reads each colour's lists as they were written.
template <int D>
using NeighbourChunks = std::vector<std::vector<Neighbour<D>>>;

template <int D>
inline const Neighbour<D>* neighbourList(const NeighbourChunks<D>& lists, const Constraints& c, std::size_t i) {
    return lists[c.listChunk[i]].data() + c.first[i];
}

struct FluidState;

/// The density a collider lends a particle at `distance` (m) from its surface,
/// and the size of the push it gives (sum of w times the normal part of the
/// direction to the ghosts): wall_density.cpp. Linear between kSize entries.
struct WallTable {
    static constexpr int kSize = 128;
    float start = 0.0f;  // m, distance of entry 0
    float step = 1.0f;   // m between entries
    std::array<float, kSize> density{};
    std::array<float, kSize> push{};
};
struct WallTerm {
    float density = 0.0f;
    float push = 0.0f;
};
/// Fills FluidState::wallTable for its spacing and h.
void buildWallTable(FluidState& f);
WallTerm wallTerm(const WallTable& t, float distance);
/// m: no entry of the table reaches this far or farther (twice its span, so
/// fluidWallPlace's quotient is past the last entry however it rounds): the
/// common case, decided without that division.
inline float wallBeyond(const WallTable& t) { return t.start + 2.0f * t.step * static_cast<float>(WallTable::kSize); }
/// Whether wallTerm at `distance` is not zero: the table reaches it.
inline bool wallReaches(const WallTable& t, float distance) {
    return distance < wallBeyond(t) && kernels::fluidWallPlace(distance, t.start, t.step, WallTable::kSize).entry >= 0;
}

/// A particle near a collider surface this step (found once per step; the
/// surface does not move while the solver iterates). 24 bytes.
struct Contact {
    kernels::FluidSurface surface;  // at the particle's position
    std::uint32_t particle;
};

struct Jet {
    FluidJetDef def;
    double openedAt = 0.0;  // s, world time when the jet was added
    double carry = 0.0;     // fraction of a particle owed from earlier steps
    std::uint64_t emitted = 0;
    /// aimFluidJet: the angle (rad, 2D) that replaces the aim keys while set.
    bool aimOverride = false;
    float overrideAngle = 0.0f;
};

struct FluidState {
    FluidDef def;
    float h = 0.0f;            // m
    float restDensity = 0.0f;  // kernel-sum units
    /// sum_n w_n dy_n^2 / r_n over the lattice's neighbours (m): the
    /// hydrostatic pressure's scale (latticeHydrostaticSum, fluidWarmCap).
    float hydrostaticSum = 0.0f;
    float radius = 0.0f;       // m, particle radius against colliders
    std::uint32_t maxNeighbours = 0;
    /// Most particles the setup reads from one sub-cell (h wide): kCrushedSubCell
    /// times the lattice's count at rest. Bounds the cost of a crushed fluid
    /// (neighbours.cpp).
    std::uint32_t subCellReadLimit = 0;
    std::uint32_t capacity = 0;
    std::uint32_t nextSerial = 0;
    std::vector<kernels::FluidPolygon> polygons;
    std::vector<Jet> jets;
    WallTable wallTable;

    Particles<2> p2;
    Particles<3> p3;
    Grid<2> g2;
    Grid<3> g3;
    NeighbourChunks<2> n2;
    NeighbourChunks<3> n3;
    Constraints constraints;
    std::vector<float> pseudoImpulse;  // accumulated bias impulse (m/s), per step
    /// Contacts of each chunk of kParticleChunk particles, in particle order.
    std::vector<std::vector<Contact>> contacts;
    std::uint64_t steps = 0;
    float pressedDepth = 0.0f;  // m, extent along gravity of the particles under pressure (integratePositions)
    /// Fastest closing speeds of the step's particles, all substeps so far:
    /// picks the next step's substeps (fluid_step.cpp).
    ApproachHistogram approach{};
    float lastMeanDensityError = 0.0f;  // of the previous step's last substep: picks the substeps
    int lastSubsteps = 1;
    int compressionSubsteps = 0;  // what the density error asks for (automaticSubsteps)
    std::uint32_t quietSteps = 0;
    float lastSubstep = 0.0f;   // s, the substep the pressure was solved for
    /// The rigid bodies near this 2D fluid during its step (body_contacts.h,
    /// filled by src/coupling); null outside stepFluid or when none are near.
    FluidBodyStep* bodies = nullptr;
    /// Where the step's copies of the bodies ended it, by slot:
    /// Box2D's step then moves the real ones, which the copies may not have
    /// followed (carryOutOfMovedBodies).
    std::vector<BodyEndPose> bodiesAtEnd;
    /// (particle id << 32 | body slot) of the last step's strikes, sorted: a
    /// drop that lands over two steps (the speculative contact slows it
    /// first) strikes once.
    std::vector<std::uint64_t> recentStrikes;

    template <int D> Particles<D>& particles() {
        if constexpr (D == 2) return p2; else return p3;
    }
    template <int D> Grid<D>& grid() {
        if constexpr (D == 2) return g2; else return g3;
    }
    template <int D> NeighbourChunks<D>& neighbours() {
        if constexpr (D == 2) return n2; else return n3;
    }
    std::size_t size() const { return def.dimension == 2 ? p2.size() : p3.size(); }
};

/// Smoothing length, rest density, limits and polygons from a validated def.
void initialiseFluid(FluidState& f);
/// Throws Error for a definition the solver cannot run.
void validateFluidDef(const FluidDef& def);
/// Rest density of an interior particle of a lattice at `spacing` (kernel-sum
/// units, the particle itself counting 1).
float latticeRestDensity(std::uint32_t dimension, float spacing, float h);
/// sum_n w_n dy_n^2 / r_n (m) over the neighbours of an interior particle of
/// a lattice at `spacing`: the hydrostatic pressure at depth d is
/// g dt d / this (kernels::fluidWarmCap).
float latticeHydrostaticSum(std::uint32_t dimension, float spacing, float h);

/// The warm start of a substep of dt (s), as both backends apply it: the
/// share of the last pressure (an impulse per substep, so the share scales
/// with the substep's length) and the cap on that pressure, at the pressed
/// depth of the last step (kernels::fluidWarmCap).
struct WarmStart {
    float fraction = 0.0f;
    float cap = 0.0f;  // m/s
};
inline WarmStart warmStartOf(const FluidState& f, float dt) {
    WarmStart w;
    w.fraction = f.lastSubstep > 0.0f ? f.def.warmStart * (dt / f.lastSubstep) : f.def.warmStart;
    w.cap = kernels::fluidWarmCap(glm::length(f.def.gravity), dt, std::max(f.pressedDepth, f.h), f.hydrostaticSum);
    return w;
}

void addBlock(FluidState& f, const FluidBlockDef& block);
/// Throws FieldError at "block[i].min" when a block of `def` (all of them, or
/// only block `only`) lays a particle inside one of `colliders` (planes,
/// spheres and boxes, by the solver's own surface test) or inside one of the
/// fluid's polygons.
void checkBlocksClear(const FluidDef& def, std::span<const ColliderDef> colliders,
                      std::size_t only = static_cast<std::size_t>(-1));
/// Where a jet's nozzle is this step: the pose and motion of the body it
/// rides on (identity and at rest for a jet fixed in the world); the recoil
/// its particles give the body comes back out.
struct JetMount {
    bool active = true;            // false: its body is gone, the jet is shut
    glm::vec2 origin{0.0f};        // m, the body's origin
    float angle = 0.0f;            // rad
    glm::vec2 centre{0.0f};        // m, the body's centre of mass
    glm::vec2 velocity{0.0f};      // m/s, of the centre of mass
    float angularVelocity = 0.0f;  // rad/s
    glm::vec2 nozzle{0.0f};        // out: m, world point of the nozzle
    glm::vec2 recoil{0.0f};        // out: N s, on the body at the nozzle
};
/// Direction angle (rad) of an aimed jet `t` s after it opened.
float jetAimAngle(const std::vector<FluidJetAimKey>& aim, float t);
/// Particles born during one step (the jets'), before they join a fluid's
/// particles: world positions (m, z = 0 in 2D), velocities (m/s) and
/// serials, in birth order.
struct Births {
    std::vector<glm::vec3> position;
    std::vector<glm::vec3> velocity;
    std::vector<std::uint32_t> id;
    std::size_t size() const { return id.size(); }
};
/// Emits into `out` (cleared first) the jets' particles of the step
/// [t0, t0 + dt) (one mount per jet), for a fluid of `alive` particles (the
/// births stop at FluidState::capacity); returns how many. Reads none of
/// the particles, so a fluid on the device emits without reading them back.
std::uint64_t emitJets(FluidState& f, std::size_t alive, double t0, float dt, std::vector<JetMount>& mounts,
                       Births& out);
/// Appends `births` to `f`'s particle arrays (at rest density, unpressed).
void appendBirths(FluidState& f, const Births& births);

/// Where buildGrid puts the grid for particles at `x` (m) with sub-cells `h`
/// m wide: sets g.h, g.origin and g.cells (uses g.scratchMedian), nothing
/// else. The device's grid (src/gpu/gpu_fluid_grid.h) takes its place from here.
template <int D> void placeGrid(WorkerPool& pool, const std::vector<Vec<D>>& x, float h, Grid<D>& g);
/// placeGrid's window for `n` particles whose box is [lo, hi]: sets g.h,
/// g.origin and g.cells and returns the axes (bit a) whose cells the budget
/// capped; placeGrid moves such an axis's origin to cappedWindowOrigin of
/// the particles' median (the device fluid, which knows only the box, too).
template <int D> std::uint32_t placeGridInBox(Vec<D> lo, Vec<D> hi, std::size_t n, float h, Grid<D>& g);
float cappedWindowOrigin(float median, float lo, float hi, float width);
/// The median of the particles' coordinate a (unique for any order of the
/// particles: deterministic); `scratch` holds the copy it partitions.
template <int D> float medianAlong(const std::vector<Vec<D>>& x, int a, std::vector<float>& scratch);

// The passes of one step, in order (fluid_step.cpp).
template <int D> void buildGrid(WorkerPool& pool, FluidState& f);
/// `countClosing`: add the particles' closing speeds to f.approach (the
/// substep rule's input); the step's first substep does, the others do not.
template <int D>
void setupConstraints(WorkerPool& pool, FluidState& f, float dt, bool countClosing, FluidStepStats& stats);
template <int D> void findContacts(WorkerPool& pool, FluidState& f, const StepContext& world, float dt);
/// Warm start and iterations; each sweep over the fluid constraints is
/// followed by one over the contacts (slide 51: contacts after the fluid), so
/// the walls' reactions reach the fluid within the step.
template <int D> void solveConstraints(WorkerPool& pool, FluidState& f, float dt);
template <int D> void solveContacts(WorkerPool& pool, FluidState& f, float dt);
/// Whether the path x0 -> x1 crosses one of the colliders the fluid meets
/// (plane, sphere, box) or ends inside one of its polygons.
bool crossesCollider(std::span<const kernels::ColliderParams> colliders, const FluidState& f, glm::vec3 x0,
                     glm::vec3 x1);
template <int D> void integratePositions(WorkerPool& pool, FluidState& f, const StepContext& world, float dt,
                                         FluidStepStats& stats);

/// The jets' particles born during the step [w.time, w.time + dt) for a
/// fluid of `alive` particles, into `out`, and their recoil given to the
/// bodies they sit on; returns how many. The CPU's step appends them to
/// `f`'s arrays (appendBirths), the device's to its buffers.
std::uint64_t emitStepJets(const StepContext& w, FluidState& f, std::size_t alive, float dt, Births& out);
/// The substeps of this step: FluidDef::substeps, or when it is 0 the count
/// from the last step's statistics (f.approach, which it empties,
/// f.pressedDepth, f.lastMeanDensityError, f.lastSubsteps), so the count is
/// deterministic, with what each rule asked for in `stats`; the device's
/// step (src/world/device_fluid.cpp) fills the same fields.
int substepsOfStep(FluidState& f, float dt, FluidStepStats& stats);
/// Whether a world collider is one the fluid meets (plane, sphere, box).
bool isFluidCollider(const kernels::ColliderParams& c);

FluidStepStats stepFluid(const StepContext& world, FluidState& f, FluidId id, float dt);
/// The end of a step with the bodies of f.bodies (null: none were near):
/// their end poses kept for the carry after Box2D's step, the strikes as
/// collision events, the impulses handed to Box2D; f.bodies cleared.
void endBodyStep(const StepContext& world, FluidState& f, FluidId id, FluidStepStats& stats);

}  // namespace spindrift::fluid
