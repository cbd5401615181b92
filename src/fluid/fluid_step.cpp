// One step of one constraint fluid: a named list of passes (docs/design.md, the
// Sprinkle recipe of slides 12-13 and 35-51).
#include "fluid/body_contacts.h"
#include "fluid/body_link.h"
#include "fluid/fluid_state.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace spindrift::fluid {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

template <int D>
void stepPasses(const StepContext& w, FluidState& f, float dt, bool first, FluidStepStats& stats) {
    WorkerPool& pool = w.pool;
    Particles<D>& p = f.particles<D>();
    auto t = Clock::now();

    // External forces: gravity changes velocities before the constraints see
    // them, so pressure answers this step's weight (semi-implicit Euler).
    {
        const Vec<D> dv = Vec<D>(glm::vec3(f.def.gravity) * dt);
        pool.forChunks(p.size(), kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) p.velocity[i] += dv;
        });
    }

    // Grid: counting sort by cell and quadrant; arrays gathered into grid order.
    {
        buildGrid<D>(pool, f);
        stats.gridMs += msSince(t);
        t = Clock::now();
    }

    // Contacts: particles within reach of a collider surface, and (2D) of a
    // rigid body's shape at the body's pose of this substep.
    {
        findContacts<D>(pool, f, w, dt);
        if constexpr (D == 2) {
            if (f.bodies != nullptr) {
                beginSubstep(*f.bodies, f, f.g2, dt);
                findBodyContacts(pool, *f.bodies, f, f.g2, dt);
            }
        }
        stats.contactsMs += msSince(t);
        t = Clock::now();
    }

    // Neighbours and constraint setup: density (the colliders' share
    // included), bias, effective mass; in the step's first substep, the
    // closing speeds the next step's substep rule reads.
    {
        setupConstraints<D>(pool, f, dt, first, stats);
        stats.setupMs += msSince(t);
        t = Clock::now();
    }

    // Solve: warm start, then the iterations, each a sweep over the fluid
    // constraints followed by one over the contacts (slide 51).
    {
        solveConstraints<D>(pool, f, dt);
        stats.solveMs += msSince(t);
        t = Clock::now();
    }

    // Positions, never through a collider; the bodies' local poses move on
    // first, so no particle ends inside where a body now is.
    {
        if constexpr (D == 2) {
            if (f.bodies != nullptr) advanceBodies(*f.bodies, dt);
        }
        integratePositions<D>(pool, f, w, dt, stats);
        stats.integrateMs += msSince(t);
    }
}

// The step's strikes of fluid particles on bodies, as collision events on the
// world's queue (the application reads them there, at most eventCapacity a
// step; the fires read every one, EventQueue::stepStrikes). A pair that
// struck in the previous step or earlier in this one is not counted again.
void addImpactEvents(const StepContext& w, FluidState& f, const FluidBodyStep& s, FluidId fluid) {
    std::vector<ParticleEvent> events;
    std::vector<std::uint64_t> strikes;
    for (const std::vector<BodyImpact>& chunk : s.impacts) {
        for (const BodyImpact& impact : chunk) {
            const std::uint64_t key = (std::uint64_t{impact.particle} << 32) | impact.body;
            if (std::binary_search(f.recentStrikes.begin(), f.recentStrikes.end(), key) ||
                std::find(strikes.begin(), strikes.end(), key) != strikes.end()) {
                continue;
            }
            strikes.push_back(key);
            ParticleEvent e;
            e.kind = ParticleEventKind::Collision;
            e.step = w.stepIndex;
            e.fluid = fluid;
            e.body = BodyId{impact.body + 1};
            e.birth = impact.particle;
            e.position = glm::vec3(impact.position, 0.0f);
            e.speed = impact.speed;
            events.push_back(e);
        }
    }
    std::sort(strikes.begin(), strikes.end());
    f.recentStrikes = std::move(strikes);
    w.events.addEvents(events);
}

/// Depth (m) of the fluid's columns: the extent along gravity of the
/// particles under pressure at the end of the last step (a drop in free fall
/// or a stream leaving a ledge presses on nothing); before the first step,
/// of all the particles, which are about to press on each other.
template <int D>
float pressedDepth(const FluidState& f, const Particles<D>& p) {
    const float gravity = glm::length(f.def.gravity);
    if (!(gravity > 0.0f) || p.size() == 0) return 0.0f;
    if (f.steps > 0) return f.pressedDepth;
    const Vec<D> down = Vec<D>(f.def.gravity / gravity);
    float lo = 3.0e38f, hi = -3.0e38f;
    for (const Vec<D>& x : p.position) {
        lo = std::min(lo, glm::dot(x, down));
        hi = std::max(hi, glm::dot(x, down));
    }
    return hi - lo;
}

/// The closing speed (m/s) that all but kFastParticles of the last step's
/// particles stay under, each counted at the fastest approach of a neighbour
/// in the step's first substep (setupConstraints): the top of its histogram
/// bin. Not the fastest particle: a drop landing
/// from a splash at 10 m/s is one particle in thousands, meets the surface at
/// most once, and the density constraint pushes it back out; the bulk's
/// closing speeds are what the solver must resolve.
float closingSpeed(const ApproachHistogram& h) {
    constexpr double kFastParticles = 5e-3;
    std::uint64_t total = 0;
    for (std::uint64_t c : h) total += c;
    const auto allowed = static_cast<std::uint64_t>(kFastParticles * static_cast<double>(total));
    std::uint64_t above = 0;
    for (std::size_t b = h.size(); b-- > 0;) {
        above += h[b];
        if (above > allowed) return static_cast<float>(b + 1) * kApproachBin;
    }
    return 0.0f;
}

/// A substep count as a whole number, 0 to the most: NaN or inf after a
/// blow-up reads as the most. For each rule's report and the count taken.
std::uint32_t wantedSubsteps(float count) {
    return !(count < static_cast<float>(kFluidMaxSubsteps)) ? kFluidMaxSubsteps
           : count > 0.0f                                    ? static_cast<std::uint32_t>(count)
                                                             : 0u;
}

/// Substeps of this step when FluidDef::substeps is 0, from the last step's
/// statistics, so the count is deterministic:
/// - speed: two neighbours may close in on each other by at most kCourant h
///   per substep, or they pass through each other before any constraint sees
///   them (a dam break at 2 cm spacing and 60 Hz reaches 2 h per step and
///   explodes); from the last step's closing speeds (closingSpeed). Relative, not
///   absolute speed: a front that runs along the floor as one, or a drop in
///   free flight, needs no substeps (the colliders' contacts are speculative
///   and path-tested, so no speed passes through a wall);
/// - compression: a deep column crushes while it is still slow (the
///   pressure that holds it builds up over steps: 100k particles, 350 layers,
///   reached a 41 % mean density error at 1 to 5 substeps, 0.22 % at 16);
/// - depth: a column of fluid `layers` particles deep is held up by a pressure
///   that the solver only keeps when layers x g dt^2 / h stays below about 1
///   per substep (2D tanks released at rest, 1 substep of 1/60 s: 20 layers
///   at 2.5 cm spacing (0.74) rest; 20 layers at 1 cm (1.85) and 60 at 2.5 cm
///   (2.2) collapse; 60 at 1 cm (5.6) collapses at 2 substeps and rests at
///   4). At one iteration the solver holds half that depth (the 20-layer
///   tank at 2.5 cm kept moving at 0.1 to 0.2 m/s at one substep and rests
///   at two);
/// - compression, the backstop: a step that ended more than
///   compressionLimit over rest density asks for the count that would have
///   brought it to aim (the error falls about as 1 / substeps^2); that count
///   holds until a smaller one would have done for kHoldSteps steps in a row,
///   then comes down by a quarter (dam break of 10k particles: 5.4 substeps
///   on average, against 7.4 when it doubled and came down by one per 30
///   steps, with the same number density at 6 s). 1.5 % and 0.75 % with two
///   or three iterations (the default is two), 1 % and 0.5 % otherwise: the
///   one-iteration resting tank kept moving at 0.056 m/s under the looser
///   pair, and with eight iterations the resting tank's start stays under
///   1.5 %, so it settles at 1 substep 1 % compressed and comes to rest
///   anywhere from 2 to 3.8 s after release as rounding falls (seven runs
///   whose gravity differed by up to 3 units in the last place; issue 12
///   item 4 asks for rest by 3 s). Under 1 % every one of them rested by
///   2.5 s; with four iterations or more the user has chosen accuracy over
///   speed (docs/fluid.md, "Substeps").
int automaticSubsteps(FluidState& f, float dt, FluidStepStats& stats) {
    constexpr float kCourant = 0.4f;
    const bool oneIteration = f.def.iterations < 2;
    const bool loose = f.def.iterations == 2 || f.def.iterations == 3;
    const float compressionLimit = loose ? 0.015f : 0.01f;
    const float depthNumber = oneIteration ? 0.4f : 0.8f;
    const float aim = loose ? 0.0075f : 0.005f;
    constexpr std::uint32_t kHoldSteps = 10;
    constexpr int kMaxSubsteps = static_cast<int>(kFluidMaxSubsteps);
    const float reach = closingSpeed(f.approach) * dt;
    f.approach.fill(0);
    const float bySpeed = std::ceil(reach / (kCourant * f.h));  // NaN or inf after a blow-up: the most
    const float depth = f.def.dimension == 2 ? pressedDepth<2>(f, f.p2) : pressedDepth<3>(f, f.p3);
    const float layers = depth / f.def.spacing;
    const float byDepth = std::ceil(std::sqrt(layers * glm::length(f.def.gravity) * dt * dt / (depthNumber * f.h)));
    // The compression of a step falls about as 1 / substeps^2 (each substep
    // lets the fluid sink by g dt^2 / substeps^2 before the pressure answers):
    // the count that would have brought the last step's error to aim.
    const float error = f.lastMeanDensityError;
    const float needed = std::ceil(static_cast<float>(f.lastSubsteps) * std::sqrt(std::max(error, 0.0f) / aim));
    if (!(error <= compressionLimit)) {
        // NaN or inf after a blow-up: the most.
        f.compressionSubsteps = std::isfinite(needed) ? static_cast<int>(std::min(
                                                            std::max(static_cast<float>(f.compressionSubsteps), needed),
                                                            static_cast<float>(kMaxSubsteps)))
                                                      : kMaxSubsteps;
        f.quietSteps = 0;
    } else if (needed < static_cast<float>(f.compressionSubsteps)) {
        if (++f.quietSteps >= kHoldSteps) {
            const int drop = std::max(1, f.compressionSubsteps / 4);
            f.compressionSubsteps = std::max(f.compressionSubsteps - drop, static_cast<int>(needed));
            f.quietSteps = 0;
        }
    } else {
        f.quietSteps = 0;
    }
    const float wanted = std::max({bySpeed, byDepth, static_cast<float>(f.compressionSubsteps)});
    stats.substepsForSpeed = wantedSubsteps(bySpeed);
    stats.substepsForDepth = wantedSubsteps(byDepth);
    stats.substepsForCompression = static_cast<std::uint32_t>(f.compressionSubsteps);
    return static_cast<int>(std::max(1u, wantedSubsteps(wanted)));
}

}  // namespace

int substepsOfStep(FluidState& f, float dt, FluidStepStats& stats) {
    return f.def.substeps > 0 ? static_cast<int>(f.def.substeps) : automaticSubsteps(f, dt, stats);
}

std::uint64_t emitStepJets(const StepContext& w, FluidState& f, std::size_t alive, float dt, Births& out) {
    // Emission: the jets' particles born during this step join before binning.
    // A jet on a body moves with it and gives it the recoil.
    std::vector<JetMount> mounts;
    for (const Jet& jet : f.jets) mounts.push_back(w.bodies.jetMount(jet.def.body));
    const std::uint64_t born = emitJets(f, alive, w.time, dt, mounts, out);
    for (std::size_t j = 0; j < f.jets.size(); ++j) w.bodies.applyRecoil(f.jets[j].def.body, mounts[j]);
    return born;
}

FluidStepStats stepFluid(const StepContext& w, FluidState& f, FluidId id, float dt) {
    FluidStepStats stats;
    stats.fluid = id;
    Births births;
    stats.born = emitStepJets(w, f, f.size(), dt, births);
    appendBirths(f, births);
    const int substeps = substepsOfStep(f, dt, stats);
    const float h = dt / static_cast<float>(substeps);
    // Rigid bodies near a 2D fluid: gathered from Box2D now, solved against as
    // local copies during the substeps, and given their impulses at the end.
    f.bodies = w.bodies.gather(f, dt);
    for (int k = 0; k < substeps; ++k) {
        if (f.def.dimension == 2) {
            stepPasses<2>(w, f, h, k == 0, stats);
        } else {
            stepPasses<3>(w, f, h, k == 0, stats);
        }
    }
    endBodyStep(w, f, id, stats);
    f.lastMeanDensityError = static_cast<float>(stats.meanDensityError);
    f.lastSubsteps = substeps;
    stats.substeps = static_cast<std::uint32_t>(substeps);
    stats.particles = f.size();
    f.steps += 1;
    return stats;
}

void endBodyStep(const StepContext& w, FluidState& f, FluidId id, FluidStepStats& stats) {
    f.bodiesAtEnd.clear();
    if (f.bodies == nullptr) {
        f.recentStrikes.clear();
        return;
    }
    // Still bodies too: the carry may not pass through their edges.
    for (const StepBody& b : f.bodies->bodies) f.bodiesAtEnd.push_back({b.slot, b.centre, b.angle});
    std::sort(f.bodiesAtEnd.begin(), f.bodiesAtEnd.end(),
              [](const BodyEndPose& a, const BodyEndPose& b) { return a.slot < b.slot; });
    addImpactEvents(w, f, *f.bodies, id);
    w.bodies.exchange(*f.bodies);
    stats.bodyContacts = f.bodies->contactCount;
    f.bodies = nullptr;
}

}  // namespace spindrift::fluid
