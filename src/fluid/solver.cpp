// The fluid constraint solver (slides 36-39): sequential impulses, one visit
// per particle per iteration, warm started with the previous step's pressure.
// Two orders: the slides' single loop over all particles (Sequential), and
// Gauss-Seidel over colour groups of grid cells (Parallel), where cells of one
// colour share no particle and are visited at the same time.
//
// Split impulses (FluidDef::splitImpulse, on by default): most of the
// Baumgarte bias (slide 34) is solved on a second, pseudo velocity that moves
// particles this step and is then forgotten, as rigid-body solvers do for
// penetration; the real velocity keeps a quarter of it (kRealBiasShare). With the bias in the real
// velocity (the slides' form) every density fluctuation of a disordered
// packing becomes kinetic energy: a tank at rest keeps boiling at about 0.2
// m/s (measured; docs/performance.md).
#include "fluid/fluid_state.h"

#include <algorithm>

namespace spindrift::fluid {
namespace {

/// Split impulses: density deficit (fraction of rho0) below which an
/// under-dense particle gets no approach allowance in the real velocity.
/// Inside the fluid the density of a disordered packing fluctuates by a few
/// per cent; letting gravity pull neighbours toward every slightly
/// under-dense particle kept a resting tank moving at 0.16 m/s (measured),
/// while surface and splash particles, far below rest density, still fall
/// together.
constexpr float kAllowanceSlop = 0.1f;
/// Split impulses: share of an over-dense particle's bias kept in the real
/// velocity (the rest goes to the pseudo velocity). All in the pseudo one
/// leaves a resting tank quietest but lets a falling column compress: the
/// real velocity then has nothing that pushes back and the positional
/// correction lags (dam break of 10k particles, 0.5 s: 1.8 % mean density
/// error); all in the real one is the slides' form (0.35 %, but a resting tank
/// jitters at 0.25 m/s). A quarter (measured, baumgarte 0.05): 0.56 % and
/// 0.11 m/s.
constexpr float kRealBiasShare = 0.25f;

template <int D>
struct SolverView {
    Vec<D>* velocity;
    Vec<D>* pseudo;  // null: bias on the real velocity
    float* pressure;
    float* pseudoImpulse;
    const std::vector<Neighbour<D>>* lists;  // per chunk (NeighbourChunks)
    const std::uint32_t* first;
    const glm::vec3* wall;  // the colliders' ghosts' g (wall_density.cpp)
    const float* bias;
    const float* invMass;
    const std::uint32_t* count;
    float allowanceSlop;  // m/s of bias an under-dense particle's allowance starts above
};

/// Applies impulse `delta` of particle i's constraint to `v`: v_n += g delta on
/// every neighbour, v_i -= sum g delta (Newton's third law, slide 39).
template <int D>
inline void applyImpulse(const SolverView<D>& s, Vec<D>* v, std::size_t i, float delta) {
    const Neighbour<D>* list = s.lists[i / kParticleChunk].data() + s.first[i];
    Vec<D> self = Vec<D>(s.wall[i]) * delta;  // the motionless ghosts take no impulse
    for (std::uint32_t k = 0; k < s.count[i]; ++k) {
        const Vec<D> impulse = list[k].g * delta;
        v[list[k].index] += impulse;
        self += impulse;
    }
    v[i] -= self;
}

/// C' of particle i's constraint over velocities v (slide 36).
template <int D>
inline float rateOf(const SolverView<D>& s, const Vec<D>* v, std::size_t i) {
    const Neighbour<D>* list = s.lists[i / kParticleChunk].data() + s.first[i];
    const Vec<D> vi = v[i];
    const std::uint32_t count = s.count[i];
    // Two chains of additions (even and odd neighbours), summed at the end:
    // one chain of 28 dependent additions bound the sweep (measured).
    float even = -glm::dot(Vec<D>(s.wall[i]), vi);  // ghosts at rest
    float odd = 0.0f;
    std::uint32_t k = 0;
    for (; k + 1 < count; k += 2) {
        even += glm::dot(list[k].g, v[list[k].index] - vi);
        odd += glm::dot(list[k + 1].g, v[list[k + 1].index] - vi);
    }
    if (k < count) even += glm::dot(list[k].g, v[list[k].index] - vi);
    return even + odd;
}

/// One visit of particle i's constraint (slide 36, signs in fluid.glsl).
template <int D>
inline void visit(const SolverView<D>& s, std::size_t i) {
    if (s.pseudo == nullptr) {
        const kernels::FluidImpulse r =
            kernels::fluidSolveImpulse(rateOf<D>(s, s.velocity, i), s.bias[i], s.invMass[i], s.pressure[i]);
        s.pressure[i] = r.accumulated;
        if (r.delta != 0.0f) applyImpulse<D>(s, s.velocity, i, r.delta);
        return;
    }
    // The bias splits by sign: an under-dense particle's positive bias lets
    // its neighbours approach (it relaxes the constraint, no energy added) and
    // stays with the real velocity, past a slop; an over-dense particle's
    // negative bias pushes apart, which is the pseudo velocity's job. Only an
    // over-dense particle has a pseudo constraint, so both are solved in one
    // pass over its neighbours (half the memory traffic of two visits).
    const float bias = s.bias[i];
    if (bias >= 0.0f) {
        const kernels::FluidImpulse r = kernels::fluidSolveImpulse(
            rateOf<D>(s, s.velocity, i), std::max(bias - s.allowanceSlop, 0.0f), s.invMass[i], s.pressure[i]);
        s.pressure[i] = r.accumulated;
        if (r.delta != 0.0f) applyImpulse<D>(s, s.velocity, i, r.delta);
        return;
    }
    const Neighbour<D>* list = s.lists[i / kParticleChunk].data() + s.first[i];
    const std::uint32_t count = s.count[i];
    const Vec<D> vi = s.velocity[i];
    const Vec<D> pi = s.pseudo[i];
    const Vec<D> wall(s.wall[i]);
    float rate = -glm::dot(wall, vi);
    float pseudoRate = -glm::dot(wall, pi);
    float rateOdd = 0.0f;
    float pseudoOdd = 0.0f;
    std::uint32_t k = 0;
    for (; k + 1 < count; k += 2) {
        const std::uint32_t j = list[k].index;
        const std::uint32_t l = list[k + 1].index;
        rate += glm::dot(list[k].g, s.velocity[j] - vi);
        pseudoRate += glm::dot(list[k].g, s.pseudo[j] - pi);
        rateOdd += glm::dot(list[k + 1].g, s.velocity[l] - vi);
        pseudoOdd += glm::dot(list[k + 1].g, s.pseudo[l] - pi);
    }
    if (k < count) {
        const std::uint32_t j = list[k].index;
        rate += glm::dot(list[k].g, s.velocity[j] - vi);
        pseudoRate += glm::dot(list[k].g, s.pseudo[j] - pi);
    }
    rate += rateOdd;
    pseudoRate += pseudoOdd;
    const kernels::FluidImpulse r = kernels::fluidSolveImpulse(rate, bias * kRealBiasShare, s.invMass[i], s.pressure[i]);
    const kernels::FluidImpulse q =
        kernels::fluidSolveImpulse(pseudoRate, bias * (1.0f - kRealBiasShare), s.invMass[i], s.pseudoImpulse[i]);
    s.pressure[i] = r.accumulated;
    s.pseudoImpulse[i] = q.accumulated;
    Vec<D> self = wall * r.delta;
    Vec<D> pseudoSelf = wall * q.delta;
    for (std::uint32_t k = 0; k < count; ++k) {
        const std::uint32_t j = list[k].index;
        const Vec<D> impulse = list[k].g * r.delta;
        const Vec<D> push = list[k].g * q.delta;
        s.velocity[j] += impulse;
        s.pseudo[j] += push;
        self += impulse;
        pseudoSelf += push;
    }
    s.velocity[i] -= self;
    s.pseudo[i] -= pseudoSelf;
}

/// The accumulated impulse particle i starts the solve with: the previous
/// substep's, scaled, or none for a particle without neighbours. Such a
/// particle has nothing to push, and a pressure kept through its flight was
/// applied in full to the neighbours it met on landing: after a crush
/// (baumgarte near 0) a splash particle carried 2.9e4 m/s of it, and the
/// landing's warm start raised the fluid's kinetic energy from 578 to 1.5e9
/// (J/kg summed; docs/fluid.md, "Launches into tanks").
template <int D>
inline float warmPressure(const SolverView<D>& s, std::size_t i, float fraction) {
    return s.count[i] != 0 ? s.pressure[i] * fraction : 0.0f;
}

/// Warm start: the previous step's pressure, scaled, applied along this step's
/// directions, and taken as the starting accumulated impulse.
template <int D>
inline void warmStart(const SolverView<D>& s, std::size_t i, float fraction) {
    const float start = warmPressure<D>(s, i, fraction);
    s.pressure[i] = start;
    if (start != 0.0f) {
        applyImpulse<D>(s, s.velocity, i, start);
    }
}

/// Runs fn(i) for every particle, colour group by colour group; the cells of
/// one colour in parallel, the particles of one cell in grid order.
template <int D, class Fn>
void forEachByColour(WorkerPool& pool, const Grid<D>& g, Fn&& fn) {
    constexpr std::uint32_t kQuadrants = 1u << D;
    for (int colour = 0; colour < (1 << D); ++colour) {
        const std::vector<std::uint32_t>& cells = g.colourCells[colour];
        pool.forChunks(cells.size(), kCellChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t c = begin; c < end; ++c) {
                const std::uint32_t first = g.keyStart[cells[c] * kQuadrants];
                const std::uint32_t last = g.keyStart[(cells[c] + 1) * kQuadrants];
                for (std::uint32_t i = first; i < last; ++i) {
                    fn(i);
                }
            }
        });
    }
}

}  // namespace

template <int D>
void solveConstraints(WorkerPool& pool, FluidState& f, float dt) {
    Particles<D>& p = f.particles<D>();
    const std::size_t n = p.size();
    f.pseudoImpulse.assign(n, 0.0f);
    if (f.def.splitImpulse) {
        p.pseudo.assign(n, Vec<D>(0.0f));
    } else {
        p.pseudo.clear();
    }
    const SolverView<D> s{p.velocity.data(),
                          f.def.splitImpulse ? p.pseudo.data() : nullptr,
                          p.pressure.data(),
                          f.pseudoImpulse.data(),
                          f.neighbours<D>().data(),
                          f.constraints.first.data(),
                          f.constraints.wallGradient.data(),
                          f.constraints.bias.data(),
                          f.constraints.invMass.data(),
                          f.constraints.count.data(),
                          kAllowanceSlop * f.restDensity * f.def.baumgarte * f.h / dt};
    // The pressure is an impulse per (sub)step: when the substep length
    // changes, the warm start scales with it, or a switch from 1 to 8
    // substeps would apply 8 times the support per unit time and blow up.
    const float fraction = f.constraints.warmFraction;
    f.lastSubstep = dt;
    const std::uint32_t iterations = f.def.iterations;
    if (f.def.solver == FluidSolver::Sequential) {
        for (std::size_t i = 0; i < n; ++i) warmStart<D>(s, i, fraction);
        solveContacts<D>(pool, f, dt);
        for (std::uint32_t it = 0; it < iterations; ++it) {
            for (std::size_t i = 0; i < n; ++i) visit<D>(s, i);
            solveContacts<D>(pool, f, dt);
        }
        return;
    }
    const Grid<D>& g = f.grid<D>();
    if (f.constraints.warmGathered) {
        // The setup gathered each particle's warm start (neighbours.cpp).
        const glm::vec3* warm = f.constraints.warmVelocity.data();
        pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                s.pressure[i] = warmPressure<D>(s, i, fraction);
                s.velocity[i] += Vec<D>(warm[i]);
            }
        });
    } else {
        forEachByColour<D>(pool, g, [&](std::size_t i) { warmStart<D>(s, i, fraction); });
    }
    solveContacts<D>(pool, f, dt);
    for (std::uint32_t it = 0; it < iterations; ++it) {
        forEachByColour<D>(pool, g, [&](std::size_t i) { visit<D>(s, i); });
        solveContacts<D>(pool, f, dt);
    }
}

template void solveConstraints<2>(WorkerPool&, FluidState&, float);
template void solveConstraints<3>(WorkerPool&, FluidState&, float);

}  // namespace spindrift::fluid
