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
// integrate_ms). Args {particles, threads, target}: the CPU's vector target
// (bench_util.h: 0 the best, 1 scalar, 2 AVX2). Every target gives the same
// results bit for bit (FluidDeterminism.BitIdenticalAtEveryVectorTarget), so
// the same substeps: the 10k cases at 1 thread compare the targets' passes
// side by side.
//
// BM_FluidLiquidFunDamBreak (issue 12): exactly LiquidFun's Testbed dam break,
// to compare with LiquidFun measured outside the repository (docs/performance.md).
//
//   build/release/bench_fluid --benchmark_filter=LiquidFun
//
// A closed 4 x 4 m box of plane walls, a column 1.6 m wide and 2.0 m high in
// its left bottom corner, gravity (0, -10) m/s^2, dt = 1/60 s, particles on
// the block lattice at 1.8 cm (10k: 88 x 111 = 9,768), 1.0 cm (30k: 160 x 200
// = 32,000) or 0.57 cm (100k: 280 x 350 = 98,000) spacing, every other
// setting at FluidDef's defaults (automatic substeps). Args {particles,
// threads, plain}: plain 1 runs the solver's defaults before over-relaxation
// (4 plain Gauss-Seidel iterations instead of 2 relaxed by 1.2), side by side
// with the defaults. One iteration is the whole run, 360 steps (t = 0 to 6 s), of
// which steps 60 to 359 (t = 1 s to 6 s, after the first impact) are timed:
// the benchmark's time is their sum (manual time). Counters: ms_per_step and
// median_ms_per_step (wall time of stepWorld over the timed steps),
// cpu_ms_per_step and median_cpu_ms_per_step (process CPU time, all threads:
// with one thread the figure that holds up on a busy machine), substeps
// (mean over the timed steps), max_mean_density_error (largest per-step mean
// of max(rho / rho0 - 1, 0) over all 360 steps), neighbour_overflows (total,
// all steps), max_speed (m/s, over all steps), number_density_median and
// number_density_p95 (measureFluidNumberDensity at t = 6 s), particles, and
// the passes' own wall times per timed step (FluidStepStats): grid_ms,
// contacts_ms, setup_ms, solve_ms, integrate_ms; what each substep rule
// asked for, mean over the timed steps (substeps_for_speed, _depth,
// _compression), and the share of timed steps in which it asked for the
// count taken (steps_set_by_speed, _depth, _compression; ties count for
// each).
#include <spindrift/world.h>

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <vector>

namespace {

using namespace spindrift;

constexpr float kSpacing = 0.02f;
constexpr int kSteps = 30;

using bench::wall;

/// The solver's defaults before over-relaxation: 4 plain Gauss-Seidel
/// iterations.
void usePlainSweeps(FluidDef& def) {
    def.iterations = 4;
    def.relaxation = 1.0f;
}

WorldId makeWorld(std::uint32_t dimension, std::uint32_t particles, std::uint32_t threads) {
    WorldDef wd;
    wd.threads = threads;
    const WorldId world = createWorld(wd);
    FluidDef def;
    def.name = "water";
    def.dimension = dimension;
    def.spacing = kSpacing;
    // The solver this benchmark has always timed, so its figures stay
    // comparable across sessions; the LiquidFun case below runs FluidDef's
    // defaults.
    usePlainSweeps(def);
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
    const bench::ScopedTarget target(state, state.range(2));
    if (!target.ok()) return;
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

double cpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

double mean(const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return sum / static_cast<double>(v.size());
}

void BM_FluidLiquidFunDamBreak(benchmark::State& state) {
    const auto particles = static_cast<std::uint32_t>(state.range(0));
    const auto threads = static_cast<std::uint32_t>(state.range(1));
    const bool plain = state.range(2) != 0;  // the defaults before over-relaxation
    const float spacing = particles <= 10000 ? 0.018f : particles <= 30000 ? 0.010f : 0.0057f;
    constexpr int kTotalSteps = 360, kFirstTimed = 60;  // t = 0..6 s, timed from t = 1 s
    constexpr float kDt = 1.0f / 60.0f;
    for (auto _ : state) {
        WorldDef wd;
        wd.threads = threads;
        const WorldId world = createWorld(wd);
        const glm::vec3 box(4.0f, 4.0f, 0.0f);
        createCollider(world, wall(glm::vec3(0.0f), {1, 0, 0}));
        createCollider(world, wall(box, {-1, 0, 0}));
        createCollider(world, wall(glm::vec3(0.0f), {0, 1, 0}));
        createCollider(world, wall(box, {0, -1, 0}));
        FluidDef def;
        def.name = "water";
        def.dimension = 2;
        def.spacing = spacing;
        def.gravity = glm::vec3(0.0f, -10.0f, 0.0f);
        def.blocks.push_back({glm::vec3(0.0f), glm::vec3(1.6f, 2.0f, 0.0f), glm::vec3(0.0f)});
        if (plain) usePlainSweeps(def);
        const FluidId fluid = createFluid(world, def);
        std::vector<double> wallMs, cpu;
        double substeps = 0.0, maxMeanError = 0.0, maxSpeed = 0.0;
        double gridMs = 0.0, contactsMs = 0.0, setupMs = 0.0, solveMs = 0.0, integrateMs = 0.0;
        // What the substep rules asked for (FluidStepStats::substepsFor*),
        // summed, and the steps in which each asked for the count taken.
        double forSpeed = 0.0, forDepth = 0.0, forCompression = 0.0;
        double setBySpeed = 0.0, setByDepth = 0.0, setByCompression = 0.0;
        std::uint64_t overflows = 0;
        for (int step = 0; step < kTotalSteps; ++step) {
            const double c0 = cpuMs();
            const auto t0 = std::chrono::steady_clock::now();
            const StepStats s = stepWorld(world, kDt);
            const auto t1 = std::chrono::steady_clock::now();
            const double c1 = cpuMs();
            const FluidStepStats& f = s.fluids.at(0);
            if (step >= kFirstTimed) {
                wallMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
                cpu.push_back(c1 - c0);
                substeps += f.substeps;
                gridMs += f.gridMs;
                contactsMs += f.contactsMs;
                setupMs += f.setupMs;
                solveMs += f.solveMs;
                integrateMs += f.integrateMs;
                forSpeed += f.substepsForSpeed;
                forDepth += f.substepsForDepth;
                forCompression += f.substepsForCompression;
                setBySpeed += f.substepsForSpeed == f.substeps ? 1.0 : 0.0;
                setByDepth += f.substepsForDepth == f.substeps ? 1.0 : 0.0;
                setByCompression += f.substepsForCompression == f.substeps ? 1.0 : 0.0;
            }
            maxMeanError = std::max(maxMeanError, f.meanDensityError);
            maxSpeed = std::max(maxSpeed, f.maxSpeed);
            overflows += f.neighbourOverflows;
        }
        const FluidNumberDensity nd = measureFluidNumberDensity(world, fluid);
        double timed = 0.0;
        for (double ms : wallMs) timed += ms;
        state.SetIterationTime(timed * 1e-3);
        state.counters["particles"] = static_cast<double>(nd.particles);
        state.counters["ms_per_step"] = mean(wallMs);
        state.counters["median_ms_per_step"] = median(wallMs);
        state.counters["cpu_ms_per_step"] = mean(cpu);
        state.counters["median_cpu_ms_per_step"] = median(cpu);
        const double timedSteps = static_cast<double>(wallMs.size());
        state.counters["substeps"] = substeps / timedSteps;
        state.counters["grid_ms"] = gridMs / timedSteps;
        state.counters["contacts_ms"] = contactsMs / timedSteps;
        state.counters["setup_ms"] = setupMs / timedSteps;
        state.counters["solve_ms"] = solveMs / timedSteps;
        state.counters["integrate_ms"] = integrateMs / timedSteps;
        state.counters["substeps_for_speed"] = forSpeed / timedSteps;
        state.counters["substeps_for_depth"] = forDepth / timedSteps;
        state.counters["substeps_for_compression"] = forCompression / timedSteps;
        state.counters["steps_set_by_speed"] = setBySpeed / timedSteps;
        state.counters["steps_set_by_depth"] = setByDepth / timedSteps;
        state.counters["steps_set_by_compression"] = setByCompression / timedSteps;
        state.counters["max_mean_density_error"] = maxMeanError;
        state.counters["neighbour_overflows"] = static_cast<double>(overflows);
        state.counters["max_speed"] = maxSpeed;
        state.counters["number_density_median"] = nd.median;
        state.counters["number_density_p95"] = nd.p95;
        destroyWorld(world);
    }
}

BENCHMARK(BM_FluidDamBreak2D)
    ->ArgNames({"particles", "threads", "target"})
    ->Args({10000, 1, 1})
    ->Args({10000, 1, 2})
    ->Args({10000, 1, 0})
    ->Args({10000, 2, 0})
    ->Args({30000, 2, 0})
    ->Args({100000, 1, 0})
    ->Args({100000, 2, 0})
    ->Iterations(kSteps)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FluidDamBreak3D)
    ->ArgNames({"particles", "threads", "target"})
    ->Args({100000, 2, 0})
    ->Iterations(kSteps)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FluidLiquidFunDamBreak)
    ->ArgNames({"particles", "threads", "plain"})
    ->Args({10000, 1, 0})
    ->Args({10000, 1, 1})
    ->Args({10000, 2, 0})
    ->Args({30000, 1, 0})
    ->Args({30000, 1, 1})
    ->Args({30000, 2, 0})
    ->Args({100000, 1, 0})
    ->Args({100000, 2, 0})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
