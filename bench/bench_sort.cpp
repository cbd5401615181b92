// Back-to-front sort of 1M particles: sortBackToFront (depth keys + LSD radix
// sort), the raw key/index radix sort, and std::sort baselines on the same data,
// all in this one binary so their ratios come from one run.
//
//   build/h-bench/bench_sort --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true --benchmark_format=json
// (one command line; docs/performance.md has the exact commands and results).
//
// Arguments: threads (a tbb::task_arena of that many threads runs the sort) and,
// for the radix sorts, the digit width in bits (8: 4 passes, 11: 3 passes).
// Counters: ms_per_sort (wall time per sort), items_per_second (pairs sorted).
#include "effects/sort.h"

#include <spindrift/world.h>

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

namespace {

constexpr std::size_t kParticles = 1'000'000;

/// Random positions in a 200 m cube around the camera, which sits at one side
/// looking across it: depths span about [-100, 270] m, both signs.
const std::vector<glm::vec3>& positions() {
    static const std::vector<glm::vec3> p = [] {
        std::mt19937 rng(20240611u);
        std::uniform_real_distribution<float> u(-100.0f, 100.0f);
        std::vector<glm::vec3> v(kParticles);
        for (glm::vec3& x : v) {
            x = glm::vec3(u(rng), u(rng), u(rng));
        }
        return v;
    }();
    return p;
}
const glm::vec3 kEye(10.0f, 20.0f, -120.0f);
const glm::vec3 kForward(0.1f, -0.2f, 1.0f);  // unnormalised on purpose

/// The keys sortBackToFront sorts, for the raw radix sort benchmark.
const std::vector<std::uint32_t>& depthKeys() {
    static const std::vector<std::uint32_t> k = [] {
        glm::vec3 f = spindrift::normalizeViewDirection(kForward);
        std::vector<std::uint32_t> keys(kParticles);
        for (std::size_t i = 0; i < kParticles; ++i) {
            keys[i] = spindrift::backToFrontKey(glm::dot(positions()[i] - kEye, f));
        }
        return keys;
    }();
    return k;
}

void setSortCounters(benchmark::State& state, int threads) {
    const auto n = static_cast<std::int64_t>(kParticles);
    state.SetItemsProcessed(state.iterations() * n);
    // kIsRate | kInvert: elapsed seconds / value, i.e. ms per sort.
    state.counters["ms_per_sort"] = benchmark::Counter(
        static_cast<double>(state.iterations()) / 1000.0,
        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["threads"] = threads;
    state.counters["n"] = static_cast<double>(n);
}

spindrift::RadixDigitBits digitBitsArg(std::int64_t bits) {
    return bits == 11 ? spindrift::RadixDigitBits::Eleven : spindrift::RadixDigitBits::Eight;
}

/// The public call: depths, keys, radix sort, a fresh index vector returned.
// Both radix benchmarks run 1 and 2 threads with 8- and 11-bit digits.
void threadAndDigitArgs(benchmark::internal::Benchmark* b) {
    b->ArgNames({"threads", "bits"})->Args({1, 8})->Args({2, 8})->Args({1, 11})->Args({2, 11});
    b->Unit(benchmark::kMillisecond)->UseRealTime();
}

void BM_SortBackToFront(benchmark::State& state) {
    const int threads = static_cast<int>(state.range(0));
    const spindrift::RadixDigitBits bits = digitBitsArg(state.range(1));
    const std::vector<glm::vec3>& p = positions();
    tbb::task_arena arena(threads);
    for (auto _ : state) {
        arena.execute([&] {
            std::vector<std::uint32_t> order = spindrift::sortBackToFront(p, kEye, kForward, bits);
            benchmark::DoNotOptimize(order.data());
        });
    }
    setSortCounters(state, threads);
    state.counters["digit_bits"] = static_cast<double>(state.range(1));
}
BENCHMARK(BM_SortBackToFront)
    ->Apply(threadAndDigitArgs);

/// sortBackToFrontQuantised: 16-bit depth keys, two 8-bit passes (not exact:
/// depths within 1/65534 of the range may swap). Compare with
/// BM_SortBackToFront/threads:N/bits:8 of the same run.
void BM_SortBackToFrontQuantised(benchmark::State& state) {
    const int threads = static_cast<int>(state.range(0));
    const std::vector<glm::vec3>& p = positions();
    tbb::task_arena arena(threads);
    for (auto _ : state) {
        arena.execute([&] {
            std::vector<std::uint32_t> order = spindrift::sortBackToFrontQuantised(p, kEye, kForward);
            benchmark::DoNotOptimize(order.data());
        });
    }
    setSortCounters(state, threads);
}
BENCHMARK(BM_SortBackToFrontQuantised)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The raw (key, index) radix sort with reused scratch (what a renderer would
/// call every frame); restoring the unsorted input is not timed.
void BM_RadixSortKeyIndex(benchmark::State& state) {
    const int threads = static_cast<int>(state.range(0));
    const spindrift::RadixDigitBits bits = digitBitsArg(state.range(1));
    std::vector<std::uint32_t> keys(kParticles);
    std::vector<std::uint32_t> indices(kParticles);
    spindrift::RadixSortScratch scratch;
    scratch.reserve(kParticles);
    tbb::task_arena arena(threads);
    for (auto _ : state) {
        state.PauseTiming();
        keys = depthKeys();
        std::iota(indices.begin(), indices.end(), 0u);
        state.ResumeTiming();
        arena.execute([&] { spindrift::radixSortKeyIndex(keys, indices, scratch, bits); });
        benchmark::DoNotOptimize(indices.data());
    }
    setSortCounters(state, threads);
    state.counters["digit_bits"] = static_cast<double>(state.range(1));
}
BENCHMARK(BM_RadixSortKeyIndex)
    ->Apply(threadAndDigitArgs);

/// Baseline for sortBackToFront: the same result with std::sort (depths, then
/// indices by (depth descending, index ascending)). One thread.
void BM_StdSortBackToFront(benchmark::State& state) {
    const std::vector<glm::vec3>& p = positions();
    std::vector<float> depth(kParticles);
    for (auto _ : state) {
        glm::vec3 f = spindrift::normalizeViewDirection(kForward);
        for (std::size_t i = 0; i < kParticles; ++i) {
            depth[i] = glm::dot(p[i] - kEye, f);
        }
        std::vector<std::uint32_t> order(kParticles);
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            float da = depth[a];
            float db = depth[b];
            if (da != db) {
                return da > db;
            }
            return a < b;
        });
        benchmark::DoNotOptimize(order.data());
    }
    setSortCounters(state, 1);
}
BENCHMARK(BM_StdSortBackToFront)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Baseline for the raw radix sort: std::sort of the pairs packed in 64 bits
/// (key << 32 | index: the same stable order). One thread.
void BM_StdSortPackedPairs(benchmark::State& state) {
    const std::vector<std::uint32_t>& k = depthKeys();
    std::vector<std::uint64_t> pairs(kParticles);
    for (auto _ : state) {
        state.PauseTiming();
        for (std::size_t i = 0; i < kParticles; ++i) {
            pairs[i] = (std::uint64_t{k[i]} << 32) | i;
        }
        state.ResumeTiming();
        std::sort(pairs.begin(), pairs.end());
        benchmark::DoNotOptimize(pairs.data());
    }
    setSortCounters(state, 1);
}
BENCHMARK(BM_StdSortPackedPairs)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
