// The "standard stack" effect on the CPU backend, next to a memory-copy
// baseline in the same binary, so that the effect's bandwidth can be compared
// with what the machine can move (docs/performance.md).
//
//   build/h-bench/bench_effects --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true --benchmark_format=json
// (one command line).
//
// Standard stack: one spawn-mode emitter whose single burst at t = 0 fills all
// 1,000,000 slots, lifetimes far longer than any run (so exactly 1M particles
// are alive in every measured step; checked against StepStats::alive), gravity,
// wind, damping, two attractors (one repelling), a plane collision, colour and
// size over-life curves. Built through the public API only (world.h,
// effects.h); stepWorld(world, 1/60) per iteration. Argument: threads of the
// CPU backend (WorldDef::threads), also used by the copy baseline.
#include "bench_util.h"
#include "effects/batch_update.h"

#include <spindrift/world.h>

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

namespace {

constexpr std::uint32_t kParticles = 1'000'000;
constexpr float kDt = 1.0f / 60.0f;

// Memory traffic of one particle-step in the CPU backend's structure-of-arrays
// (src/particles/emitter_state.h: 64 B per slot): the arrays the update needs to
// read and the arrays it changes. Rule: count each array once per direction.
//   read:    position 12, velocity 12, age 4, lifetime 4, rotation 4,
//            angular velocity 4, birth serial 4 (key of the start colour and
//            size the over-life curves multiply)                       = 44 B
//   written: position 12, velocity 12, age 4, size 4, rotation 4, colour 16
//                                                                      = 52 B
// Lifetime, angular velocity and birth never change after birth; colour and
// size are recomputed from the start values, not read. (The vector update,
// src/effects/batch_update.h, moves exactly these; the slots it leaves to the
// scalar kernel, and the scalar baseline, load and store every array, 64 + 64 B.)
constexpr double kBytesReadPerParticleStep = 12 + 12 + 4 + 4 + 4 + 4 + 4;
constexpr double kBytesWrittenPerParticleStep = 12 + 12 + 4 + 4 + 4 + 16;
constexpr double kBytesPerParticleStep = kBytesReadPerParticleStep + kBytesWrittenPerParticleStep;
static_assert(kBytesReadPerParticleStep == 44 && kBytesWrittenPerParticleStep == 52);

/// The copy baseline moves the same bytes per iteration as one step of the
/// standard stack: 48 MB read + 48 MB written = 1M x 96 B.
constexpr std::size_t kCopyBytes =
    static_cast<std::size_t>(kParticles * kBytesPerParticleStep / 2);  // 48,000,000
constexpr std::size_t kCopyChunk = std::size_t{1} << 20;

spindrift::Curve curve(std::vector<spindrift::CurveKey> keys) { return spindrift::Curve{std::move(keys)}; }

/// A world holding the standard stack, warmed up until all 1M particles live.
class StandardStack {
public:
    /// warmup: steps taken before the measured ones (the burst is born in the
    /// first): 3 measures the launch; 120 (2 s) a settled effect, most of
    /// whose particles then rest or slide on the ground.
    explicit StandardStack(std::uint32_t threads, int warmup = 3) {
        using namespace spindrift;
        WorldDef def;
        def.backend = Backend::Cpu;
        def.threads = threads;
        def.seed = 2024;
        world_ = createWorld(def);

        ForceDef gravity;
        gravity.name = "gravity";
        gravity.kind = ForceKind::Gravity;
        gravity.vector = glm::vec3(0.0f, -9.81f, 0.0f);
        createForce(world_, gravity);

        ForceDef wind;
        wind.name = "wind";
        wind.kind = ForceKind::Wind;
        wind.vector = glm::vec3(3.0f, 0.0f, 1.0f);
        wind.strength = 0.05f;
        createForce(world_, wind);

        ForceDef damping;
        damping.name = "damping";
        damping.kind = ForceKind::Damping;
        damping.strength = 0.2f;
        createForce(world_, damping);

        ForceDef attract;
        attract.name = "attractor";
        attract.kind = ForceKind::Attractor;
        attract.position = glm::vec3(4.0f, 3.0f, 0.0f);
        attract.strength = 5.0f;
        attract.radius = 1.0f;
        attract.falloff = 2.0f;
        attract.range = 20.0f;
        createForce(world_, attract);

        ForceDef repel = attract;
        repel.name = "repeller";
        repel.position = glm::vec3(-3.0f, 1.0f, 2.0f);
        repel.strength = -3.0f;
        repel.falloff = 1.0f;
        repel.range = 8.0f;
        createForce(world_, repel);

        ColliderDef ground;
        ground.name = "ground";
        ground.kind = ColliderKind::Plane;
        ground.position = glm::vec3(0.0f);
        ground.normal = glm::vec3(0.0f, 1.0f, 0.0f);
        ground.friction = 0.2f;
        ground.resilience = 0.5f;
        createCollider(world_, ground);

        EmitterDef e;
        e.name = "standard";
        e.lifecycle = Lifecycle::Spawn;
        e.capacity = kParticles;
        e.rate = 0.0f;
        e.bursts = {BurstDef{0.0f, kParticles}};
        // Launched downwards in a wide cone from just above the ground: the
        // first particles hit the plane in the first steps, and more every step.
        e.shape.kind = SpawnShapeKind::Sphere;
        e.shape.center = glm::vec3(0.0f, 1.0f, 0.0f);
        e.shape.radius = 0.9f;
        e.shape.direction = glm::vec3(0.0f, -1.0f, 0.0f);
        e.shape.spreadAngle = 1.2f;
        e.speed = {0.5f, 5.0f};
        // Far longer than any run (a few thousand steps at most), so nobody dies.
        e.lifetime = {1000.0f, 2000.0f};
        e.size = {0.05f, 0.1f};
        e.rotation = {0.0f, 6.28f};
        e.angularVelocity = {-1.0f, 1.0f};
        e.color = {glm::vec4(1.0f, 0.5f, 0.1f, 1.0f), glm::vec4(1.0f, 0.9f, 0.3f, 1.0f)};
        e.colorOverLife = curve({{0.0f, glm::vec4(1.0f)},
                                 {0.5f, glm::vec4(0.8f, 0.6f, 0.5f, 0.8f)},
                                 {1.0f, glm::vec4(0.2f, 0.2f, 0.2f, 0.0f)}});
        e.sizeOverLife = curve({{0.0f, glm::vec4(0.5f)}, {1.0f, glm::vec4(2.0f)}});
        createEmitter(world_, e);

        for (int i = 0; i < warmup; ++i) {
            step();
        }
        collisions_ = 0;
    }
    ~StandardStack() { spindrift::destroyWorld(world_); }
    StandardStack(const StandardStack&) = delete;
    StandardStack& operator=(const StandardStack&) = delete;

    /// One step; throws unless exactly kParticles are alive after it.
    void step() {
        spindrift::StepStats stats = spindrift::stepWorld(world_, kDt);
        if (stats.alive != kParticles || stats.died != 0) {
            throw std::runtime_error("standard stack: " + std::to_string(stats.alive) + " alive and " +
                                     std::to_string(stats.died) + " died in step " +
                                     std::to_string(stats.step) + "; expected 1000000 alive, none dying");
        }
        collisions_ += stats.collisions;
    }
    std::uint64_t collisions() const { return collisions_; }

private:
    spindrift::WorldId world_;
    std::uint64_t collisions_ = 0;
};

/// Two pre-faulted 48 MB buffers; copy() moves one into the other in 1 MB
/// chunks with tbb::parallel_for and std::memcpy.
class CopyBaseline {
public:
    explicit CopyBaseline(int threads)
        : arena_(threads), from_(kCopyBytes, std::uint8_t{1}), to_(kCopyBytes, std::uint8_t{2}) {}
    void copy() {
        arena_.execute([&] {
            const std::size_t chunks = (kCopyBytes + kCopyChunk - 1) / kCopyChunk;
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1),
                              [&](const tbb::blocked_range<std::size_t>& r) {
                                  for (std::size_t c = r.begin(); c != r.end(); ++c) {
                                      std::size_t begin = c * kCopyChunk;
                                      std::size_t size = std::min(kCopyChunk, kCopyBytes - begin);
                                      std::memcpy(to_.data() + begin, from_.data() + begin, size);
                                  }
                              });
        });
        benchmark::DoNotOptimize(to_.data());
        benchmark::ClobberMemory();
    }

private:
    tbb::task_arena arena_;
    std::vector<std::uint8_t> from_;
    std::vector<std::uint8_t> to_;
};

void setParticleCounters(benchmark::State& state) {
    const auto steps = static_cast<std::int64_t>(state.iterations());
    state.SetItemsProcessed(steps * kParticles);  // items_per_second = particle-steps/s
    state.SetBytesProcessed(static_cast<std::int64_t>(static_cast<double>(steps) * kParticles *
                                                      kBytesPerParticleStep));
    state.counters["bytes_per_particle_step"] = kBytesPerParticleStep;
    state.counters["bytes_read_per_particle_step"] = kBytesReadPerParticleStep;
    state.counters["bytes_written_per_particle_step"] = kBytesWrittenPerParticleStep;
    state.counters["ms_per_step"] = benchmark::Counter(
        static_cast<double>(steps) / 1000.0, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["particles"] = kParticles;
    state.counters["threads"] = static_cast<double>(state.range(0));
}

void BM_StandardStack(benchmark::State& state) {
    try {
        StandardStack stack(static_cast<std::uint32_t>(state.range(0)));
        for (auto _ : state) {
            stack.step();
        }
        state.counters["collisions_per_step"] = benchmark::Counter(
            static_cast<double>(stack.collisions()), benchmark::Counter::kAvgIterations);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return;
    }
    setParticleCounters(state);
}
BENCHMARK(BM_StandardStack)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_MemcpyBaseline(benchmark::State& state) {
    CopyBaseline copy(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        copy.copy();
    }
    // Read + written bytes, counted like the effect's: 2 x 48 MB per copy.
    state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * 2 *
                            static_cast<std::int64_t>(kCopyBytes));
    state.counters["copy_bytes"] = static_cast<double>(kCopyBytes);
    state.counters["threads"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_MemcpyBaseline)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The ratio, measured side by side: every iteration takes one step of the
/// standard stack and one copy, timed separately, so both see the same machine
/// (load, frequency, neighbours). ratio = effect bytes/s / copy bytes/s, both
/// counting read + written bytes. Target: >= 0.7 with 2 threads.
// Argument 1, the update's target: 0 the best vector target of the CPU, 1
// the old scalar update for every slot (the vector update's baseline,
// UpdateTarget::Scalar), 2 the AVX2 copy (the best one's predecessor on a CPU
// with AVX-512; skipped where the CPU has no AVX2).
// Argument 2: warm-up steps (StandardStack): the measured regime would
// otherwise drift with the number of iterations the library picks, as the
// particles come to rest on the ground.
void BM_StandardStackVsCopy(benchmark::State& state) {
    using Clock = std::chrono::steady_clock;
    const spindrift::bench::ScopedTarget target(state, state.range(1));
    if (!target.ok()) return;
    try {
        StandardStack stack(static_cast<std::uint32_t>(state.range(0)), static_cast<int>(state.range(2)));
        CopyBaseline copy(static_cast<int>(state.range(0)));
        double stepSeconds = 0.0;
        double copySeconds = 0.0;
        for (auto _ : state) {
            auto t0 = Clock::now();
            stack.step();
            auto t1 = Clock::now();
            copy.copy();
            auto t2 = Clock::now();
            stepSeconds += std::chrono::duration<double>(t1 - t0).count();
            copySeconds += std::chrono::duration<double>(t2 - t1).count();
        }
        const double steps = static_cast<double>(state.iterations());
        const double effectBytesPerSecond = steps * kParticles * kBytesPerParticleStep / stepSeconds;
        const double copyBytesPerSecond = steps * 2.0 * static_cast<double>(kCopyBytes) / copySeconds;
        state.counters["effect_bytes_per_second"] = effectBytesPerSecond;
        state.counters["copy_bytes_per_second"] = copyBytesPerSecond;
        state.counters["effect_particle_steps_per_second"] = steps * kParticles / stepSeconds;
        state.counters["effect_to_copy_ratio"] = effectBytesPerSecond / copyBytesPerSecond;
        state.counters["ms_per_step"] = 1000.0 * stepSeconds / steps;
        state.counters["ms_per_copy"] = 1000.0 * copySeconds / steps;
        state.counters["collisions_per_step"] = static_cast<double>(stack.collisions()) / steps;
        state.counters["bytes_per_particle_step"] = kBytesPerParticleStep;
        state.counters["threads"] = static_cast<double>(state.range(0));
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
BENCHMARK(BM_StandardStackVsCopy)
    ->ArgNames({"threads", "target", "warmup"})
    ->ArgsProduct({{1, 2}, {0, 1, 2}, {3, 120}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
