// The fluid's grid on the device (src/gpu/gpu_fluid_grid.h) against the
// CPU's buildGrid (src/fluid/grid.cpp): the same order and keyStart, element
// for element. Both are a stable sort by the same integer keys, computed by
// the same float operations (fluid.glsl's fluidGridKey), so anything short of
// equality is a bug: a key computed differently, an unstable sort, or a wrong
// start of an empty key.
#include "fluid/fluid_state.h"
#include "fluid/fluid_test_util.h"
#include "gpu/gpu_fluid_grid.h"
#include "gpu/vulkan_buffer.h"
#include "gpu_test_util.h"

#include <spindrift/fluid.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <random>

namespace spindrift {
namespace {

using test::GpuTest;
template <int D>
using Vec = fluid::Vec<D>;

constexpr float kDt = 1.0f / 60.0f;

/// The place of a CPU grid as the device grid takes it.
template <int D>
gpu::FluidGridParams paramsOf(const fluid::Grid<D>& g) {
    gpu::FluidGridParams p;
    p.dimension = D;
    for (int a = 0; a < D; ++a) p.origin[a] = g.origin[a];
    p.invH = 1.0f / g.h;
    p.cells = glm::ivec3(g.cells[0], g.cells[1], g.cells[2]);
    return p;
}
constexpr float kInf = std::numeric_limits<float>::infinity();

// One validated device and grid for the whole suite.
class GpuFluidGridTest : public test::GpuSuiteWith<gpu::GpuFluidGrid, &gpu::createGpuFluidGrid> {
protected:
    struct Result {
        std::vector<std::uint32_t> order;
        std::vector<std::uint32_t> keyStart;
        gpu::FluidGridParams params;
    };

    // The CPU's grid of particles at x, sub-cells h wide.
    template <int D>
    static Result onCpu(const std::vector<Vec<D>>& x, float h) {
        fluid::FluidState f;
        f.def.dimension = D;
        f.h = h;
        for (std::size_t i = 0; i < x.size(); ++i) {
            f.particles<D>().push(x[i], Vec<D>(0.0f), static_cast<std::uint32_t>(i));
        }
        WorkerPool pool(2);
        fluid::buildGrid<D>(pool, f);
        const fluid::Grid<D>& g = f.grid<D>();
        return {g.order, g.keyStart, paramsOf<D>(g)};
    }

    // The device's grid of the same particles in the same place.
    template <int D>
    static Result onDevice(const std::vector<Vec<D>>& x, const gpu::FluidGridParams& params) {
        Shared& s = shared();
        gpu::Device& d = *s.device;
        const auto n = static_cast<std::uint32_t>(x.size());
        const VkDeviceSize bytes = VkDeviceSize{n} * sizeof(Vec<D>);  // tightly packed, as the CPU's arrays
        static_assert(sizeof(Vec<D>) == D * sizeof(float));
        gpu::Buffer p = gpu::createStorageBuffer(d, std::max<VkDeviceSize>(bytes, 16u));
        if (n > 0) {
            gpu::Transfer up{&p, const_cast<Vec<D>*>(x.data()), bytes};
            gpu::upload(d, std::span(&up, 1));
        }
        gpu::submitOnce(d, [&](VkCommandBuffer cmd) { gpu::recordFluidGrid(cmd, *s.part, p, n, params); });
        Result r{gpu::readGridOrder(*s.part), gpu::readGridKeyStart(*s.part), params};
        gpu::destroyBuffer(d, p);
        return r;
    }

    // Both grids, compared element for element.
    template <int D>
    static void expectSameGrid(const std::vector<Vec<D>>& x, float h, const char* what) {
        const Result cpu = onCpu<D>(x, h);
        const Result gpu = onDevice<D>(x, cpu.params);
        ASSERT_EQ(cpu.order.size(), x.size()) << what;
        ASSERT_EQ(gpu.order.size(), cpu.order.size()) << what;
        ASSERT_EQ(gpu.keyStart.size(), cpu.keyStart.size()) << what;
        std::size_t orderDiffs = 0, startDiffs = 0;
        for (std::size_t i = 0; i < cpu.order.size(); ++i) orderDiffs += gpu.order[i] != cpu.order[i];
        for (std::size_t k = 0; k < cpu.keyStart.size(); ++k) startDiffs += gpu.keyStart[k] != cpu.keyStart[k];
        EXPECT_EQ(orderDiffs, 0u) << what << ": " << x.size() << " particles";
        EXPECT_EQ(startDiffs, 0u) << what << ": " << cpu.keyStart.size() << " key starts";
        EXPECT_EQ(gpu.keyStart.back(), x.size()) << what;
    }
};

// A dam break's particles after `steps` steps, in creation order (readFluid),
// which after the collapse is far from grid order.
template <int D>
std::vector<Vec<D>> damBreak(float spacing, float h, glm::vec3 column, glm::vec3 box, int steps) {
    test::FluidWorld world;
    test::closedBox(world.id, glm::vec3(0.0f), box, D);
    FluidDef def;
    def.name = "water";
    def.dimension = D;
    def.spacing = spacing;
    def.smoothing = h;
    def.blocks.push_back({glm::vec3(0.0f), column, glm::vec3(0.0f)});
    const FluidId id = createFluid(world.id, def);
    for (int i = 0; i < steps; ++i) {
        stepWorld(world.id, kDt);
    }
    const FluidSnapshot s = readFluid(world.id, id);
    std::vector<Vec<D>> x(s.position.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        x[i] = Vec<D>(s.position[i]);
    }
    return x;
}

TEST_F(GpuFluidGridTest, DamBreak2DMatchesTheCpuGridExactly) {
    const float h = 0.06f;
    const std::vector<Vec<2>> x = damBreak<2>(0.02f, h, {1.0f, 1.5f, 0.0f}, {3.0f, 2.0f, 0.0f}, 30);
    ASSERT_GT(x.size(), 3000u);  // several tiles of the sort (1024 keys)
    expectSameGrid<2>(x, h, "2D dam break");
    // Shuffled: many particles of one key far apart in index order, so the
    // sort's stability decides the order within each key.
    std::vector<Vec<2>> shuffled = x;
    std::mt19937 rng(7u);
    for (std::size_t i = shuffled.size(); i > 1; --i) {
        std::swap(shuffled[i - 1], shuffled[rng() % i]);
    }
    expectSameGrid<2>(shuffled, h, "2D dam break, shuffled");
    // Few particles: one tile, most keys empty.
    expectSameGrid<2>(std::vector<Vec<2>>(x.begin(), x.begin() + 70), h, "70 particles");
    expectSameGrid<2>(std::vector<Vec<2>>(x.begin(), x.begin() + 1), h, "one particle");
    expectSameGrid<2>(std::vector<Vec<2>>(), h, "no particle");
}

TEST_F(GpuFluidGridTest, DamBreak3DMatchesTheCpuGridExactly) {
    const float h = 0.1f;
    const std::vector<Vec<3>> x = damBreak<3>(0.04f, h, {0.4f, 0.6f, 0.4f}, {1.2f, 0.8f, 0.6f}, 30);
    ASSERT_GT(x.size(), 1024u);
    expectSameGrid<3>(x, h, "3D dam break");
}

// Particles far outside the capped grid window are clamped into its edge
// cells: floor, clamp and conversion in that order on both sides, at huge
// and infinite coordinates; and particles exactly on sub-cell boundaries,
// where a key computed even slightly differently (a GPU-only nudge of 1e-5
// sub-cells) changes the sub-cell, which the dam breaks' particles almost
// never sit close enough to a boundary to show.
TEST_F(GpuFluidGridTest, ClampedAndBoundaryParticlesMatchTheCpuGridExactly) {
    const float h = 0.06f;
    std::vector<Vec<2>> x = damBreak<2>(0.02f, h, {1.0f, 1.5f, 0.0f}, {3.0f, 2.0f, 0.0f}, 10);
    const std::size_t fluid = x.size();
    const float far[] = {-kInf, -3e38f, -1e12f, -2.5e6f, -1000.0f, -40.0f, 45.0f, 300.0f, 7e5f, 1e20f, 3e38f, kInf};
    for (float a : far) {
        for (float b : far) {
            x.push_back({a, b});
        }
        x.push_back({a, 0.5f});
        x.push_back({1.0f, a});
    }
    // On sub-cell boundaries near the window's edges (origin + k h).
    const gpu::FluidGridParams place = onCpu<2>(x, h).params;
    for (int k = -3; k <= 3; ++k) {
        const float h2 = 2.0f * h;
        x.push_back({place.origin.x + static_cast<float>(k) * h, place.origin.y});
        x.push_back({place.origin.x + static_cast<float>(place.cells.x) * h2 + static_cast<float>(k) * h,
                     place.origin.y + static_cast<float>(place.cells.y) * h2 + static_cast<float>(k) * h});
    }
    // The far particles must stretch the grid past its cell budget, so the
    // window is capped and they really are clamped.
    std::size_t outside = 0;
    for (std::size_t i = fluid; i < x.size(); ++i) {
        for (int a = 0; a < 2; ++a) {
            const float end = place.origin[a] + static_cast<float>(place.cells[a]) * 2.0f * h;
            if (x[i][a] < place.origin[a] || x[i][a] >= end) {
                ++outside;
                break;
            }
        }
    }
    EXPECT_GT(outside, 150u);
    expectSameGrid<2>(x, h, "clamped");
}

}  // namespace
}  // namespace spindrift
