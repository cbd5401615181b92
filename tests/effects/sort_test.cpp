// Back-to-front sort and the radix sort under it, checked against std::stable_sort
// with a plain depth comparator (the independent reference).
#include "effects/sort.h"
#include "effects/sort_test_util.h"

#include <spindrift/world.h>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace {

using spindrift::RadixDigitBits;
using spindrift::test::hardPositions;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// The reference: depth = dot(p - eye, normalize(forward)) with glm, farthest
/// first, NaN depths last, ties in index order (std::stable_sort).
std::vector<std::uint32_t> referenceOrder(const std::vector<glm::vec3>& positions, glm::vec3 eye,
                                          glm::vec3 forward) {
    glm::vec3 f = glm::normalize(forward);
    std::vector<float> depth(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
        depth[i] = glm::dot(positions[i] - eye, f);
    }
    std::vector<std::uint32_t> order(positions.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        float da = depth[a];
        float db = depth[b];
        if (std::isnan(da)) {
            return false;
        }
        return std::isnan(db) || da > db;
    });
    return order;
}

bool isPermutation(const std::vector<std::uint32_t>& order) {
    std::vector<bool> seen(order.size(), false);
    for (std::uint32_t i : order) {
        if (i >= order.size() || seen[i]) {
            return false;
        }
        seen[i] = true;
    }
    return true;
}

// backToFrontKey works on the float's bits (src/kernels/sort_key.glsl, so the
// GPU can run it); here it is checked against the definition by float
// compares: -0 folded into +0 by adding +0, NaN found by x != x. All 2^32
// bit patterns agreed when this was written (a one-off run); the test walks a
// stride of them plus every pattern near the boundaries, fast enough for ASan.
TEST(SortBackToFront, KeyMatchesTheFloatCompareDefinition) {
    auto reference = [](float depth) {
        std::uint32_t nan = depth != depth ? 0xFFFFFFFFu : 0u;
        depth += 0.0f;  // -0 + +0 = +0
        std::uint32_t u = std::bit_cast<std::uint32_t>(depth);
        return (u >> 31 != 0 ? u : u ^ 0x7FFFFFFFu) | nan;
    };
    auto check = [&](std::uint32_t bits) {
        float depth = std::bit_cast<float>(bits);
        ASSERT_EQ(spindrift::backToFrontKey(depth), reference(depth)) << std::hex << bits;
    };
    for (std::uint64_t u = 0; u <= 0xFFFFFFFFull; u += 4099) {
        check(static_cast<std::uint32_t>(u));
    }
    for (std::uint32_t edge : {0x00000000u, 0x7F800000u, 0x80000000u, 0xFF800000u, 0xFFFFFFFFu}) {
        for (std::uint32_t d = 0; d < 64; ++d) {
            check(edge + d);
            check(edge - d);
        }
    }
}

TEST(SortBackToFront, FarthestFirstByHand) {
    // forward = -z (unnormalised): depth = -z, so the most negative z is farthest.
    std::vector<glm::vec3> p = {{0, 0, -1}, {5, 0, -10}, {0, 0, 3}, {0, -7, -5}, {0, 0, 0}};
    std::vector<std::uint32_t> order =
        spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -4.0f));
    EXPECT_EQ(order, (std::vector<std::uint32_t>{1, 3, 0, 4, 2}));
}

TEST(SortBackToFront, EyeOffsetDoesNotChangeOrderAlongView) {
    std::vector<glm::vec3> p = {{0, 0, 1}, {0, 0, 2}, {0, 0, 3}};
    // Looking along +z from z = 10: depth = z - 10 is negative for all three;
    // z = 3 has the largest depth, so it comes first.
    std::vector<std::uint32_t> order =
        spindrift::sortBackToFront(p, glm::vec3(0, 0, 10), glm::vec3(0, 0, 1));
    EXPECT_EQ(order, (std::vector<std::uint32_t>{2, 1, 0}));
}

TEST(SortBackToFront, TiesKeepIndexOrder) {
    std::vector<glm::vec3> p(1000, glm::vec3(1.0f, 2.0f, 3.0f));
    std::vector<std::uint32_t> expected(p.size());
    std::iota(expected.begin(), expected.end(), 0u);
    EXPECT_EQ(spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(0, 0, 1)), expected);
    // Two interleaved depths: each group in index order, farther group first.
    for (std::size_t i = 0; i < p.size(); i += 2) {
        p[i].z = 4.0f;
    }
    std::vector<std::uint32_t> order = spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(0, 0, 1));
    for (std::size_t i = 0; i < 500; ++i) {
        EXPECT_EQ(order[i], 2 * i);
        EXPECT_EQ(order[500 + i], 2 * i + 1);
    }
}

TEST(SortBackToFront, PlusAndMinusZeroDepthsTie) {
    // Depths +0 and -0 are equal, so index order decides, not the sign bit.
    // (-0, -0, -0) . (0, 0, 1) = -0 exactly; (0, 0, 0) gives +0.
    const glm::vec3 minusZero(-0.0f);
    std::vector<glm::vec3> p = {glm::vec3(0.0f), minusZero, glm::vec3(0.0f), minusZero,
                                {0, 0, -1.0f}, {0, 0, 1.0f}};
    ASSERT_TRUE(std::signbit(glm::dot(minusZero - glm::vec3(0.0f), glm::vec3(0, 0, 1))));
    std::vector<std::uint32_t> order =
        spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(0, 0, 1));
    EXPECT_EQ(order, (std::vector<std::uint32_t>{5, 0, 1, 2, 3, 4}));
    EXPECT_EQ(spindrift::backToFrontKey(0.0f), spindrift::backToFrontKey(-0.0f));
}

TEST(SortBackToFront, NaNDepthsGoLastInIndexOrder) {
    std::vector<glm::vec3> p = {{0, 0, kNaN}, {0, 0, -kInf}, {0, 0, 1}, {kNaN, 0, 0},
                                {0, 0, kInf}, {0, 0, -1}, {0, 0, -kNaN}};
    std::vector<std::uint32_t> order =
        spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(0, 0, 1));
    // +inf farthest, -inf nearest of the numbers, then NaNs (also x = NaN: NaN * 0).
    EXPECT_EQ(order, (std::vector<std::uint32_t>{4, 2, 5, 1, 0, 3, 6}));
}

TEST(SortBackToFront, MatchesStableSortOnRandomInputs) {
    const glm::vec3 eyes[] = {glm::vec3(0.0f), glm::vec3(3.5f, -2.0f, 10.0f)};
    const glm::vec3 forwards[] = {glm::vec3(0, 0, 1), glm::vec3(0.3f, -2.0f, 0.7f),
                                  glm::vec3(-1e-3f, 0, 0)};
    for (std::size_t n : {0u, 1u, 2u, 1000u, 100003u}) {
        std::vector<glm::vec3> p = hardPositions(n, static_cast<std::uint32_t>(n) + 7u);
        for (glm::vec3 eye : eyes) {
            for (glm::vec3 forward : forwards) {
                std::vector<std::uint32_t> expected = referenceOrder(p, eye, forward);
                for (RadixDigitBits bits : {RadixDigitBits::Eight, RadixDigitBits::Eleven}) {
                    std::vector<std::uint32_t> order =
                        spindrift::sortBackToFront(p, eye, forward, bits);
                    ASSERT_EQ(order.size(), n);
                    ASSERT_TRUE(isPermutation(order));
                    ASSERT_EQ(order, expected) << "n " << n << " bits " << static_cast<int>(bits);
                }
                EXPECT_EQ(spindrift::sortBackToFront(p, eye, forward), expected);
            }
        }
    }
}

TEST(SortBackToFront, FarthestFirstOnRandomInputs) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-50.0f, 50.0f);
    std::vector<glm::vec3> p(20000);
    for (glm::vec3& v : p) {
        v = glm::vec3(u(rng), u(rng), u(rng));
    }
    glm::vec3 eye(1, 2, 3);
    glm::vec3 forward(1, 1, -1);
    std::vector<std::uint32_t> order = spindrift::sortBackToFront(p, eye, forward);
    ASSERT_TRUE(isPermutation(order));
    // Checked in double precision: depths computed in float may round two
    // nearly-equal depths together, so allow a relative slack of a few ulps.
    glm::dvec3 f = glm::normalize(glm::dvec3(forward));
    double previous = std::numeric_limits<double>::infinity();
    for (std::uint32_t i : order) {
        double d = glm::dot(glm::dvec3(p[i]) - glm::dvec3(eye), f);
        EXPECT_LE(d, previous + 1e-4) << "index " << i;
        previous = d;
    }
    double first = glm::dot(glm::dvec3(p[order.front()]) - glm::dvec3(eye), f);
    double last = glm::dot(glm::dvec3(p[order.back()]) - glm::dvec3(eye), f);
    EXPECT_GT(first, 70.0);
    EXPECT_LT(last, -70.0);
}

TEST(SortBackToFront, SameResultForAnyThreadCount) {
    std::vector<glm::vec3> p = hardPositions(300001, 11);
    glm::vec3 eye(0.5f, 0.25f, -3.0f);
    glm::vec3 forward(0.2f, 0.1f, 1.0f);
    std::vector<std::uint32_t> expected = referenceOrder(p, eye, forward);
    for (int threads : {1, 2}) {
        tbb::task_arena arena(threads);
        std::vector<std::uint32_t> order;
        arena.execute([&] { order = spindrift::sortBackToFront(p, eye, forward); });
        EXPECT_EQ(order, expected) << threads << " threads";
    }
}

TEST(SortBackToFront, RejectsBadViews) {
    std::vector<glm::vec3> p(3, glm::vec3(1.0f));
    EXPECT_THROW(spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(0.0f)), spindrift::Error);
    EXPECT_THROW(spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(kNaN, 0, 1)),
                 spindrift::Error);
    EXPECT_THROW(spindrift::sortBackToFront(p, glm::vec3(kInf, 0, 0), glm::vec3(0, 0, 1)),
                 spindrift::Error);
    // Finite but extreme forward vectors are normalised, not rejected.
    EXPECT_EQ(spindrift::sortBackToFront(p, glm::vec3(0.0f), glm::vec3(0, 0, 1e-30f)).size(), 3u);
    glm::vec3 big = spindrift::normalizeViewDirection(glm::vec3(3e38f, 0, 3e38f));
    EXPECT_NEAR(big.x, std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(big.z, std::sqrt(0.5f), 1e-6f);
    glm::vec3 tiny = spindrift::normalizeViewDirection(glm::vec3(0, -1e-40f, 0));
    EXPECT_EQ(tiny, glm::vec3(0, -1, 0));
}

TEST(SortDepthKey, OrderMatchesDescendingDepth) {
    const float values[] = {kInf, 3e38f, 1e10f, 1.5f, 1.0f, std::nextafter(1.0f, 0.0f), 1e-30f,
                            std::numeric_limits<float>::denorm_min(), 0.0f, -0.0f,
                            -std::numeric_limits<float>::denorm_min(), -1e-30f, -1.0f, -1.5f,
                            -3e38f, -kInf, kNaN, -kNaN};
    for (float a : values) {
        for (float b : values) {
            bool aBeforeB = !std::isnan(a) && (std::isnan(b) || a > b);
            EXPECT_EQ(spindrift::backToFrontKey(a) < spindrift::backToFrontKey(b), aBeforeB)
                << a << " vs " << b;
        }
    }
    EXPECT_EQ(spindrift::backToFrontKey(kNaN), 0xFFFFFFFFu);
    EXPECT_EQ(spindrift::backToFrontKey(std::bit_cast<float>(0xFFC00001u)), 0xFFFFFFFFu);
}

/// Reference for the raw sort: stable sort of (key, index) pairs by key.
void expectRadixMatchesStableSort(std::vector<std::uint32_t> keys, RadixDigitBits bits) {
    std::vector<std::uint32_t> indices(keys.size());
    std::mt19937 rng(static_cast<std::uint32_t>(keys.size()));
    for (std::uint32_t& i : indices) {
        i = rng();  // arbitrary payload, not just 0..n-1
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        expected.emplace_back(keys[i], indices[i]);
    }
    std::stable_sort(expected.begin(), expected.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    spindrift::RadixSortScratch scratch;
    spindrift::radixSortKeyIndex(keys, indices, scratch, bits);
    ASSERT_EQ(keys.size(), expected.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
        ASSERT_EQ(keys[i], expected[i].first) << "at " << i;
        ASSERT_EQ(indices[i], expected[i].second) << "at " << i;
    }
}

TEST(SortRadix, MatchesStableSortOnKeyDistributions) {
    for (RadixDigitBits bits : {RadixDigitBits::Eight, RadixDigitBits::Eleven}) {
        for (std::size_t n : {0u, 1u, 2u, 1000u, 100003u, 200000u}) {
            std::mt19937 rng(static_cast<std::uint32_t>(n));
            std::vector<std::uint32_t> keys(n);
            // Full range: every pass runs (an even count with 8-bit digits, odd with 11).
            for (std::uint32_t& k : keys) k = rng();
            expectRadixMatchesStableSort(keys, bits);
            // Few distinct keys: many ties, stability matters.
            for (std::uint32_t& k : keys) k = rng() % 5;
            expectRadixMatchesStableSort(keys, bits);
            // Only the middle digit varies: all other passes are skipped (one pass).
            for (std::uint32_t& k : keys) k = 0xA5000042u | ((rng() & 0x7Fu) << 12);
            expectRadixMatchesStableSort(keys, bits);
            // Two varying digits (even count of executed passes).
            for (std::uint32_t& k : keys) k = 0x1200u | (rng() & 0xFF0000FFu);
            expectRadixMatchesStableSort(keys, bits);
            // All equal: nothing to do.
            std::fill(keys.begin(), keys.end(), 0xDEADBEEFu);
            expectRadixMatchesStableSort(keys, bits);
            // Already sorted and reverse sorted.
            std::iota(keys.begin(), keys.end(), 0u);
            expectRadixMatchesStableSort(keys, bits);
            std::reverse(keys.begin(), keys.end());
            expectRadixMatchesStableSort(keys, bits);
        }
    }
}

TEST(SortRadix, UnalignedSpansAndLargeInputs) {
    // Spans that start off a 64-byte line: the same offset for keys and indices
    // (write-combined with a shifted line phase) and different offsets (plain
    // scatter). 2.5M pairs need more than 32 blocks of 2^16, so blocks grow.
    struct Case {
        std::size_t n;
        std::size_t keyOffset;
        std::size_t indexOffset;
    };
    for (Case c : {Case{100003, 3, 3}, Case{100003, 1, 6}, Case{2500003, 5, 5}, Case{2500003, 0, 7}}) {
        std::mt19937 rng(static_cast<std::uint32_t>(c.n + c.keyOffset));
        std::vector<std::uint32_t> keyStorage(c.n + 16);
        std::vector<std::uint32_t> indexStorage(c.n + 16);
        std::span<std::uint32_t> keys(keyStorage.data() + c.keyOffset, c.n);
        std::span<std::uint32_t> indices(indexStorage.data() + c.indexOffset, c.n);
        std::vector<std::pair<std::uint32_t, std::uint32_t>> expected(c.n);
        for (std::size_t i = 0; i < c.n; ++i) {
            keys[i] = rng();
            indices[i] = static_cast<std::uint32_t>(i);
            expected[i] = {keys[i], indices[i]};
        }
        std::stable_sort(expected.begin(), expected.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        spindrift::RadixSortScratch scratch;
        spindrift::radixSortKeyIndex(keys, indices, scratch);
        bool same = true;
        for (std::size_t i = 0; i < c.n && same; ++i) {
            same = keys[i] == expected[i].first && indices[i] == expected[i].second;
        }
        EXPECT_TRUE(same) << "n " << c.n << " offsets " << c.keyOffset << ", " << c.indexOffset;
        // Nothing written outside the spans.
        for (std::size_t i = 0; i < c.keyOffset; ++i) EXPECT_EQ(keyStorage[i], 0u);
        for (std::size_t i = c.keyOffset + c.n; i < keyStorage.size(); ++i) EXPECT_EQ(keyStorage[i], 0u);
        for (std::size_t i = 0; i < c.indexOffset; ++i) EXPECT_EQ(indexStorage[i], 0u);
        for (std::size_t i = c.indexOffset + c.n; i < indexStorage.size(); ++i) EXPECT_EQ(indexStorage[i], 0u);
    }
}

TEST(SortRadix, ScratchIsReusedAcrossSizes) {
    spindrift::RadixSortScratch scratch;
    for (std::size_t n : {100000u, 10u, 150000u, 3u}) {
        std::mt19937 rng(static_cast<std::uint32_t>(n));
        std::vector<std::uint32_t> keys(n);
        std::vector<std::uint32_t> indices(n);
        for (std::size_t i = 0; i < n; ++i) {
            keys[i] = rng() % 1000;
            indices[i] = static_cast<std::uint32_t>(i);
        }
        std::vector<std::uint32_t> expected = indices;
        std::stable_sort(expected.begin(), expected.end(),
                         [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
        spindrift::radixSortKeyIndex(keys, indices, scratch);
        EXPECT_EQ(indices, expected);
        EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
    }
}

TEST(SortRadix, RejectsMismatchedSpans) {
    std::vector<std::uint32_t> keys(3);
    std::vector<std::uint32_t> indices(2);
    spindrift::RadixSortScratch scratch;
    EXPECT_THROW(spindrift::radixSortKeyIndex(keys, indices, scratch), spindrift::Error);
}

}  // namespace

// The quantised sort (16-bit depth keys, two passes): a permutation; any pair
// out of depth order lies within one bucket, (hi - lo) / 65534, of each other
// and keeps index order (stable within a bucket); NaN depths last; the same
// for 1 and 2 threads. Reference: the depths themselves, computed here.
namespace {

TEST(SortBackToFrontQuantised, OrderedToOneBucketAndStable) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-100.0f, 100.0f);
    const std::size_t n = 300'000;  // several blocks of the partition
    std::vector<glm::vec3> p(n);
    for (glm::vec3& v : p) {
        v = glm::vec3(unit(rng), unit(rng), unit(rng));
    }
    for (std::size_t i = 0; i < n; i += 97) {
        p[i] = p[i / 2];  // exact duplicates: ties
    }
    p[12345].x = std::numeric_limits<float>::quiet_NaN();
    const glm::vec3 eye(-150.0f, 0.0f, 0.0f);
    const glm::vec3 forward(1.0f, 0.2f, 0.1f);
    const glm::vec3 f = spindrift::normalizeViewDirection(forward);
    std::vector<std::uint32_t> order = spindrift::sortBackToFrontQuantised(p, eye, forward);
    ASSERT_EQ(order.size(), n);
    std::vector<std::uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(sorted[i], i);
    }
    std::vector<float> depth(n);
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < n; ++i) {
        depth[i] = glm::dot(p[i] - eye, f);
        if (std::isfinite(depth[i])) {
            lo = std::min(lo, depth[i]);
            hi = std::max(hi, depth[i]);
        }
    }
    EXPECT_EQ(order.back(), 12345u);  // the NaN depth
    // One bucket, plus rounding of the key's two float operations.
    const float bucket = (hi - lo) / 65534.0f * 1.01f;
    std::size_t inverted = 0;
    for (std::size_t k = 0; k + 2 < n; ++k) {
        const std::uint32_t a = order[k], b = order[k + 1];
        if (depth[a] < depth[b]) {
            ++inverted;
            EXPECT_LE(depth[b] - depth[a], bucket) << "position " << k;
            EXPECT_LT(a, b) << "position " << k;  // same bucket: index order
        }
    }
    EXPECT_GT(inverted, 0u);  // not vacuous: 300k depths share 65534 buckets
    tbb::task_arena one(1);
    std::vector<std::uint32_t> single;
    one.execute([&] { single = spindrift::sortBackToFrontQuantised(p, eye, forward); });
    EXPECT_EQ(single, order);
}

TEST(SortBackToFrontQuantised, EqualDepthsAndHardInputs) {
    std::vector<glm::vec3> same(5000, glm::vec3(1.0f, 2.0f, 3.0f));
    std::vector<std::uint32_t> order = spindrift::sortBackToFrontQuantised(same, glm::vec3(0.0f), glm::vec3(0, 0, 1));
    for (std::size_t i = 0; i < order.size(); ++i) {
        ASSERT_EQ(order[i], i);
    }
    // Infinite and overflowing depths: a permutation, every +inf depth
    // before every -inf one.
    std::vector<glm::vec3> hard = hardPositions(50'000, 3);
    order = spindrift::sortBackToFrontQuantised(hard, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    std::vector<std::uint32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) {
        ASSERT_EQ(sorted[i], i);
    }
    bool seenMinusInf = false;
    std::size_t infinities = 0;
    for (std::uint32_t i : order) {
        const float d = hard[i].z;
        if (d == std::numeric_limits<float>::infinity()) {
            EXPECT_FALSE(seenMinusInf);
            ++infinities;
        }
        if (d == -std::numeric_limits<float>::infinity()) {
            seenMinusInf = true;
            ++infinities;
        }
    }
    EXPECT_GT(infinities, 0u);
    EXPECT_THROW(spindrift::sortBackToFrontQuantised(hard, glm::vec3(0.0f), glm::vec3(0.0f)), spindrift::Error);
}

}  // namespace
