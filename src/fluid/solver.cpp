// The fluid constraint solver (slides 36-39): sequential impulses, one visit
// per particle per iteration, warm started with the previous step's pressure.
// Two orders: the slides' single loop over all particles (Sequential), and
// Gauss-Seidel over colour groups of grid cells (Parallel), where cells of one
// colour share no particle and are visited at the same time.
#include "fluid/fluid_state.h"

namespace spindrift::fluid {
namespace {

template <int D>
struct SolverView {
    Vec<D>* velocity;
    float* pressure;
    const Neighbour<D>* lists;
    const float* bias;
    float biasScale;
    const float* invMass;
    const std::uint32_t* count;
    std::uint32_t maxN;
};

/// Applies impulse `delta` of particle i's constraint: v_n += g delta on every
/// neighbour, v_i -= sum g delta (Newton's third law, slide 39).
template <int D>
inline void applyImpulse(const SolverView<D>& s, std::size_t i, float delta) {
    const Neighbour<D>* list = s.lists + i * s.maxN;
    Vec<D> self(0.0f);
    for (std::uint32_t k = 0; k < s.count[i]; ++k) {
        const Vec<D> impulse = list[k].g * delta;
        s.velocity[list[k].index] += impulse;
        self += impulse;
    }
    s.velocity[i] -= self;
}

/// One visit of particle i's constraint (slide 36, signs in fluid.glsl).
template <int D>
inline void visit(const SolverView<D>& s, std::size_t i) {
    const Neighbour<D>* list = s.lists + i * s.maxN;
    const Vec<D> vi = s.velocity[i];
    float rate = 0.0f;
    for (std::uint32_t k = 0; k < s.count[i]; ++k) {
        rate += glm::dot(list[k].g, s.velocity[list[k].index] - vi);
    }
    const kernels::FluidImpulse r = kernels::fluidSolveImpulse(rate, s.bias[i] * s.biasScale, s.invMass[i], s.pressure[i]);
    s.pressure[i] = r.accumulated;
    if (r.delta != 0.0f) {
        applyImpulse<D>(s, i, r.delta);
    }
}

/// Warm start: the previous step's pressure, scaled, applied along this step's
/// directions, and taken as the starting accumulated impulse.
template <int D>
inline void warmStart(const SolverView<D>& s, std::size_t i, float fraction) {
    const float start = s.pressure[i] * fraction;
    s.pressure[i] = start;
    if (start != 0.0f && s.count[i] != 0) {
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
    const SolverView<D> s{p.velocity.data(), p.pressure.data(), f.neighbours<D>().data(),
                          f.constraints.bias.data(), 1.0f, f.constraints.invMass.data(),
                          f.constraints.count.data(), f.maxNeighbours};
    const float fraction = f.def.warmStart;
    const std::size_t n = p.size();
    if (f.def.solver == FluidSolver::Sequential) {
        for (std::size_t i = 0; i < n; ++i) warmStart<D>(s, i, fraction);
        solveContacts<D>(pool, f, dt);
        for (std::uint32_t it = 0; it < f.def.iterations; ++it) {
            for (std::size_t i = 0; i < n; ++i) visit<D>(s, i);
            solveContacts<D>(pool, f, dt);
        }
        return;
    }
    const Grid<D>& g = f.grid<D>();
    forEachByColour<D>(pool, g, [&](std::size_t i) { warmStart<D>(s, i, fraction); });
    solveContacts<D>(pool, f, dt);
    for (std::uint32_t it = 0; it < f.def.iterations; ++it) {
        forEachByColour<D>(pool, g, [&](std::size_t i) { visit<D>(s, i); });
        solveContacts<D>(pool, f, dt);
    }
}

template void solveConstraints<2>(WorkerPool&, FluidState&, float);
template void solveConstraints<3>(WorkerPool&, FluidState&, float);

}  // namespace spindrift::fluid
