// Back-to-front sorting: the depth -> key mapping and an LSD radix sort of
// (uint32 key, uint32 index) pairs, shared by sortBackToFront (world.h) and,
// later, the renderer.
//
// The radix sort is stable, so its result is unique: it is the same for every
// thread count and every partition of the work (tests/effects/sort_test.cpp
// checks 1 and 2 threads, and partitions of 1 to 20 blocks). It runs in the
// caller's oneTBB arena; wrap the call in a tbb::task_arena to limit threads.
#pragma once

#include "kernels/sort_key.glsl"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace spindrift {

/// Maps a view depth to a key whose ascending unsigned order is descending
/// depth (farthest first):
///   positive depths  -> 0x00000000 .. 0x7FFFFFFF (+inf is 0x007FFFFF),
///   +0 and -0        -> 0x7FFFFFFF (they are equal depths, so they tie),
///   negative depths  -> 0x80000000 .. 0xFF800000 (-inf is 0xFF800000),
///   NaN (any)        -> 0xFFFFFFFF: NaN depths sort last, after -inf.
/// Positives: flip every bit but the sign bit; negatives: keep the bits. That is
/// the usual order-preserving float -> uint map (flip the sign bit of positives,
/// all bits of negatives) with every bit then inverted, so that larger depths
/// come first. The one definition is kernels::backToFrontKey in
/// src/kernels/sort_key.glsl, which the GPU sort compiles too.
inline std::uint32_t backToFrontKey(float depth) noexcept { return kernels::backToFrontKey(depth); }

/// Digit width of the LSD radix sort. 8 bits: 4 passes of 256 buckets; 11 bits:
/// 3 passes (11, 11, 10 bits) of 2048 buckets. Passes whose digit is the same
/// for every key are skipped. docs/performance.md has the measurements that
/// chose the default.
enum class RadixDigitBits : std::uint8_t { Eight = 8, Eleven = 11 };
inline constexpr RadixDigitBits kDefaultRadixDigitBits = RadixDigitBits::Eight;

/// Memory reused by radixSortKeyIndex across calls: two key and two index
/// buffers for the passes between the first and the last (64-byte aligned, for
/// the streaming stores), and the count tables. It grows and never shrinks.
class RadixSortScratch {
public:
    /// Makes room for n pairs (no-op when already big enough).
    void reserve(std::size_t n);
    std::uint32_t* keys(int which) { return keys_[which].get(); }
    std::uint32_t* indices(int which) { return indices_[which].get(); }
    std::vector<std::uint32_t>& counts() { return counts_; }

private:
    struct AlignedDelete {
        void operator()(std::uint32_t* p) const;
    };
    using Buffer = std::unique_ptr<std::uint32_t[], AlignedDelete>;
    Buffer keys_[2];     // uninitialised on purpose
    Buffer indices_[2];  // (no zero-fill pass)
    std::size_t capacity_ = 0;
    std::vector<std::uint32_t> counts_;
};

/// Sorts the pairs (keys[i], indices[i]) by key, ascending and stable: pairs with
/// equal keys keep their relative order. On return both spans hold the sorted
/// pairs. keys.size() must equal indices.size() and be < 2^32; throws
/// spindrift::Error otherwise.
void radixSortKeyIndex(std::span<std::uint32_t> keys, std::span<std::uint32_t> indices,
                       RadixSortScratch& scratch,
                       RadixDigitBits digitBits = kDefaultRadixDigitBits);

/// sortBackToFront (world.h) with a chosen digit width, for bench/bench_sort.cpp.
std::vector<std::uint32_t> sortBackToFront(std::span<const glm::vec3> positions, glm::vec3 eye,
                                           glm::vec3 forward, RadixDigitBits digitBits);

/// Back-to-front order by depth quantised to 16 bits: the finite depths'
/// range [lo, hi] cut into 65534 equal buckets, farthest bucket first, a
/// bucket in index order (stable), NaN depths last. Two radix passes instead
/// of sortBackToFront's four, for a renderer that needs speed more than
/// exactness (docs/performance.md): a pair out of depth order is never more
/// than one bucket, (hi - lo) / 65534, apart. Checks its arguments as
/// sortBackToFront does.
std::vector<std::uint32_t> sortBackToFrontQuantised(std::span<const glm::vec3> positions, glm::vec3 eye,
                                                    glm::vec3 forward);

/// The unit view direction sortBackToFront uses: glm::normalize(forward), and
/// for a finite forward too large or too small for that, forward divided by its
/// largest |component| first. Throws spindrift::Error for a zero or non-finite
/// forward.
glm::vec3 normalizeViewDirection(glm::vec3 forward);

}  // namespace spindrift
