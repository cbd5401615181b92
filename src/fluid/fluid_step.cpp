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
void stepPasses(const StepContext& w, FluidState& f, float dt, FluidStepStats& stats) {
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

    // Neighbours and constraint setup: density, bias, effective mass.
    {
        setupConstraints<D>(pool, f, dt, stats);
        stats.setupMs += msSince(t);
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
// world's queue (the fires and the application read them there). A pair that
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

}  // namespace

FluidStepStats stepFluid(const StepContext& w, FluidState& f, FluidId id, float dt) {
    FluidStepStats stats;
    stats.fluid = id;
    // Emission: the jets' particles born during this step join before binning.
    // A jet on a body moves with it and gives it the recoil.
    std::vector<JetMount> mounts;
    for (const Jet& jet : f.jets) mounts.push_back(w.bodies.jetMount(jet.def.body));
    stats.born = emitJets(f, w.time, dt, mounts);
    for (std::size_t j = 0; j < f.jets.size(); ++j) w.bodies.applyRecoil(f.jets[j].def.body, mounts[j]);
    // Substeps: a particle may move at most kCourant h per substep, or it
    // would pass through its neighbours before any constraint sees them
    // (a dam break at 2 cm spacing and 60 Hz reaches 2 h per step and
    // explodes). Chosen from the last step's top speed plus what gravity adds,
    // so the count is deterministic.
    constexpr float kCourant = 0.4f;
    constexpr int kMaxSubsteps = 8;
    const float reach = (f.lastMaxSpeed + glm::length(f.def.gravity) * dt) * dt;
    const float wanted = std::ceil(reach / (kCourant * f.h));  // NaN or inf after a blow-up: the most
    const int substeps = f.def.substeps > 0 ? static_cast<int>(f.def.substeps)
                         : wanted <= 1.0f   ? 1
                         : wanted < static_cast<float>(kMaxSubsteps) ? static_cast<int>(wanted)
                                                                    : kMaxSubsteps;
    const float h = dt / static_cast<float>(substeps);
    // Rigid bodies near a 2D fluid: gathered from Box2D now, solved against as
    // local copies during the substeps, and given their impulses at the end.
    f.bodies = w.bodies.gather(f, dt);
    if (f.bodies == nullptr) {
        f.recentStrikes.clear();
    }
    for (int k = 0; k < substeps; ++k) {
        if (f.def.dimension == 2) {
            stepPasses<2>(w, f, h, stats);
        } else {
            stepPasses<3>(w, f, h, stats);
        }
    }
    if (f.bodies != nullptr) {
        addImpactEvents(w, f, *f.bodies, id);
        w.bodies.exchange(*f.bodies);
        stats.bodyContacts = f.bodies->contactCount;
        f.bodies = nullptr;
    }
    f.lastMaxSpeed = static_cast<float>(stats.maxSpeed);
    stats.substeps = static_cast<std::uint32_t>(substeps);
    stats.particles = f.size();
    f.steps += 1;
    return stats;
}

}  // namespace spindrift::fluid
