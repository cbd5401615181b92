// Back-to-front sort on the device (src/gpu/gpu_sort.h) next to the CPU's
// sortBackToFront, same positions, same binary (docs/performance.md, "Vulkan
// backend").
//
//   build/release/bench_gpu_sort --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true --benchmark_format=json
// (one command line).
//
// Data as bench/bench_sort.cpp: random positions in a 200 m cube, the camera
// at one side looking across it. Argument: keys (100k, 1M). BM_GpuSort times
// one submission that records the whole sort and waits on its fence (the
// positions stay on the device, nothing is read back); BM_CpuSort times
// sortBackToFront with 2 threads. Without a GPU the device is Mesa's lavapipe,
// which runs the shaders on the same CPU cores: the ratio measures the path,
// not a GPU.
#include "effects/sort.h"
#include "gpu/gpu_sort.h"
#include "gpu/vulkan_buffer.h"

#include <spindrift/world.h>

#include <benchmark/benchmark.h>
#include <tbb/task_arena.h>

#include <cstdint>
#include <exception>
#include <random>
#include <vector>

namespace {

const glm::vec3 kEye(10.0f, 20.0f, -120.0f);
const glm::vec3 kForward(0.1f, -0.2f, 1.0f);

std::vector<glm::vec3> positions(std::size_t n) {
    std::mt19937 rng(20240611u);
    std::uniform_real_distribution<float> u(-100.0f, 100.0f);
    std::vector<glm::vec3> v(n);
    for (glm::vec3& x : v) {
        x = glm::vec3(u(rng), u(rng), u(rng));
    }
    return v;
}

void setCounters(benchmark::State& state, std::int64_t n) {
    state.SetItemsProcessed(state.iterations() * n);
    state.counters["n"] = static_cast<double>(n);
}

void BM_GpuSort(benchmark::State& state) {
    using namespace spindrift;
    const auto n = static_cast<std::uint32_t>(state.range(0));
    std::unique_ptr<gpu::Device> device;
    try {
        device = gpu::createDevice({});
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return;
    }
    gpu::Device& d = *device;
    {
        std::vector<glm::vec3> p = positions(n);
        gpu::Buffer buffer = gpu::createStorageBuffer(d, VkDeviceSize{n} * 12);
        gpu::Transfer t{&buffer, p.data(), VkDeviceSize{n} * 12};
        gpu::upload(d, std::span(&t, 1));
        std::unique_ptr<gpu::GpuSort> sort = gpu::createGpuSort(d);
        gpu::SortInput in{&buffer, nullptr, n, kEye, normalizeViewDirection(kForward)};
        auto once = [&] { gpu::submitOnce(d, [&](VkCommandBuffer cmd) { gpu::recordSortBackToFront(*sort, cmd, in); }); };
        once();  // scratch allocated outside the timing
        std::vector<std::uint32_t> order = gpu::readSortedIndices(*sort, n);
        if (order != sortBackToFront(p, kEye, kForward)) {
            state.SkipWithError("GPU order differs from sortBackToFront");
        }
        for (auto _ : state) {
            once();
        }
        setCounters(state, n);
        sort.reset();
        gpu::destroyBuffer(d, buffer);
    }
    gpu::destroyDevice(d);
}

void BM_CpuSort(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    std::vector<glm::vec3> p = positions(n);
    tbb::task_arena arena(2);
    arena.execute([&] {
        for (auto _ : state) {
            benchmark::DoNotOptimize(spindrift::sortBackToFront(p, kEye, kForward));
        }
    });
    setCounters(state, static_cast<std::int64_t>(n));
}

}  // namespace

BENCHMARK(BM_GpuSort)->ArgName("keys")->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CpuSort)->ArgName("keys")->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
