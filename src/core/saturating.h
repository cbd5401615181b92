// Counts that must not wrap: births dropped for want of capacity can exceed
// any integer (a rate of 3e38 particles/s), and a wrapped count would report
// a few where there were more than can be counted.
#pragma once

#include <cstdint>
#include <limits>

namespace spindrift {

/// a + b, or the largest std::uint64_t if the sum does not fit.
constexpr std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
    return b > std::numeric_limits<std::uint64_t>::max() - a ? std::numeric_limits<std::uint64_t>::max() : a + b;
}

/// x >= 0 (a whole number in a double) as a count, saturating at the largest
/// std::uint64_t.
constexpr std::uint64_t saturatingCount(double x) {
    // 2^64 as a double; anything at or above it saturates.
    return x >= 18446744073709551616.0 ? std::numeric_limits<std::uint64_t>::max() : static_cast<std::uint64_t>(x);
}

}  // namespace spindrift
