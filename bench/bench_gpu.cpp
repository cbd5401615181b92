// The effect update on the Vulkan backend next to the CPU backend, in the same
// binary, on the same world (docs/performance.md, "Vulkan backend").
//
//   build/release/bench_gpu --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true --benchmark_format=json
// (one command line).
//
// World: one recycle-mode emitter (the GPU particle talk's fixed slots) with
// lifetimes of 0.5 to 1 s, warmed up for 1 s so that every slot is alive and
// slots are re-born every step; gravity, wind, damping, an attractor and a
// repeller, a ground plane, colour and size over-life curves: the standard
// stack of bench_effects in recycle mode. Argument 0: particles; argument 1:
// backend (0 = cpu with 2 threads, 1 = vulkan); argument 2: the Vulkan
// world's frames in flight (1: every step waits for the device; 2: the host
// records step n + 1 while the device runs step n); argument 3: on the CPU, 1
// runs the old scalar update for every slot (UpdateTarget::Scalar, the
// baseline of the vector update, src/effects/batch_update.h), 0 the best
// vector target of this CPU. On a machine without a GPU the
// Vulkan backend runs on Mesa's lavapipe, a CPU implementation, so the numbers
// here measure the path, not a GPU; 1M particles on lavapipe take about a
// second per step, too long to repeat here, so the Vulkan case is 100k only.
#include "effects/batch_update.h"

#include <spindrift/world.h>

#include <benchmark/benchmark.h>

#include <cstdint>
#include <exception>
#include <string>

namespace {

constexpr float kDt = 1.0f / 60.0f;

spindrift::WorldId makeWorld(std::uint32_t particles, spindrift::Backend backend, std::uint32_t frames) {
    using namespace spindrift;
    WorldDef def;
    def.backend = backend;
    def.threads = 2;
    def.framesInFlight = frames;
    WorldId w = createWorld(def);
    ForceDef f;
    f.kind = ForceKind::Gravity;
    createForce(w, f);
    f = ForceDef{};
    f.kind = ForceKind::Wind;
    f.vector = {2.0f, 0.0f, 0.0f};
    f.strength = 0.05f;
    createForce(w, f);
    f = ForceDef{};
    f.kind = ForceKind::Damping;
    f.strength = 0.2f;
    createForce(w, f);
    f = ForceDef{};
    f.kind = ForceKind::Attractor;
    f.position = {2.0f, 2.0f, 0.0f};
    f.strength = 5.0f;
    createForce(w, f);
    f.position = {-2.0f, 1.0f, 0.0f};
    f.strength = -3.0f;
    f.falloff = 1.0f;
    createForce(w, f);
    ColliderDef floor;
    floor.kind = ColliderKind::Plane;
    floor.resilience = 0.4f;
    floor.friction = 0.2f;
    createCollider(w, floor);
    EmitterDef e;
    e.lifecycle = Lifecycle::Recycle;
    e.capacity = particles;
    e.lifetime = {0.5f, 1.0f};
    e.shape.kind = SpawnShapeKind::Sphere;
    e.shape.center = {0.0f, 1.0f, 0.0f};
    e.shape.radius = 0.5f;
    e.shape.spreadAngle = 0.8f;
    e.speed = {2.0f, 6.0f};
    e.colorOverLife.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(1.0f, 0.5f, 0.2f, 0.0f)}};
    e.sizeOverLife.keys = {{0.0f, glm::vec4(0.5f)}, {1.0f, glm::vec4(2.0f)}};
    createEmitter(w, e);
    for (int i = 0; i < 60; ++i) {
        stepWorld(w, kDt);
    }
    return w;
}

void BM_RecycleStack(benchmark::State& state) {
    const auto particles = static_cast<std::uint32_t>(state.range(0));
    const auto backend = state.range(1) == 0 ? spindrift::Backend::Cpu : spindrift::Backend::Vulkan;
    spindrift::WorldId w;
    const spindrift::UpdateTarget saved = spindrift::updateTarget();
    spindrift::setUpdateTarget(state.range(3) != 0 ? spindrift::UpdateTarget::Scalar
                                                   : spindrift::bestUpdateTarget());
    state.SetLabel(std::string(spindrift::updateTargetName(spindrift::updateTarget())));
    try {
        w = makeWorld(particles, backend, static_cast<std::uint32_t>(state.range(2)));
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return;
    }
    double deviceMs = 0.0;
    std::uint64_t counted = 0;
    for (auto _ : state) {
        spindrift::StepStats s = spindrift::stepWorld(w, kDt);
        deviceMs += s.deviceMilliseconds;
        counted += s.countedSteps;
        if (s.countedSteps > 0 && s.alive != particles) {
            state.SkipWithError("not every slot is alive");
            break;
        }
    }
    spindrift::flushWorld(w);  // drains the step still in flight (untimed: one of many)
    state.SetItemsProcessed(state.iterations() * particles);
    // Device time per step from the Vulkan world's timestamps (0 on the CPU).
    state.counters["device_ms_per_step"] = counted > 0 ? deviceMs / static_cast<double>(counted) : 0.0;
    state.counters["particle_steps_per_second"] =
        benchmark::Counter(static_cast<double>(particles), benchmark::Counter::kIsIterationInvariantRate);
    spindrift::destroyWorld(w);
    spindrift::setUpdateTarget(saved);
}

}  // namespace

BENCHMARK(BM_RecycleStack)
    ->ArgNames({"particles", "vulkan", "frames", "scalar"})
    ->Args({100'000, 0, 1, 1})
    ->Args({100'000, 0, 1, 0})
    ->Args({100'000, 1, 1, 0})
    ->Args({100'000, 1, 2, 0})
    ->Args({1'000'000, 0, 1, 1})
    ->Args({1'000'000, 0, 1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
