// The constraint fluid (issue 4): a dam break on the CPU backend, per world
// step at 60 Hz and 4 iterations, with the density error it leaves.
//
//   build/fluid/bench_fluid --benchmark_format=json
//
// Scene: a column of water w wide and 2w high (and w/2 deep in 3D) against
// the left wall of a closed tank 4w wide, particles at
// 2 cm, sized for the particle count of the argument; gravity 9.81 m/s^2;
// automatic substeps. Each benchmark runs the first 30 steps (0.5 s) of the
// collapse once, one step per iteration (the world persists): the column
// falls and the front runs along the floor. Counters: ms_per_step (wall time
// per stepWorld at dt = 1/60 s), ms_per_substep, mean_density_error and
// median_density_error (over the steps, of the step's mean of
// max(rho / rho0 - 1, 0)), substeps (mean per step), particles, and the
// passes' wall time per step (grid_ms, setup_ms, contacts_ms, solve_ms,
// integrate_ms).
#include <spindrift/world.h>

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace {

using namespace spindrift;

constexpr float kSpacing = 0.02f;
constexpr int kSteps = 30;

using bench::wall;

WorldId makeWorld(std::uint32_t dimension, std::uint32_t particles, std::uint32_t threads) {
    WorldDef wd;
    wd.threads = threads;
    const WorldId world = createWorld(wd);
    FluidDef def;
    def.name = "water";
    def.dimension = dimension;
    def.spacing = kSpacing;
    def.iterations = 4;
    // Column of n x 2n (x n/2 deep in 3D) particles.
    glm::vec3 column;
    if (dimension == 2) {
        const float n = std::round(std::sqrt(static_cast<float>(particles) / 2.0f));
        column = glm::vec3(n, 2.0f * n, 0.0f) * kSpacing;
    } else {
        const float n = std::round(std::cbrt(static_cast<float>(particles)));
        column = glm::vec3(n, 2.0f * n, 0.5f * n) * kSpacing;
    }
    const glm::vec3 tank(4.0f * column.x, 2.0f * column.y, column.z);
    createCollider(world, wall(glm::vec3(0.0f), {1, 0, 0}));
    createCollider(world, wall(tank, {-1, 0, 0}));
    createCollider(world, wall(glm::vec3(0.0f), {0, 1, 0}));
    if (dimension == 3) {
        createCollider(world, wall(glm::vec3(0.0f), {0, 0, 1}));
        createCollider(world, wall(tank, {0, 0, -1}));
    }
    def.blocks.push_back({glm::vec3(0.0f), column, glm::vec3(0.0f)});
    createFluid(world, def);
    return world;
}

void damBreak(benchmark::State& state, std::uint32_t dimension) {
    const auto particles = static_cast<std::uint32_t>(state.range(0));
    const auto threads = static_cast<std::uint32_t>(state.range(1));
    const WorldId world = makeWorld(dimension, particles, threads);
    std::vector<double> errors;
    double substeps = 0.0;
    double ms = 0.0;
    double passes[5] = {};
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        const StepStats s = stepWorld(world, 1.0f / 60.0f);
        ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        errors.push_back(s.fluids.at(0).meanDensityError);
        const FluidStepStats& f = s.fluids.at(0);
        substeps += f.substeps;
        const double pass[5] = {f.gridMs, f.setupMs, f.contactsMs, f.solveMs, f.integrateMs};
        for (int k = 0; k < 5; ++k) passes[k] += pass[k];
    }
    const double steps = static_cast<double>(errors.size());
    state.counters["particles"] = static_cast<double>(readFluid(world, FluidId{1}).count());
    state.counters["ms_per_step"] = ms / steps;
    double sum = 0.0;
    for (double e : errors) sum += e;
    state.counters["mean_density_error"] = sum / steps;
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    state.counters["median_density_error"] = errors[errors.size() / 2];
    state.counters["substeps"] = substeps / steps;
    state.counters["ms_per_substep"] = ms / substeps;
    const char* names[5] = {"grid_ms", "setup_ms", "contacts_ms", "solve_ms", "integrate_ms"};
    for (int k = 0; k < 5; ++k) state.counters[names[k]] = passes[k] / steps;
    destroyWorld(world);
}

void BM_FluidDamBreak2D(benchmark::State& state) { damBreak(state, 2); }
void BM_FluidDamBreak3D(benchmark::State& state) { damBreak(state, 3); }

BENCHMARK(BM_FluidDamBreak2D)
    ->ArgNames({"particles", "threads"})
    ->Args({10000, 2})
    ->Args({30000, 2})
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Iterations(kSteps)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FluidDamBreak3D)
    ->ArgNames({"particles", "threads"})
    ->Args({100000, 2})
    ->Iterations(kSteps)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
