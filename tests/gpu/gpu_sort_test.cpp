// The GPU back-to-front sort against the CPU's sortBackToFront (itself checked
// against std::stable_sort in tests/effects/sort_test.cpp): the same order,
// exactly, for random positions, ties, signed zeros, NaNs and dead slots.
// Emitters through the public API: tests/gpu/emitter_sort_test.cpp.
#include "effects/sort.h"
#include "effects/sort_test_util.h"
#include "gpu/gpu_sort.h"
#include "gpu/vulkan_buffer.h"
#include "gpu_test_util.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace spindrift {
namespace {

using test::GpuTest;
using test::hardPositions;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// One validated device and sort for the whole suite.
class GpuSortTest : public test::GpuSuiteWith<gpu::GpuSort, &gpu::createGpuSort> {
protected:
    struct Result {
        std::vector<std::uint32_t> order;  // all count indices
        std::uint32_t live = 0;
    };

    // Uploads the positions (and ages), sorts on the device, reads back.
    static Result sortOnDevice(const std::vector<glm::vec3>& positions, glm::vec3 eye, glm::vec3 forward,
                               const std::vector<float>* ages = nullptr) {
        Shared& s = shared();
        gpu::Device& d = *s.device;
        const auto n = static_cast<std::uint32_t>(positions.size());
        gpu::Buffer p = gpu::createStorageBuffer(d, std::max<VkDeviceSize>(12u * n, 16u));
        gpu::Buffer a = gpu::createStorageBuffer(d, std::max<VkDeviceSize>(4u * n, 16u));
        std::vector<gpu::Transfer> up{{&p, const_cast<glm::vec3*>(positions.data()), 12u * n}};
        if (ages != nullptr) {
            up.push_back({&a, const_cast<float*>(ages->data()), 4u * n});
        }
        gpu::upload(d, up);
        gpu::SortInput in{&p, ages != nullptr ? &a : nullptr, n, eye, normalizeViewDirection(forward)};
        gpu::submitOnce(d, [&](VkCommandBuffer cmd) { gpu::recordSortBackToFront(*s.part, cmd, in); });
        Result r{gpu::readSortedIndices(*s.part, n), gpu::readLiveCount(*s.part)};
        gpu::destroyBuffer(d, p);
        gpu::destroyBuffer(d, a);
        return r;
    }
};

// Sizes around the tile (1024 keys) and the workgroup (64), 0 and 1.
TEST_F(GpuSortTest, RandomPositionsMatchTheCpuSortExactly) {
    const glm::vec3 eyes[] = {glm::vec3(0.0f), glm::vec3(3.5f, -2.0f, 10.0f)};
    const glm::vec3 forwards[] = {glm::vec3(0, 0, 1), glm::vec3(0.3f, -2.0f, 0.7f), glm::vec3(-1e-3f, 0, 0)};
    for (std::size_t n : {0u, 1u, 2u, 63u, 65u, 1000u, 1024u, 1025u, 5000u}) {
        std::vector<glm::vec3> p = hardPositions(n, static_cast<std::uint32_t>(n) + 11u);
        for (glm::vec3 eye : eyes) {
            for (glm::vec3 forward : forwards) {
                Result r = sortOnDevice(p, eye, forward);
                ASSERT_EQ(r.order, sortBackToFront(p, eye, forward)) << "n = " << n;
                EXPECT_EQ(r.live, n);
            }
        }
    }
}

// Many tiles, several scan segments per invocation, a count that is neither a
// power of two nor a multiple of the tile.
TEST_F(GpuSortTest, LargeInputMatchesTheCpuSortExactly) {
    std::vector<glm::vec3> p = hardPositions(100'003, 5u);
    const glm::vec3 eye(10.0f, 20.0f, -120.0f), forward(0.1f, -0.2f, 1.0f);
    EXPECT_EQ(sortOnDevice(p, eye, forward).order, sortBackToFront(p, eye, forward));
}

TEST_F(GpuSortTest, EqualDepthsAndSignedZerosKeepIndexOrder) {
    // 3000 points on two planes of equal depth, interleaved: each plane in
    // index order, the farther first.
    std::vector<glm::vec3> p(3000);
    for (std::size_t i = 0; i < p.size(); ++i) {
        p[i] = glm::vec3(static_cast<float>(i), 1.0f, i % 2 == 0 ? 4.0f : 2.0f);
    }
    Result r = sortOnDevice(p, glm::vec3(0.0f), glm::vec3(0, 0, 1));
    for (std::size_t i = 0; i < 1500; ++i) {
        ASSERT_EQ(r.order[i], 2 * i);
        ASSERT_EQ(r.order[1500 + i], 2 * i + 1);
    }
    // Depths +0 and -0 tie: index order, not the sign bit.
    const glm::vec3 minusZero(-0.0f);
    std::vector<glm::vec3> z = {glm::vec3(0.0f), minusZero, glm::vec3(0.0f), minusZero, {0, 0, -1.0f}, {0, 0, 1.0f}};
    EXPECT_EQ(sortOnDevice(z, glm::vec3(0.0f), glm::vec3(0, 0, 1)).order,
              (std::vector<std::uint32_t>{5, 0, 1, 2, 3, 4}));
}

TEST_F(GpuSortTest, NaNDepthsGoLastInIndexOrder) {
    std::vector<glm::vec3> p = {{0, 0, kNaN}, {0, 0, -kInf}, {0, 0, 1}, {kNaN, 0, 0},
                                {0, 0, kInf}, {0, 0, -1},    {0, 0, -kNaN}};
    EXPECT_EQ(sortOnDevice(p, glm::vec3(0.0f), glm::vec3(0, 0, 1)).order,
              (std::vector<std::uint32_t>{4, 2, 5, 1, 0, 3, 6}));
}

// With ages bound, dead slots (age < 0) follow every live one, NaN depths
// included, in index order; the live count is exact.
TEST_F(GpuSortTest, DeadSlotsGoLastAndAreNotCounted) {
    std::vector<glm::vec3> p = hardPositions(2500, 3u);
    p[7] = glm::vec3(kNaN);
    std::vector<float> ages(p.size());
    std::mt19937 rng(9u);
    for (float& a : ages) {
        a = rng() % 3 == 0 ? -1.0f : 0.5f;
    }
    ages[7] = 0.0f;  // live, NaN depth
    const glm::vec3 eye(1.0f, 2.0f, 3.0f), forward(0.0f, 1.0f, -1.0f);
    std::vector<glm::vec3> livePositions;
    std::vector<std::uint32_t> liveIndex, dead;
    for (std::uint32_t i = 0; i < p.size(); ++i) {
        if (ages[i] < 0.0f) {
            dead.push_back(i);
        } else {
            livePositions.push_back(p[i]);
            liveIndex.push_back(i);
        }
    }
    std::vector<std::uint32_t> expected = sortBackToFront(livePositions, eye, forward);
    for (std::uint32_t& i : expected) {
        i = liveIndex[i];
    }
    expected.insert(expected.end(), dead.begin(), dead.end());
    Result r = sortOnDevice(p, eye, forward, &ages);
    EXPECT_EQ(r.live, liveIndex.size());
    EXPECT_EQ(r.order, expected);
}

}  // namespace
}  // namespace spindrift
