// Inputs shared by the CPU and GPU back-to-front sort tests.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace spindrift::test {

/// Random positions mixing the hard cases: wide and tiny magnitudes, negative
/// depths, exact duplicates, points at depth +-0, huge values (some depths
/// overflow to +-inf), a few infinities.
inline std::vector<glm::vec3> hardPositions(std::size_t n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> kind(0, 15);
    std::vector<glm::vec3> p;
    p.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 v(unit(rng), unit(rng), unit(rng));
        switch (kind(rng)) {
            case 0: v *= 1e-30f; break;                                   // tiny
            case 1: v *= 3e38f; break;                                    // huge: overflow
            case 2: v.z = (rng() & 1) ? 0.0f : -0.0f; v.x = v.y = 0; break;  // depth +-0
            case 3: v.z = (rng() & 1) ? 0.0f : -0.0f; break;              // +-0 and sums
            case 4: if (!p.empty()) { v = p[rng() % p.size()]; } break;   // duplicate
            case 5: v = glm::vec3(0.0f, 0.0f, static_cast<float>(rng() % 4)); break;  // ties
            case 6: v *= 1e6f; break;
            case 7: if (rng() % 64 == 0) { v.z = (rng() & 1) ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity(); } break;
            default: v *= 100.0f; break;
        }
        p.push_back(v);
    }
    return p;
}

}  // namespace spindrift::test
