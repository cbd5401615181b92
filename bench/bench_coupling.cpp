// Fluid-body coupling (issue 6): a 2D dam break of 30,000 particles into a
// field of 0, 20 or 200 crates (Box2D bodies), per world step at 60 Hz.
//
//   build/release/bench_coupling --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//
// Scene: a column of water w wide and 2w high (w = 122 particles at 2 cm)
// against the left wall of a tank 4w wide; the tank is a static body (floor
// and walls), which the water touches in every variant, so the 0-crate
// baseline pays the same static contacts; crates = -1 is the same dam break in
// a tank of plane colliders and no body at all (bench_fluid's). Crates 0.12 m square, densities
// alternating 500 and 2000 kg/m^2 (floaters and sinkers), stacked in rows on
// the floor from x = 1.1w to 3.9w. Each benchmark runs the first 60 steps (1
// s; the front reaches the first crates after ~0.3 s) once, one step per
// iteration. Counters: ms_per_step, body_contacts (particle-body contacts per
// step, all substeps), bodies_ms (Box2D step per step), contacts_ms and
// solve_ms (fluid passes, which include the body contacts), substeps.
//
// BM_Showcase: scenes/showcase.toml as `spindrift render` plays it (9 s of
// 1/60 s steps) on 1 and 2 threads, the whole run once per iteration.
// Counters: ms_per_step (world step, mean), fluid_ms_late (fluid step, mean
// over t >= 5.3 s, where the pool behind the gate forms; its passes
// grid_ms_late, integrate_ms_late, contacts_ms_late, setup_ms_late and solve_ms_late, and particles_late),
// substeps (mean) and substeps_late, and last_fire_out_s (when the last fire went out; 0: one
// still burns at the end).
#include <spindrift/fires.h>
#include <spindrift/scene.h>
#include <spindrift/world.h>

#include "bench_util.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace {

using namespace spindrift;

constexpr float kSpacing = 0.02f;
constexpr int kSteps = 60;
constexpr std::uint32_t kParticles = 30000;

using bench::wall;

/// crates < 0: no bodies at all, the tank of plane colliders (bench_fluid's).
WorldId makeWorld(int crates, std::uint32_t threads) {
    WorldDef wd;
    wd.threads = threads;
    const WorldId world = createWorld(wd);
    const float n = std::round(std::sqrt(static_cast<float>(kParticles) / 2.0f));
    const float w = n * kSpacing;  // m, column width
    const float width = 4.0f * w;
    FluidDef def;
    def.name = "water";
    def.dimension = 2;
    def.spacing = kSpacing;
    def.iterations = 4;
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(w, 2.0f * w, 0.0f), glm::vec3(0.0f)});
    if (crates < 0) {
        createCollider(world, wall(glm::vec3(0.0f), {1, 0, 0}));
        createCollider(world, wall(glm::vec3(width, 0.0f, 0.0f), {-1, 0, 0}));
        createCollider(world, wall(glm::vec3(0.0f), {0, 1, 0}));
        createFluid(world, def);
        return world;
    }
    BodyDef tank;
    tank.name = "tank";
    tank.type = BodyType::Static;
    tank.shapes.push_back(boxShape({0.5f * width + 0.1f, 0.05f}, {0.5f * width, -0.05f}));
    tank.shapes.push_back(boxShape({0.05f, 2.0f * w}, {-0.05f, 2.0f * w}));
    tank.shapes.push_back(boxShape({0.05f, 2.0f * w}, {width + 0.05f, 2.0f * w}));
    createBody(world, tank);
    createFluid(world, def);
    // Crates in rows on the floor, as many per row as fit 0.2 m apart.
    const float x0 = 1.1f * w, x1 = 3.9f * w;
    const auto count = static_cast<std::uint32_t>(crates);
    const auto perRow = std::min<std::uint32_t>(count, static_cast<std::uint32_t>((x1 - x0) / 0.2f));
    for (std::uint32_t i = 0; i < count; ++i) {
        const std::uint32_t row = i / perRow, column = i % perRow;
        BodyDef crate;
        crate.name = "crate";
        crate.position = {x0 + (static_cast<float>(column) + 0.5f) * (x1 - x0) / static_cast<float>(perRow),
                          0.061f + 0.125f * static_cast<float>(row)};
        crate.density = i % 2 == 0 ? 500.0f : 2000.0f;
        crate.shapes.push_back(boxShape({0.06f, 0.06f}));
        createBody(world, crate);
    }
    return world;
}

void BM_CoupledDamBreak(benchmark::State& state) {
    const auto crates = static_cast<int>(state.range(0));
    const auto threads = static_cast<std::uint32_t>(state.range(1));
    const WorldId world = makeWorld(crates, threads);
    double ms = 0.0, bodiesMs = 0.0, contactsMs = 0.0, solveMs = 0.0, substeps = 0.0, contacts = 0.0;
    int steps = 0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        const StepStats s = stepWorld(world, 1.0f / 60.0f);
        ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        const FluidStepStats& f = s.fluids.at(0);
        bodiesMs += s.bodiesMs;
        contactsMs += f.contactsMs;
        solveMs += f.solveMs;
        substeps += f.substeps;
        contacts += static_cast<double>(f.bodyContacts);
        steps += 1;
    }
    state.counters["ms_per_step"] = ms / steps;
    state.counters["bodies_ms"] = bodiesMs / steps;
    state.counters["contacts_ms"] = contactsMs / steps;
    state.counters["solve_ms"] = solveMs / steps;
    state.counters["substeps"] = substeps / steps;
    state.counters["body_contacts"] = contacts / steps;
    state.counters["particles"] = static_cast<double>(readFluid(world, FluidId{1}).count());
    destroyWorld(world);
}

BENCHMARK(BM_CoupledDamBreak)
    ->ArgNames({"crates", "threads"})
    ->Args({-1, 2})
    ->Args({0, 2})
    ->Args({20, 2})
    ->Args({200, 2})
    ->Iterations(kSteps)
    ->Unit(benchmark::kMillisecond);

void BM_Showcase(benchmark::State& state) {
    SceneDef scene = loadScene(std::string(SPINDRIFT_SOURCE_DIR) + "/scenes/showcase.toml");
    scene.world.threads = static_cast<std::uint32_t>(state.range(0));
    const auto steps = static_cast<int>(std::ceil(scene.render.seconds / scene.run.dt));
    constexpr double kLateFrom = 5.3;  // s
    double ms = 0.0, lateFluidMs = 0.0, substeps = 0.0, lateSubsteps = 0.0, lastOut = 0.0;
    double lateContactsMs = 0.0, lateSetupMs = 0.0, lateSolveMs = 0.0, lateParticles = 0.0;
    double lateGridMs = 0.0, lateIntegrateMs = 0.0;
    int late = 0;
    for (auto _ : state) {
        const WorldId w = buildWorld(scene);
        ms = lateFluidMs = substeps = lateSubsteps = lastOut = 0.0;
        lateContactsMs = lateSetupMs = lateSolveMs = lateParticles = lateGridMs = lateIntegrateMs = 0.0;
        late = 0;
        for (int i = 0; i < steps; ++i) {
            const StepStats s = stepWorld(w, scene.run.dt);
            takeEvents(w);
            ms += s.milliseconds;
            const FluidStepStats& f = s.fluids.at(0);
            const double fluidMs = f.gridMs + f.contactsMs + f.setupMs + f.solveMs + f.integrateMs;
            substeps += f.substeps;
            if (s.time >= kLateFrom) {
                lateFluidMs += fluidMs;
                lateGridMs += f.gridMs;
                lateIntegrateMs += f.integrateMs;
                lateContactsMs += f.contactsMs;
                lateSetupMs += f.setupMs;
                lateSolveMs += f.solveMs;
                lateParticles += static_cast<double>(f.particles);
                lateSubsteps += f.substeps;
                late += 1;
            }
            bool burning = false;
            for (std::uint32_t fire = 1; fire <= fireCount(w); ++fire) burning |= fireStrength(w, FireId{fire}) > 0.0f;
            if (burning) lastOut = 0.0;
            else if (lastOut == 0.0) lastOut = s.time;
        }
        destroyWorld(w);
    }
    state.counters["ms_per_step"] = ms / steps;
    state.counters["fluid_ms_late"] = lateFluidMs / std::max(late, 1);
    state.counters["grid_ms_late"] = lateGridMs / std::max(late, 1);
    state.counters["integrate_ms_late"] = lateIntegrateMs / std::max(late, 1);
    state.counters["contacts_ms_late"] = lateContactsMs / std::max(late, 1);
    state.counters["setup_ms_late"] = lateSetupMs / std::max(late, 1);
    state.counters["solve_ms_late"] = lateSolveMs / std::max(late, 1);
    state.counters["particles_late"] = lateParticles / std::max(late, 1);
    state.counters["substeps"] = substeps / steps;
    state.counters["substeps_late"] = lateSubsteps / std::max(late, 1);
    state.counters["last_fire_out_s"] = lastOut;
}

BENCHMARK(BM_Showcase)->ArgNames({"threads"})->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
