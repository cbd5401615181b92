// The fluid constraint solver (slides 36-39): sequential impulses, one visit
// per particle per iteration, warm started with the previous step's pressure.
// Two orders: the slides' single loop over all particles (Sequential), and
// Gauss-Seidel over colour groups of grid cells (Parallel), where cells of one
// colour share no particle and are visited at the same time.
//
// Split impulses (FluidDef::splitImpulse, on by default): most of the
// Baumgarte bias (slide 34) is solved on a second, pseudo velocity that moves
// particles this step and is then forgotten, as rigid-body solvers do for
// penetration; the real velocity keeps a quarter of it (fluid.glsl). With the bias in the real
// velocity (the slides' form) every density fluctuation of a disordered
// packing becomes kinetic energy: a tank at rest keeps boiling at about 0.2
// m/s (measured; docs/performance.md).
#include "core/room.h"
#include "fluid/fluid_state.h"

#include <algorithm>
#include <cstring>

namespace spindrift::fluid {
namespace {

/// Four floats in one SIMD register (GCC's and Clang's vector extension;
/// plain float operations lane by lane, so the same results as four scalar
/// ones, on any target). glm's vec4 stayed four scalar registers (measured).
typedef float Float4 __attribute__((vector_size(16)));

/// A 2D Motion as four floats (vx, vy, px, py): one load of a neighbour
/// serves both rates, one store both impulses.
inline Float4 bothOf(const Motion<2>& m) {
    Float4 r;
    std::memcpy(&r, &m, sizeof r);
    return r;
}
inline void storeBoth(Motion<2>& m, Float4 r) { std::memcpy(&m, &r, sizeof r); }
/// (gx, gy, gx, gy): a pair's g for both constraints at once.
inline Float4 twice(glm::vec2 g) { return Float4{g.x, g.y, g.x, g.y}; }
/// Lane 0: t[0] + t[1], lane 2: t[2] + t[3], the two dot products of a pair
/// whose products t holds (the sums glm::dot makes: IEEE addition commutes).
inline Float4 pairDots(Float4 t) { return t + __builtin_shufflevector(t, t, 1, 0, 3, 2); }

template <int D>
struct SolverView {
    Motion<D>* motion;  // velocities, and pseudo velocities when split
    bool split;         // false: bias on the real velocity
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

/// Applies impulse `delta` of particle i's constraint to the velocities: v_n +=
/// g delta on every neighbour, v_i -= sum g delta (Newton's third law, slide 39).
template <int D>
inline void applyImpulse(const SolverView<D>& s, std::size_t i, float delta) {
    const Neighbour<D>* list = s.lists[i / kParticleChunk].data() + s.first[i];
    Vec<D> self = Vec<D>(s.wall[i]) * delta;  // the motionless ghosts take no impulse
    for (std::uint32_t k = 0; k < s.count[i]; ++k) {
        const Vec<D> impulse = list[k].g * delta;
        s.motion[list[k].index].velocity += impulse;
        self += impulse;
    }
    s.motion[i].velocity -= self;
}

/// C' of particle i's constraint over the velocities (slide 36).
template <int D>
inline float rateOf(const SolverView<D>& s, std::size_t i) {
    const Neighbour<D>* list = s.lists[i / kParticleChunk].data() + s.first[i];
    const Motion<D>* m = s.motion;
    const Vec<D> vi = m[i].velocity;
    const std::uint32_t count = s.count[i];
    // Two chains of additions (even and odd neighbours), summed at the end:
    // one chain of 28 dependent additions bound the sweep (measured).
    float even = -glm::dot(Vec<D>(s.wall[i]), vi);  // ghosts at rest
    float odd = 0.0f;
    std::uint32_t k = 0;
    for (; k + 1 < count; k += 2) {
        even += glm::dot(list[k].g, m[list[k].index].velocity - vi);
        odd += glm::dot(list[k + 1].g, m[list[k + 1].index].velocity - vi);
    }
    if (k < count) even += glm::dot(list[k].g, m[list[k].index].velocity - vi);
    return even + odd;
}

/// C' of an over-dense particle's two constraints, over the velocities and
/// over the pseudo velocities, in one pass over its neighbours.
struct SplitRates {
    float rate;
    float pseudoRate;
};

template <int D>
inline SplitRates splitRates(const SolverView<D>& s, std::size_t i) {
    const Neighbour<D>* list = s.lists[i / kParticleChunk].data() + s.first[i];
    const std::uint32_t count = s.count[i];
    const Motion<D>* m = s.motion;
    const Vec<D> wall(s.wall[i]);
    if constexpr (D == 2) {
        // The same sums as below, two lanes at a time (bit-identical).
        const Float4 mi = bothOf(m[i]);
        Float4 even{-glm::dot(wall, m[i].velocity), 0.0f, -glm::dot(wall, m[i].pseudo), 0.0f};
        Float4 odd{0.0f, 0.0f, 0.0f, 0.0f};
        std::uint32_t k = 0;
        for (; k + 1 < count; k += 2) {
            even += pairDots(twice(list[k].g) * (bothOf(m[list[k].index]) - mi));
            odd += pairDots(twice(list[k + 1].g) * (bothOf(m[list[k + 1].index]) - mi));
        }
        if (k < count) even += pairDots(twice(list[k].g) * (bothOf(m[list[k].index]) - mi));
        return {even[0] + odd[0], even[2] + odd[2]};
    } else {
        const Vec<D> vi = m[i].velocity;
        const Vec<D> pi = m[i].pseudo;
        float rate = -glm::dot(wall, vi);
        float pseudoRate = -glm::dot(wall, pi);
        float rateOdd = 0.0f;
        float pseudoOdd = 0.0f;
        std::uint32_t k = 0;
        for (; k + 1 < count; k += 2) {
            const Motion<D>& a = m[list[k].index];
            const Motion<D>& b = m[list[k + 1].index];
            rate += glm::dot(list[k].g, a.velocity - vi);
            pseudoRate += glm::dot(list[k].g, a.pseudo - pi);
            rateOdd += glm::dot(list[k + 1].g, b.velocity - vi);
            pseudoOdd += glm::dot(list[k + 1].g, b.pseudo - pi);
        }
        if (k < count) {
            const Motion<D>& a = m[list[k].index];
            rate += glm::dot(list[k].g, a.velocity - vi);
            pseudoRate += glm::dot(list[k].g, a.pseudo - pi);
        }
        return {rate + rateOdd, pseudoRate + pseudoOdd};
    }
}

/// Applies an over-dense particle's two impulses: `delta` to the velocities,
/// `push` to the pseudo velocities, as applyImpulse does.
template <int D>
inline void applySplitImpulses(const SolverView<D>& s, std::size_t i, float delta, float push) {
    const Neighbour<D>* list = s.lists[i / kParticleChunk].data() + s.first[i];
    const std::uint32_t count = s.count[i];
    Motion<D>* m = s.motion;
    const Vec<D> wall(s.wall[i]);
    if constexpr (D == 2) {
        const Float4 both{delta, delta, push, push};
        Float4 self = twice(wall) * both;
        for (std::uint32_t k = 0; k < count; ++k) {
            const Float4 impulse = twice(list[k].g) * both;
            Motion<2>& n = m[list[k].index];
            storeBoth(n, bothOf(n) + impulse);
            self += impulse;
        }
        storeBoth(m[i], bothOf(m[i]) - self);
    } else {
        Vec<D> self = wall * delta;
        Vec<D> pseudoSelf = wall * push;
        for (std::uint32_t k = 0; k < count; ++k) {
            Motion<D>& n = m[list[k].index];
            const Vec<D> impulse = list[k].g * delta;
            const Vec<D> shift = list[k].g * push;
            n.velocity += impulse;
            n.pseudo += shift;
            self += impulse;
            pseudoSelf += shift;
        }
        m[i].velocity -= self;
        m[i].pseudo -= pseudoSelf;
    }
}

/// One visit of particle i's constraint (slide 36, signs in fluid.glsl).
template <int D>
inline void visit(const SolverView<D>& s, std::size_t i) {
    if (!s.split) {
        const kernels::FluidImpulse r =
            kernels::fluidSolveImpulse(rateOf<D>(s, i), s.bias[i], s.invMass[i], s.pressure[i]);
        s.pressure[i] = r.accumulated;
        if (r.delta != 0.0f) applyImpulse<D>(s, i, r.delta);
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
            rateOf<D>(s, i), kernels::fluidAllowance(bias, s.allowanceSlop), s.invMass[i], s.pressure[i]);
        s.pressure[i] = r.accumulated;
        if (r.delta != 0.0f) applyImpulse<D>(s, i, r.delta);
        return;
    }
    const SplitRates rates = splitRates<D>(s, i);
    const kernels::FluidImpulse r =
        kernels::fluidSolveImpulse(rates.rate, kernels::fluidRealBias(bias), s.invMass[i], s.pressure[i]);
    const kernels::FluidImpulse q =
        kernels::fluidSolveImpulse(rates.pseudoRate, kernels::fluidPseudoBias(bias), s.invMass[i], s.pseudoImpulse[i]);
    s.pressure[i] = r.accumulated;
    s.pseudoImpulse[i] = q.accumulated;
    applySplitImpulses<D>(s, i, r.delta, q.delta);
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
        applyImpulse<D>(s, i, start);
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
    assignInRoom(f.pseudoImpulse, n, 0.0f);
    // The working copy of the velocities (Particles::motion), with the warm
    // start the setup gathered (neighbours.cpp) already added.
    const bool gathered = f.constraints.warmGathered && f.def.solver == FluidSolver::Parallel;
    p.motion.resize(n);
    pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        const glm::vec3* warm = f.constraints.warmVelocity.data();
        for (std::size_t i = begin; i < end; ++i) {
            p.motion[i] = Motion<D>{gathered ? p.velocity[i] + Vec<D>(warm[i]) : p.velocity[i], Vec<D>(0.0f)};
        }
    });
    const SolverView<D> s{p.motion.data(),
                          f.def.splitImpulse,
                          p.pressure.data(),
                          f.pseudoImpulse.data(),
                          f.neighbours<D>().data(),
                          f.constraints.first.data(),
                          f.constraints.wallGradient.data(),
                          f.constraints.bias.data(),
                          f.constraints.invMass.data(),
                          f.constraints.count.data(),
                          kernels::fluidAllowanceSlop(f.restDensity, f.def.baumgarte, f.h, dt)};
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
    } else {
        const Grid<D>& g = f.grid<D>();
        if (gathered) {
            pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
                for (std::size_t i = begin; i < end; ++i) s.pressure[i] = warmPressure<D>(s, i, fraction);
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
    pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) p.velocity[i] = p.motion[i].velocity;
    });
}

template void solveConstraints<2>(WorkerPool&, FluidState&, float);
template void solveConstraints<3>(WorkerPool&, FluidState&, float);

}  // namespace spindrift::fluid
