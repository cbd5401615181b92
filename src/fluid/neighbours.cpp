// Neighbour lists and constraint setup (slides 35 and 46-52), one pass: for
// every particle, the particles of the 3^D sub-cells around its own within h,
// each stored with its index and g = w * direction; its density, bias and
// effective mass; and the step's density statistics.
#include "core/cpu_target.h"
#include "fluid/fluid_state.h"

#include <algorithm>
#include <cmath>

#if SPINDRIFT_X86
#include <immintrin.h>
#endif

namespace spindrift::fluid {
namespace {

/// Lanes of the widest filter (AVX-512's 16 floats): blocks are padded to a
/// multiple, and near lists have this much room past their candidates.
constexpr std::size_t kNearLanes = 16;
/// A padding candidate's coordinates (m): its squared distance overflows to
/// infinity from any particle, so no filter keeps it.
constexpr float kFarAway = 1.0e30f;

struct ChunkStats {
    double errorSum = 0.0;
    double maxError = -1.0e30;
    ApproachHistogram approach{};
    std::uint64_t neighbourSum = 0;
    std::uint64_t overflows = 0;
};

/// Sub-cell coordinates of a key (fluid.glsl's fluidKeySubCell).
template <int D>
std::array<int, 3> subCellOf(const Grid<D>& g, std::uint32_t key) {
    const glm::ivec3 s = kernels::fluidKeySubCell(key, D, glm::ivec3(g.cells[0], g.cells[1], g.cells[2]));
    return {s.x, s.y, s.z};
}

template <int D>
std::uint32_t keyOfSubCell(const Grid<D>& g, int sx, int sy, int sz) {
    return kernels::fluidSubCellKey(glm::ivec3(sx, sy, sz), D, glm::ivec3(g.cells[0], g.cells[1], g.cells[2]));
}

/// The particles within h of the one being set up (phase 1 of the setup), as
/// structure of arrays: offset (m, from the particle to it) per axis and
/// index. Room for kNearLanes more than the candidates, so a vector filter
/// stores whole vectors past the last kept one. Not the squared distance:
/// the pairs compute it again from the offsets (nearR2), three operations
/// per neighbour, where keeping it cost the filter a compress and a store
/// per candidate (about three candidates per neighbour).
template <int D>
struct NearList {
    std::array<std::vector<float>, D> offset;
    std::vector<std::uint32_t> index;

    void reserve(std::size_t candidates) {
        const std::size_t room = candidates + kNearLanes;
        if (index.size() >= room) return;  // only grows: resizing zeroes every slot (measured, 15 % of the setup)
        const std::size_t size = std::max(2 * index.size(), room);
        for (std::vector<float>& axis : offset) axis.resize(size);
        index.resize(size);
    }
};

/// The particles of the 3^D sub-cells around one sub-cell, in sub-cell and
/// then grid order, as structure of arrays: phase 1's candidates for every
/// particle of that sub-cell (grid order keeps them consecutive), gathered
/// once for all of them instead of once per particle. Padded to a multiple
/// of kNearLanes with points far away (kFarAway), which no filter keeps.
/// `overflows`: the particles of crushed sub-cells left out
/// (kCrushedSubCell), counted for each particle.
template <int D>
struct CandidateBlock {
    std::uint32_t key = ~0u;  // the sub-cell it was gathered around
    std::uint32_t colour = 0;  // of that sub-cell's cell (Grid::colourCells)
    std::array<std::vector<float>, D> position;
    std::vector<std::uint32_t> index;
    std::size_t count = 0;  // candidates before the padding
    std::uint64_t overflows = 0;
};

/// A near list's and a candidate block's arrays as plain addresses, for the
/// vector filters' loops.
template <int D>
struct NearOut {
    float* offset[D];
    std::uint32_t* index;
};
template <int D>
NearOut<D> nearOut(NearList<D>& near) {
    NearOut<D> out{{}, near.index.data()};
    for (int a = 0; a < D; ++a) out.offset[a] = near.offset[a].data();
    return out;
}
template <int D>
struct BlockIn {
    const float* position[D];
    const std::uint32_t* index;
    std::size_t size;  // padded
};
template <int D>
BlockIn<D> blockIn(const CandidateBlock<D>& block) {
    BlockIn<D> in{{}, block.index.data(), block.index.size()};
    for (int a = 0; a < D; ++a) in.position[a] = block.position[a].data();
    return in;
}

/// Fills `block` with the candidates of the 3^D sub-cells around sub-cell
/// `key`. A sub-cell crushed past kCrushedSubCell times its count at rest
/// (fluid_state.h) is read only `readLimit` far: the rest count as
/// overflows. Without the bound a fluid squeezed into a point makes every
/// particle every other's neighbour, and a step costs seconds
/// (docs/fuzzing.md: a jet of 16,777,217 particles/s, a tank of zero width).
template <int D>
void gatherBlock(const Particles<D>& p, const Grid<D>& g, std::uint32_t key, std::uint32_t readLimit,
                 CandidateBlock<D>& block) {
    const int subCells[3] = {2 * g.cells[0], 2 * g.cells[1], D == 3 ? 2 * g.cells[2] : 1};
    const int zReach = D == 3 ? 1 : 0;
    block.key = key;
    block.overflows = 0;
    // The sub-cells' runs of grid order first, then one resize and plain
    // stores: a push_back per candidate checked the capacity each time
    // (measured, a sixth of the setup's time outside the filter and pairs).
    std::array<std::uint32_t, 27> runFirst{}, runLast{};
    std::size_t runs = 0, total = 0;
    const std::array<int, 3> sc = subCellOf<D>(g, key);
    // A cell is 2^D sub-cells, so its coordinates are the sub-cell's halved.
    block.colour = colourOf(static_cast<std::size_t>(sc[0] >> 1), static_cast<std::size_t>(sc[1] >> 1),
                            static_cast<std::size_t>(sc[2] >> 1));
    for (int dz = -zReach; dz <= zReach; ++dz) {
        const int sz = sc[2] + dz;
        if (sz < 0 || sz >= subCells[2]) continue;
        for (int dy = -1; dy <= 1; ++dy) {
            const int sy = sc[1] + dy;
            if (sy < 0 || sy >= subCells[1]) continue;
            for (int dx = -1; dx <= 1; ++dx) {
                const int sx = sc[0] + dx;
                if (sx < 0 || sx >= subCells[0]) continue;
                const std::uint32_t k = keyOfSubCell<D>(g, sx, sy, sz);
                const std::uint32_t first = g.keyStart[k];
                const std::uint32_t last = std::min(g.keyStart[k + 1], first + readLimit);
                block.overflows += g.keyStart[k + 1] - last;
                runFirst[runs] = first;
                runLast[runs] = last;
                total += last - first;
                ++runs;
            }
        }
    }
    block.count = total;
    const std::size_t padded = (total + kNearLanes - 1) / kNearLanes * kNearLanes;
    for (std::vector<float>& axis : block.position) axis.resize(padded);
    block.index.resize(padded);
    std::size_t at = 0;
    for (std::size_t r = 0; r < runs; ++r) {
        for (std::uint32_t j = runFirst[r]; j < runLast[r]; ++j, ++at) {
            for (int a = 0; a < D; ++a) block.position[a][at] = p.position[j][a];
            block.index[at] = j;
        }
    }
    for (; at < padded; ++at) {
        for (int a = 0; a < D; ++a) block.position[a][at] = kFarAway;
        block.index[at] = 0u;
    }
}

/// The squared length (m^2) of an offset as every filter and the pairs
/// compute it: glm's dot(offset, offset) with no fused multiply-add, so the
/// same float everywhere (the vector loops repeat these operations lane for
/// lane).
template <int D>
[[gnu::always_inline]] inline float squaredLength(const float (&offset)[D]) {
    float r2 = offset[0] * offset[0] + offset[1] * offset[1];
    if constexpr (D == 3) r2 = r2 + offset[2] * offset[2];
    return r2;
}

/// Writes to `near` [0, the returned count) the particles of `block` within h
/// of particle i (not i itself), in block order, with no branch on the
/// distance. The offsets and squared distances are those of glm's
/// `x_j - x_i` and `dot(offset, offset)` (no fused multiply-add), so every
/// filter keeps the same particles with the same values.
template <int D>
std::size_t filterNearScalar(const CandidateBlock<D>& block, const float* xi, std::uint32_t i, float h2,
                             NearList<D>& near) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < block.count; ++k) {
        float offset[D];
        for (int a = 0; a < D; ++a) offset[a] = block.position[a][k] - xi[a];
        const float r2 = squaredLength<D>(offset);
        for (int a = 0; a < D; ++a) near.offset[a][kept] = offset[a];
        near.index[kept] = block.index[k];
        kept += static_cast<std::size_t>(r2 < h2) & static_cast<std::size_t>(block.index[k] != i);
    }
    return kept;
}

#if SPINDRIFT_X86
/// filterNearScalar in 16 lanes: AVX-512's compress packs the kept lanes,
/// and a whole vector is stored (NearList has room past the end).
template <int D>
__attribute__((target("avx512f"))) std::size_t filterNearAvx512(const CandidateBlock<D>& block, const float* xi,
                                                                 std::uint32_t i, float h2, NearList<D>& near) {
    const __m512 limit = _mm512_set1_ps(h2);
    const __m512i self = _mm512_set1_epi32(static_cast<int>(i));
    __m512 origin[D];
    for (int a = 0; a < D; ++a) origin[a] = _mm512_set1_ps(xi[a]);
    // The addresses in locals: read through `near` after each store, g++
    // reloads them (it cannot tell the stores don't reach them), and those
    // reloads stalled behind the compressed stores (measured, two thirds of
    // the filter's time with two threads).
    const NearOut<D> out = nearOut(near);
    const BlockIn<D> in = blockIn(block);
    std::size_t kept = 0;
    for (std::size_t k = 0; k < in.size; k += 16) {
        __m512 offset[D];
        for (int a = 0; a < D; ++a) offset[a] = _mm512_sub_ps(_mm512_loadu_ps(in.position[a] + k), origin[a]);
        __m512 r2 = _mm512_add_ps(_mm512_mul_ps(offset[0], offset[0]), _mm512_mul_ps(offset[1], offset[1]));
        if constexpr (D == 3) r2 = _mm512_add_ps(r2, _mm512_mul_ps(offset[2], offset[2]));
        const __m512i index = _mm512_loadu_si512(in.index + k);
        const __mmask16 keep = _mm512_cmp_ps_mask(r2, limit, _CMP_LT_OQ) & _mm512_cmpneq_epi32_mask(index, self);
        for (int a = 0; a < D; ++a) _mm512_storeu_ps(out.offset[a] + kept, _mm512_maskz_compress_ps(keep, offset[a]));
        _mm512_storeu_si512(out.index + kept, _mm512_maskz_compress_epi32(keep, index));
        kept += static_cast<std::size_t>(__builtin_popcount(keep));
    }
    return kept;
}

/// For each 8-bit mask of kept lanes, the lanes' indices packed to the front:
/// AVX2 has no compress, so a permute by this row packs them.
struct PackTable {
    std::uint32_t lanes[256][8];
};
constexpr PackTable makePackTable() {
    PackTable t{};
    for (std::uint32_t mask = 0; mask < 256; ++mask) {
        std::uint32_t next = 0;
        for (std::uint32_t lane = 0; lane < 8; ++lane) {
            if ((mask >> lane) & 1u) t.lanes[mask][next++] = lane;
        }
    }
    return t;
}
constexpr PackTable kPackTable = makePackTable();

/// filterNearScalar in 8 lanes (AVX2), packed by kPackTable.
template <int D>
__attribute__((target("avx2"))) std::size_t filterNearAvx2(const CandidateBlock<D>& block, const float* xi,
                                                             std::uint32_t i, float h2, NearList<D>& near) {
    const __m256 limit = _mm256_set1_ps(h2);
    const __m256i self = _mm256_set1_epi32(static_cast<int>(i));
    __m256 origin[D];
    for (int a = 0; a < D; ++a) origin[a] = _mm256_set1_ps(xi[a]);
    const NearOut<D> out = nearOut(near);  // in locals, as in filterNearAvx512
    const BlockIn<D> in = blockIn(block);
    std::size_t kept = 0;
    for (std::size_t k = 0; k < in.size; k += 8) {
        __m256 offset[D];
        for (int a = 0; a < D; ++a) offset[a] = _mm256_sub_ps(_mm256_loadu_ps(in.position[a] + k), origin[a]);
        __m256 r2 = _mm256_add_ps(_mm256_mul_ps(offset[0], offset[0]), _mm256_mul_ps(offset[1], offset[1]));
        if constexpr (D == 3) r2 = _mm256_add_ps(r2, _mm256_mul_ps(offset[2], offset[2]));
        const __m256i index = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in.index + k));
        const int within = _mm256_movemask_ps(_mm256_cmp_ps(r2, limit, _CMP_LT_OQ));
        const int isSelf = _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(index, self)));
        const auto keep = static_cast<unsigned>(within & ~isSelf);
        const __m256i pack = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kPackTable.lanes[keep]));
        for (int a = 0; a < D; ++a) _mm256_storeu_ps(out.offset[a] + kept, _mm256_permutevar8x32_ps(offset[a], pack));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.index + kept), _mm256_permutevar8x32_epi32(index, pack));
        kept += static_cast<std::size_t>(__builtin_popcount(keep));
    }
    return kept;
}
#endif

/// Lanes of the pairs' loop (phase 2 of the setup): one particle's sums over
/// its pairs are kept per lane, 16 of them (AVX-512's width), and added as
/// one tree at the end (laneTree), so every target, whatever its vector
/// width (or none), adds the same numbers in the same order: bit-identical
/// results.
constexpr std::size_t kPairLanes = 16;

/// One particle's sums over its pairs.
template <int D>
struct PairSums {
    float density = 0.0f;  // the neighbours' W
    float mass = 0.0f;     // sum w^2
    float fastest = 0.0f;  // m/s, the fastest closing speed of a neighbour
    Vec<D> gSum{0.0f};
    Vec<D> warm{0.0f};     // m/s, the gathered warm start
};

/// What phase 2 reads for one particle: its near list, the particles'
/// velocities and pressures (gathered through the neighbours' indices), i's
/// own values and the setup's constants, as plain addresses and values (read
/// through a NearList inside a lane loop, g++ reloads them per lane and does
/// not vectorise it).
template <int D>
struct PairArrays {
    const std::uint32_t* index;
    const float* offset[D];         // m
    const float* velocity;          // the particles' velocities, D floats each (m/s)
    const float* pressure;          // the particles' last pressures (m/s)
    std::uint32_t i;
    float vi[D];                    // m/s
    float lambdaI;                  // i's warm-start pressure (m/s), scaled
    float warmFraction;
    float invH;
    float invH2;
};

/// The terms of near-list entry k, a pair of particle i and neighbour j.
template <int D>
struct PairTerm {
    float density;       // W(r / h)
    float w;             // the pair's weight
    float g[D];          // w * direction, from i to j
    float closing;       // m/s, how fast the two approach
    float warmPressure;  // m/s, lambda_i + lambda_j of the warm start
};

/// The squared distance (m^2) of near-list entry k: the same float the
/// filters kept the entry by (squaredLength).
template <int D>
[[gnu::always_inline]] inline float nearR2(const PairArrays<D>& a, std::size_t k) {
    float offset[D];
    for (int axis = 0; axis < D; ++axis) offset[axis] = a.offset[axis][k];
    return squaredLength<D>(offset);
}

/// `kClosing`: the closing speed too (it gathers the neighbour's velocity,
/// about a tenth of the setup's time, measured; only a step's first substep
/// counts it).
template <int D, bool kClosing>
[[gnu::always_inline]] inline PairTerm<D> pairTerm(const PairArrays<D>& a, std::size_t k) {
    PairTerm<D> t;
    const float r2 = nearR2(a, k);
    const std::uint32_t j = a.index[k];
    const float r = std::sqrt(r2);
    t.density = kernels::fluidDensityKernel(r * a.invH);
    const bool apart = r2 > 0.0f;
    const float invR = apart ? 1.0f / r : 0.0f;
    t.w = kernels::fluidWeight(r2, a.invH2);
    // A neighbour on top of i (r = 0) pushes along x (fluidPairGradient).
    const float side = kernels::fluidCoincidentSide(a.i, j);
    const float wOverR = t.w * invR;
    float closing = 0.0f;  // glm::dot(vi - v_j, offset), in glm's order
#pragma GCC unroll 3  // unrolled before the vectoriser sees the lane loop
    for (int axis = 0; axis < D; ++axis) {
        const float offset = a.offset[axis][k];
        t.g[axis] = kernels::fluidPairGradient(offset, t.w, wOverR, apart, axis == 0, side);
        if constexpr (kClosing) {
            const float approach = (a.vi[axis] - a.velocity[D * j + axis]) * offset;
            closing = axis == 0 ? approach : closing + approach;
        }
    }
    t.closing = closing * invR;
    t.warmPressure = a.lambdaI + a.pressure[j] * a.warmFraction;
    return t;
}

/// The sum of 16 lanes as a tree: lane l and l + 8, then l and l + 4, l and
/// l + 2, the last two. The order a 512-bit register's halves are added in,
/// so the hand-written AVX-512 loop (setUpPairsAvx512) reduces its
/// registers in four additions where adding the lanes in order took a chain
/// of sixteen per sum; every other target adds the same tree.
inline float laneTree(const float* lanes) {
    float half[8];
    for (std::size_t l = 0; l < 8; ++l) half[l] = lanes[l] + lanes[l + 8];
    for (std::size_t l = 0; l < 4; ++l) half[l] = half[l] + half[l + 4];
    for (std::size_t l = 0; l < 2; ++l) half[l] = half[l] + half[l + 2];
    return half[0] + half[1];
}

/// One particle's sums over its pairs, per lane: entry k of the near list
/// goes to lane k % kPairLanes. Not zeroed by itself (value-initialise it):
/// the baseline writes every lane, and zeroing it per particle was 4 % of
/// the setup there.
template <int D>
struct PairLanes {
    float density[kPairLanes];
    float mass[kPairLanes];
    float fastest[kPairLanes];
    float gSum[D][kPairLanes];
    float warm[D][kPairLanes];

    /// The lanes' sums as a tree (laneTree), the same on every target.
    PairSums<D> sum() const {
        PairSums<D> sums;
        sums.density = laneTree(density);
        sums.mass = laneTree(mass);
        for (std::size_t l = 0; l < kPairLanes; ++l) {
            sums.fastest = fastest[l] > sums.fastest ? fastest[l] : sums.fastest;
        }
        for (int a = 0; a < D; ++a) {
            sums.gSum[a] = laneTree(gSum[a]);
            sums.warm[a] = laneTree(warm[a]);
        }
        return sums;
    }
};

/// Phase 2 for one particle: its near list's W summed into the density (all
/// `listed` of them) and its first `paired` neighbours' g = w * direction
/// written to `dst`, with their sums. A lane loop the vectoriser turns into
/// gathers where the target has them (AVX2, AVX-512); always inlined into
/// each of those targets' copies below.
template <int D, bool kClosing>
[[gnu::always_inline]] inline PairSums<D> setUpPairLanes(const PairArrays<D>& in, std::size_t listed,
                                                         std::size_t paired, Neighbour<D>* dst) {
    constexpr std::size_t L = kPairLanes;
    const PairArrays<D> arrays = in;  // a local copy: through the reference, the 3D loop stayed scalar
    PairLanes<D> lanes{};
    float g[D][L];
    for (std::size_t base = 0; base < listed; base += L) {
        // Lanes past `listed` read the near list's room past its end (valid
        // indices, finite values) and add nothing. Not `omp simd`: g++ 12
        // then unrolls the 16 lanes completely before the vectoriser sees
        // them, and `unroll 1` cannot be combined with it.
#pragma GCC unroll 1
        for (std::size_t l = 0; l < L; ++l) {
            const std::size_t k = base + l;
            const PairTerm<D> t = pairTerm<D, kClosing>(arrays, k);
            lanes.density[l] += k < listed ? t.density : 0.0f;
            // The pairs' sums are masked by a factor (x 1 or x 0: the terms
            // are finite), not a select each: g++ 12 if-converts a few
            // selects on one condition and leaves more as branches.
            const float pairedFactor = k < paired ? 1.0f : 0.0f;
            for (int a = 0; a < D; ++a) {
                g[a][l] = t.g[a];
                lanes.gSum[a][l] += t.g[a] * pairedFactor;
                lanes.warm[a][l] -= t.g[a] * t.warmPressure * pairedFactor;
            }
            if constexpr (kClosing) {
                const float closing = k < paired ? t.closing : 0.0f;  // the fastest starts at 0
                lanes.fastest[l] = closing > lanes.fastest[l] ? closing : lanes.fastest[l];
            }
            lanes.mass[l] += t.w * t.w * pairedFactor;
        }
        const std::size_t stored = paired > base ? std::min(L, paired - base) : 0;
        for (std::size_t l = 0; l < stored; ++l) {
            Neighbour<D>& out = dst[base + l];
            for (int a = 0; a < D; ++a) out.g[a] = g[a][l];
            out.index = arrays.index[base + l];
        }
    }
    return lanes.sum();
}

/// setUpPairLanes for targets without gathers (SSE2, SSE4.2, and the scalar
/// target), lane by lane: each lane's entries in the same order, summed in
/// registers (a masked lane adds exactly nothing), so the same bits without
/// computing lanes past the list. Summed into an array indexed by k % 16
/// instead, the setup was 20 % slower than the scalar loop before the lanes.
template <int D, bool kClosing>
PairSums<D> setUpPairsBaseline(const PairArrays<D>& arrays, std::size_t listed, std::size_t paired,
                               Neighbour<D>* dst) {
    PairLanes<D> lanes;
    for (std::size_t l = 0; l < kPairLanes; ++l) {  // every lane: a lane past the list gets zeros
        float density = 0.0f;
        float mass = 0.0f;
        float fastest = 0.0f;
        float gSum[D] = {};
        float warm[D] = {};
        std::size_t k = l;
        for (; k < paired; k += kPairLanes) {
            const PairTerm<D> t = pairTerm<D, kClosing>(arrays, k);
            density += t.density;
            for (int a = 0; a < D; ++a) {
                dst[k].g[a] = t.g[a];
                gSum[a] += t.g[a];
                warm[a] -= t.g[a] * t.warmPressure;
            }
            dst[k].index = arrays.index[k];
            if constexpr (kClosing) fastest = t.closing > fastest ? t.closing : fastest;
            mass += t.w * t.w;
        }
        for (; k < listed; k += kPairLanes) density += pairTerm<D, false>(arrays, k).density;
        lanes.density[l] = density;
        lanes.mass[l] = mass;
        lanes.fastest[l] = fastest;
        for (int a = 0; a < D; ++a) {
            lanes.gSum[a][l] = gSum[a];
            lanes.warm[a][l] = warm[a];
        }
    }
    return lanes.sum();
}

#if SPINDRIFT_X86
/// Lanes [0, count) of an 8-lane register, all bits set (count may exceed 8).
__attribute__((target("avx2"))) inline __m256 firstLanes8(std::size_t count) {
    const int lanes = static_cast<int>(std::min<std::size_t>(count, 8));
    return _mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(lanes), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
}

/// One particle's sums over the lanes of half of the 16 (kPairLanes): lanes
/// 0 to 7 or 8 to 15.
struct PairHalf2 {
    __m256 density, mass, fastest, gSum[2], warm[2];
};

/// Register o (0 to 2) of the 2D Neighbour entries of 8 lanes (gx, gy,
/// index): lane l is float p = 8 o + l, component p % 3 of entry p / 3;
/// `entry` holds p / 3 for each lane, kFromY and kFromIndex have bit l set
/// where the component is 1 (gy) or 2 (the index). Stores its first
/// `floats` floats (masked: nothing past them).
template <int kFromY, int kFromIndex>
__attribute__((target("avx2"))) inline void storeEntryFloats(float* out, __m256i entry, __m256 gx, __m256 gy,
                                                             __m256 index, std::size_t floats) {
    const __m256 g = _mm256_blend_ps(_mm256_permutevar8x32_ps(gx, entry), _mm256_permutevar8x32_ps(gy, entry), kFromY);
    const __m256 e = _mm256_blend_ps(g, _mm256_permutevar8x32_ps(index, entry), kFromIndex);
    if (floats >= 8) {
        _mm256_storeu_ps(out, e);
    } else if (floats > 0) {
        _mm256_maskstore_ps(out, _mm256_castps_si256(firstLanes8(floats)), e);
    }
}

/// Writes lanes [0, stored) of (gx, gy) and the indices (stored may exceed
/// 8) as 2D Neighbour entries (12 bytes: gx, gy, index), 8 entries in three
/// registers, each from one permute of each source and two blends.
__attribute__((target("avx2"))) inline void storeEntries2Avx2(Neighbour<2>* dst, __m256 gx, __m256 gy, __m256 index,
                                                              std::size_t stored) {
    float* out = &dst[0].g.x;
    const std::size_t floats = 3 * std::min<std::size_t>(stored, 8);
    storeEntryFloats<0b10010010, 0b00100100>(out, _mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2), gx, gy, index, floats);
    if (floats <= 8) return;
    storeEntryFloats<0b00100100, 0b01001001>(out + 8, _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5), gx, gy, index,
                                             floats - 8);
    if (floats <= 16) return;
    storeEntryFloats<0b01001001, 0b10010010>(out + 16, _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7), gx, gy, index,
                                             floats - 16);
}

/// The sum (or with kMax the largest) of 16 lanes held as two halves, in
/// laneTree's order: lane l and l + 8, then l + 4, l + 2, the last two.
template <bool kMax>
__attribute__((target("avx2"))) inline float reduceHalves(__m256 low, __m256 high) {
    const __m256 eight = kMax ? _mm256_max_ps(low, high) : _mm256_add_ps(low, high);
    const __m128 left = _mm256_castps256_ps128(eight);
    const __m128 right = _mm256_extractf128_ps(eight, 1);
    const __m128 four = kMax ? _mm_max_ps(left, right) : _mm_add_ps(left, right);
    const __m128 two = kMax ? _mm_max_ps(four, _mm_movehl_ps(four, four)) : _mm_add_ps(four, _mm_movehl_ps(four, four));
    const __m128 last = _mm_shuffle_ps(two, two, 1);
    return _mm_cvtss_f32(kMax ? _mm_max_ss(two, last) : _mm_add_ss(two, last));
}

/// Entries [at, at + 8) of a 2D particle's near list into the lanes of
/// `half` (setUpPairsAvx512's operations, lane for lane).
template <bool kClosing>
__attribute__((target("avx2"), always_inline)) inline void addPairHalf2(const PairArrays<2>& a, std::size_t at,
                                                                        std::size_t listed, std::size_t paired,
                                                                        Neighbour<2>* dst, PairHalf2& half) {
    const __m256 zero = _mm256_setzero_ps();
    const __m256 one = _mm256_set1_ps(1.0f);
    const __m256 inList = firstLanes8(listed - at);
    const __m256 inPairs = paired > at ? firstLanes8(paired - at) : zero;
    const __m256 offset[2] = {_mm256_loadu_ps(a.offset[0] + at), _mm256_loadu_ps(a.offset[1] + at)};
    const __m256 r2 =
        _mm256_add_ps(_mm256_mul_ps(offset[0], offset[0]), _mm256_mul_ps(offset[1], offset[1]));  // nearR2
    const __m256i index = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(a.index + at));
    const __m256 r = _mm256_sqrt_ps(r2);
    // W(r / h) (fluidDensityKernel), in its order of operations.
    const __m256 d = _mm256_mul_ps(r, _mm256_set1_ps(a.invH));
    const __m256 d2 = _mm256_mul_ps(d, d);
    const __m256 d3 = _mm256_mul_ps(d2, d);
    const __m256 fifth = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.6f), d3), d2);
    const __m256 seventh = _mm256_mul_ps(_mm256_mul_ps(_mm256_mul_ps(d3, d2), d2), _mm256_set1_ps(1.0f / 7.0f));
    const __m256 inner = _mm256_sub_ps(_mm256_add_ps(_mm256_sub_ps(d, d3), fifth), seventh);
    const __m256 kernel = _mm256_sub_ps(one, _mm256_mul_ps(_mm256_set1_ps(2.1875f), inner));
    half.density = _mm256_blendv_ps(half.density, _mm256_add_ps(half.density, kernel), inList);
    // w (fluidWeight), 1 / r and g (fluidPairGradient).
    const __m256 apart = _mm256_cmp_ps(r2, zero, _CMP_GT_OQ);
    const __m256 invR = _mm256_and_ps(apart, _mm256_div_ps(one, r));
    const __m256 q = _mm256_sub_ps(one, _mm256_mul_ps(r2, _mm256_set1_ps(a.invH2)));
    const __m256 w = _mm256_and_ps(_mm256_cmp_ps(q, zero, _CMP_GT_OQ), _mm256_mul_ps(_mm256_mul_ps(q, q), q));
    const __m256 wOverR = _mm256_mul_ps(w, invR);
    // fluidCoincidentSide: +1 where j > i, as unsigned numbers (the sign
    // bits flipped for AVX2's signed comparison).
    const __m256i flip = _mm256_set1_epi32(static_cast<int>(0x80000000u));
    const __m256 above = _mm256_castsi256_ps(_mm256_cmpgt_epi32(
        _mm256_xor_si256(index, flip), _mm256_xor_si256(_mm256_set1_epi32(static_cast<int>(a.i)), flip)));
    const __m256 side = _mm256_blendv_ps(_mm256_set1_ps(-1.0f), one, above);
    const __m256 pressure = _mm256_mask_i32gather_ps(zero, a.pressure, index, inPairs, 4);
    const __m256 warmPressure =
        _mm256_add_ps(_mm256_set1_ps(a.lambdaI), _mm256_mul_ps(pressure, _mm256_set1_ps(a.warmFraction)));
    __m256 g[2];
    __m256 closing = zero;
    for (int axis = 0; axis < 2; ++axis) {
        const __m256 together = axis == 0 ? _mm256_mul_ps(side, w) : zero;
        g[axis] = _mm256_blendv_ps(together, _mm256_mul_ps(offset[axis], wOverR), apart);
        half.gSum[axis] = _mm256_blendv_ps(half.gSum[axis], _mm256_add_ps(half.gSum[axis], g[axis]), inPairs);
        half.warm[axis] = _mm256_blendv_ps(
            half.warm[axis], _mm256_sub_ps(half.warm[axis], _mm256_mul_ps(g[axis], warmPressure)), inPairs);
        if constexpr (kClosing) {
            const __m256i component = _mm256_add_epi32(_mm256_slli_epi32(index, 1), _mm256_set1_epi32(axis));
            const __m256 vj = _mm256_mask_i32gather_ps(zero, a.velocity, component, inPairs, 4);
            const __m256 approach = _mm256_mul_ps(_mm256_sub_ps(_mm256_set1_ps(a.vi[axis]), vj), offset[axis]);
            closing = axis == 0 ? approach : _mm256_add_ps(closing, approach);
        }
    }
    if constexpr (kClosing) {
        half.fastest = _mm256_max_ps(_mm256_and_ps(inPairs, _mm256_mul_ps(closing, invR)), half.fastest);
    }
    half.mass = _mm256_blendv_ps(half.mass, _mm256_add_ps(half.mass, _mm256_mul_ps(w, w)), inPairs);
    if (paired > at) storeEntries2Avx2(dst + at, g[0], g[1], _mm256_castsi256_ps(index), paired - at);
}

/// The pairs' loop of a 2D fluid with AVX2 intrinsics: setUpPairsAvx512's
/// operations with each 16-lane register as two halves of 8, so the same
/// bits; the sums stay in registers.
template <bool kClosing>
__attribute__((target("avx2"))) PairSums<2> setUpPairs2Avx2(const PairArrays<2>& arrays, std::size_t listed,
                                                            std::size_t paired, Neighbour<2>* dst) {
    const PairArrays<2> a = arrays;  // a copy the stores cannot reach (setUpPairsAvx512)
    PairHalf2 low{}, high{};
    for (std::size_t base = 0; base < listed; base += 16) {
        addPairHalf2<kClosing>(a, base, listed, paired, dst, low);
        if (base + 8 < listed) addPairHalf2<kClosing>(a, base + 8, listed, paired, dst, high);
    }
    PairSums<2> sums;
    sums.density = reduceHalves<false>(low.density, high.density);
    sums.mass = reduceHalves<false>(low.mass, high.mass);
    if constexpr (kClosing) sums.fastest = reduceHalves<true>(low.fastest, high.fastest);
    for (int axis = 0; axis < 2; ++axis) {
        sums.gSum[axis] = reduceHalves<false>(low.gSum[axis], high.gSum[axis]);
        sums.warm[axis] = reduceHalves<false>(low.warm[axis], high.warm[axis]);
    }
    return sums;
}

/// The pairs' copy for AVX2: written by hand in 2D, the compiled lanes in 3D.
template <int D, bool kClosing>
__attribute__((target("avx2"))) PairSums<D> setUpPairsAvx2(const PairArrays<D>& arrays, std::size_t listed,
                                                           std::size_t paired, Neighbour<D>* dst) {
    if constexpr (D == 2) {
        return setUpPairs2Avx2<kClosing>(arrays, listed, paired, dst);
    } else {
        return setUpPairLanes<D, kClosing>(arrays, listed, paired, dst);
    }
}

#define SD_PAIRS_AVX512 "avx512f,avx512vl,avx512bw,avx512dq"

/// A register's 16 lanes reduced in laneTree's order: their sum, or with
/// kMax their largest (the closing speeds: all >= 0, the lanes start at 0).
template <bool kMax>
__attribute__((target(SD_PAIRS_AVX512))) inline float reduceLanes512(__m512 v) {
    return reduceHalves<kMax>(_mm512_maskz_extractf32x8_ps(0xff, v, 0), _mm512_maskz_extractf32x8_ps(0xff, v, 1));
}

/// Lanes [0, count) of a 16-lane mask (count may exceed 16).
inline __mmask16 firstLanes(std::size_t count) {
    return count >= 16 ? static_cast<__mmask16>(0xffff) : static_cast<__mmask16>((1u << count) - 1u);
}

/// Writes lanes [0, stored) of (gx, gy) and the indices as 2D Neighbour
/// entries (12 bytes: gx, gy, index), 16 entries in three registers: two
/// permutes each, and masked stores that touch nothing past `stored`.
__attribute__((target(SD_PAIRS_AVX512))) inline void storeEntries2(Neighbour<2>* dst, __m512 gx, __m512 gy,
                                                                   __m512i index, std::size_t stored) {
    // Float p of the 48 is component p % 3 of entry p / 3. First gx and gy
    // (an index of 16 + e picks gy's lane e), then the indices' lanes.
    alignas(64) static constexpr std::array<std::array<std::int32_t, 16>, 3> kG = [] {
        std::array<std::array<std::int32_t, 16>, 3> t{};
        for (int o = 0; o < 3; ++o)
            for (int l = 0; l < 16; ++l) {
                const int p = 16 * o + l;
                t[o][l] = (p % 3 == 1 ? 16 : 0) + p / 3;  // the index lanes are filled next
            }
        return t;
    }();
    alignas(64) static constexpr std::array<std::array<std::int32_t, 16>, 3> kI = [] {
        std::array<std::array<std::int32_t, 16>, 3> t{};
        for (int o = 0; o < 3; ++o)
            for (int l = 0; l < 16; ++l) {
                const int p = 16 * o + l;
                t[o][l] = p % 3 == 2 ? 16 + p / 3 : l;  // l: keep the g lane already there
            }
        return t;
    }();
    float* out = &dst[0].g.x;
    const __m512 indexBits = _mm512_castsi512_ps(index);
    std::size_t floats = 3 * stored;
    for (int o = 0; o < 3 && floats > 0; ++o) {
        const __m512 g = _mm512_permutex2var_ps(gx, _mm512_load_si512(kG[static_cast<std::size_t>(o)].data()), gy);
        const __m512 entries =
            _mm512_permutex2var_ps(g, _mm512_load_si512(kI[static_cast<std::size_t>(o)].data()), indexBits);
        _mm512_mask_storeu_ps(out + 16 * o, firstLanes(floats), entries);
        floats -= std::min<std::size_t>(floats, 16);
    }
}

/// The pairs' loop written with AVX-512 intrinsics: the same operations,
/// lane for lane, as pairTerm and setUpPairLanes (no fused multiply-add, the
/// same order), so the same bits; the sums stay in registers (the compiled
/// lane loop kept them in memory, zeroed per particle) and are reduced by
/// laneTree's order. The neighbours' pressures (and velocities) are masked
/// gathers: only listed lanes read.
template <int D, bool kClosing>
__attribute__((target(SD_PAIRS_AVX512))) PairSums<D> setUpPairsAvx512(const PairArrays<D>& arrays, std::size_t listed,
                                                                      std::size_t paired, Neighbour<D>* dst) {
    // A copy the stores cannot reach: read through the reference after each
    // store, g++ reloaded the addresses, and those reloads stalled behind
    // the stores (measured, a third of the loop's time with two threads).
    const PairArrays<D> a = arrays;
    const __m512 zero = _mm512_setzero_ps();
    const __m512 one = _mm512_set1_ps(1.0f);
    const __m512 invH = _mm512_set1_ps(a.invH);
    const __m512 invH2 = _mm512_set1_ps(a.invH2);
    const __m512 lambdaI = _mm512_set1_ps(a.lambdaI);
    const __m512 warmFraction = _mm512_set1_ps(a.warmFraction);
    const __m512i self = _mm512_set1_epi32(static_cast<int>(a.i));
    __m512 density = zero, mass = zero, fastest = zero;
    __m512 gSum[D], warm[D];
    for (int axis = 0; axis < D; ++axis) gSum[axis] = warm[axis] = zero;
    for (std::size_t base = 0; base < listed; base += 16) {
        const __mmask16 inList = firstLanes(listed - base);
        const __mmask16 inPairs = paired > base ? firstLanes(paired - base) : static_cast<__mmask16>(0);
        __m512 offset[D];
        for (int axis = 0; axis < D; ++axis) offset[axis] = _mm512_loadu_ps(a.offset[axis] + base);
        __m512 r2 = _mm512_add_ps(_mm512_mul_ps(offset[0], offset[0]), _mm512_mul_ps(offset[1], offset[1]));  // nearR2
        if constexpr (D == 3) r2 = _mm512_add_ps(r2, _mm512_mul_ps(offset[2], offset[2]));
        const __m512i index = _mm512_loadu_si512(a.index + base);
        const __m512 r = _mm512_maskz_sqrt_ps(0xffff, r2);  // maskz: g++ 12 warns on the plain form's undefined source
        // W(r / h) (fluidDensityKernel), in its order of operations.
        const __m512 d = _mm512_mul_ps(r, invH);
        const __m512 d2 = _mm512_mul_ps(d, d);
        const __m512 d3 = _mm512_mul_ps(d2, d);
        const __m512 fifth = _mm512_mul_ps(_mm512_mul_ps(_mm512_set1_ps(0.6f), d3), d2);
        const __m512 seventh = _mm512_mul_ps(_mm512_mul_ps(_mm512_mul_ps(d3, d2), d2), _mm512_set1_ps(1.0f / 7.0f));
        const __m512 inner = _mm512_sub_ps(_mm512_add_ps(_mm512_sub_ps(d, d3), fifth), seventh);
        const __m512 kernel = _mm512_sub_ps(one, _mm512_mul_ps(_mm512_set1_ps(2.1875f), inner));
        density = _mm512_mask_add_ps(density, inList, density, kernel);
        // w (fluidWeight), 1 / r and g (fluidPairGradient).
        const __mmask16 apart = _mm512_cmp_ps_mask(r2, zero, _CMP_GT_OQ);
        const __m512 invR = _mm512_maskz_div_ps(apart, one, r);
        const __m512 q = _mm512_sub_ps(one, _mm512_mul_ps(r2, invH2));
        const __m512 w = _mm512_maskz_mul_ps(_mm512_cmp_ps_mask(q, zero, _CMP_GT_OQ), _mm512_mul_ps(q, q), q);
        const __m512 wOverR = _mm512_mul_ps(w, invR);
        const __m512 side = _mm512_mask_blend_ps(_mm512_cmpgt_epu32_mask(index, self), _mm512_set1_ps(-1.0f), one);
        const __m512 pressure = _mm512_mask_i32gather_ps(zero, inPairs, index, a.pressure, 4);
        const __m512 warmPressure = _mm512_add_ps(lambdaI, _mm512_mul_ps(pressure, warmFraction));
        __m512 g[D];
        __m512 closing = zero;
        for (int axis = 0; axis < D; ++axis) {
            const __m512 together = axis == 0 ? _mm512_mul_ps(side, w) : zero;
            g[axis] = _mm512_mask_blend_ps(apart, together, _mm512_mul_ps(offset[axis], wOverR));
            gSum[axis] = _mm512_mask_add_ps(gSum[axis], inPairs, gSum[axis], g[axis]);
            warm[axis] = _mm512_mask_sub_ps(warm[axis], inPairs, warm[axis], _mm512_mul_ps(g[axis], warmPressure));
            if constexpr (kClosing) {
                const __m512i at =
                    _mm512_add_epi32(_mm512_mullo_epi32(index, _mm512_set1_epi32(D)), _mm512_set1_epi32(axis));
                const __m512 vj = _mm512_mask_i32gather_ps(zero, inPairs, at, a.velocity, 4);
                const __m512 approach = _mm512_mul_ps(_mm512_sub_ps(_mm512_set1_ps(a.vi[axis]), vj), offset[axis]);
                closing = axis == 0 ? approach : _mm512_add_ps(closing, approach);
            }
        }
        if constexpr (kClosing) {
            fastest = _mm512_maskz_max_ps(0xffff, _mm512_maskz_mov_ps(inPairs, _mm512_mul_ps(closing, invR)), fastest);
        }
        mass = _mm512_mask_add_ps(mass, inPairs, mass, _mm512_mul_ps(w, w));
        const std::size_t stored = paired > base ? std::min<std::size_t>(16, paired - base) : 0;
        if constexpr (D == 2) {
            if (stored != 0) storeEntries2(dst + base, g[0], g[1], index, stored);
        } else {
            alignas(64) float lanes[D][16];
            alignas(64) std::uint32_t indices[16];
            for (int axis = 0; axis < D; ++axis) _mm512_store_ps(lanes[axis], g[axis]);
            _mm512_store_si512(indices, index);
            for (std::size_t l = 0; l < stored; ++l) {
                for (int axis = 0; axis < D; ++axis) dst[base + l].g[axis] = lanes[axis][l];
                dst[base + l].index = indices[l];
            }
        }
    }
    PairSums<D> sums;
    sums.density = reduceLanes512<false>(density);
    sums.mass = reduceLanes512<false>(mass);
    if constexpr (kClosing) sums.fastest = reduceLanes512<true>(fastest);
    for (int axis = 0; axis < D; ++axis) {
        sums.gSum[axis] = reduceLanes512<false>(gSum[axis]);
        sums.warm[axis] = reduceLanes512<false>(warm[axis]);
    }
    return sums;
}
#undef SD_PAIRS_AVX512

/// The copy of a setup phase (the filter, the pairs) for the process's
/// update target (core/cpu_target.h): AVX-512, AVX2, or the baseline for
/// every other one.
template <class Fn>
Fn forUpdateTarget(Fn baseline, Fn avx2, Fn avx512) {
    switch (updateTarget()) {
    case UpdateTarget::Avx512: return avx512;
    case UpdateTarget::Avx2: return avx2;
    default: return baseline;
    }
}
#endif

/// What the setup writes for each particle after its pairs, and reads to
/// do it, as plain addresses and values.
struct ParticleOutputs {
    const float* wallDensity;
    const glm::vec3* wallGradient;
    glm::vec3* warmVelocity;  // m/s
    float* invMass;
    float* bias;  // m/s
    std::uint32_t* count;
    std::uint32_t* first;      // Constraints::first
    std::uint32_t* listChunk;  // Constraints::listChunk
    float* density;  // over rest density
    float restDensity;
    float invRest;
    float relaxation;
    float baumgarte;
    float h;      // m
    float invDt;  // 1/s
};

/// The pairs' copy for the process's update target, with or without the
/// closing speeds.
template <int D>
auto pairsFor(bool closing) {
#if SPINDRIFT_X86
    return closing ? forUpdateTarget(&setUpPairsBaseline<D, true>, &setUpPairsAvx2<D, true>, &setUpPairsAvx512<D, true>)
                   : forUpdateTarget(&setUpPairsBaseline<D, false>, &setUpPairsAvx2<D, false>,
                                     &setUpPairsAvx512<D, false>);
#else
    return closing ? &setUpPairsBaseline<D, true> : &setUpPairsBaseline<D, false>;
#endif
}

}  // namespace

template <int D>
void setupConstraints(WorkerPool& pool, FluidState& f, float dt, bool countClosing, FluidStepStats& stats) {
    Particles<D>& p = f.particles<D>();
    const Grid<D>& g = f.grid<D>();
    NeighbourChunks<D>& lists = f.neighbours<D>();
    Constraints& c = f.constraints;
    const std::size_t n = p.size();
    const std::uint32_t cap = f.maxNeighbours;
    constexpr std::size_t kColours = std::size_t{1} << D;
    lists.resize(WorkerPool::chunkCount(n, kParticleChunk) * kColours);
    c.bias.resize(n);
    c.invMass.resize(n);
    c.count.resize(n);
    c.first.resize(n);
    c.listChunk.resize(n);
    c.warmVelocity.resize(n);
    // The warm start's scale and cap (solver.cpp, fluidWarmCap): the last
    // pressures are capped where they are kept, so the gathered and the
    // scattered warm start read the same.
    const WarmStart warm = warmStartOf(f, dt);
    c.warmFraction = warm.fraction;
    const float warmFraction = c.warmFraction;
    pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) p.pressure[i] = kernels::fluidCappedPressure(p.pressure[i], warm.cap);
    });

    const float h2 = f.h * f.h;
    const float invH2 = 1.0f / h2;
    const float invH = 1.0f / f.h;
    const float invDt = 1.0f / dt;
    const float invRest = 1.0f / f.restDensity;
    std::vector<ChunkStats> chunks(WorkerPool::chunkCount(n, kParticleChunk));
#if SPINDRIFT_X86
    const auto filter = forUpdateTarget(&filterNearScalar<D>, &filterNearAvx2<D>, &filterNearAvx512<D>);
#else
    const auto filter = &filterNearScalar<D>;
#endif
    const auto pairs = pairsFor<D>(countClosing);
    const ParticleOutputs outputs{c.wallDensity.data(),
                                  c.wallGradient.data(),
                                  c.warmVelocity.data(),
                                  c.invMass.data(),
                                  c.bias.data(),
                                  c.count.data(),
                                  c.first.data(),
                                  c.listChunk.data(),
                                  p.density.data(),
                                  f.restDensity,
                                  invRest,
                                  sweepRelaxation(f.def),
                                  f.def.baumgarte,
                                  f.h,
                                  invDt};

    pool.forChunks(n, kParticleChunk, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
        // What is read after each particle's pairs, copied in: read through
        // the lambda's captured references, each load waited behind the
        // pairs' stores (measured with two threads: a tenth of this loop's
        // time on the test of `countClosing` alone).
        const bool closing = countClosing;
        const auto pairsOf = pairs;
        const ParticleOutputs o = outputs;
        ChunkStats s;
        // The lists go to one array per colour of cell (NeighbourChunks), so
        // that a sweep, which visits the cells colour by colour, reads them
        // as one stream. In one array in grid order, a sweep read one cell's
        // lists and skipped the next's: the sweeps of a 30k dam break 10 to
        // 20 % slower, of a 100k one about a quarter (docs/fluid.md). Each
        // array's [0, used) is
        // this step's; the arrays keep their sizes from step to step and
        // only grow (the entries past `used` are stale, and no list reaches
        // them). Cleared and grown per particle, an array value-initialised
        // every entry before the pairs wrote it: measured, a fifth of the
        // setup's time outside the filter and the pairs.
        std::array<std::size_t, kColours> usedOf{};
        // The array being written and its `used`, swapped on a change of
        // colour only (once a sub-cell), so a particle's path reads them
        // from registers as it did with one array.
        std::uint32_t colour = 0;
        auto array = static_cast<std::uint32_t>(chunk * kColours);
        std::vector<Neighbour<D>>* out = &lists[array];
        std::size_t used = 0;
        NearList<D> near;
        CandidateBlock<D> block;
        for (std::size_t i = begin; i < end; ++i) {
            const Vec<D> xi = p.position[i];
            const Vec<D> vi = p.velocity[i];
            // Phase 1: the particles of the 3^D sub-cells around i that lie
            // within h, gathered with a store per candidate and no branch on
            // the distance (about a third pass in 2D, at random, so a branch
            // mispredicts often: measured, the setup was 60 % of a step).
            if (g.key[i] != block.key) {
                gatherBlock<D>(p, g, g.key[i], f.subCellReadLimit, block);
                near.reserve(block.index.size());
            }
            if (block.colour != colour) {
                usedOf[colour] = used;
                colour = block.colour;
                array = static_cast<std::uint32_t>(chunk * kColours + colour);
                out = &lists[array];
                used = usedOf[colour];
            }
            o.first[i] = static_cast<std::uint32_t>(used);
            o.listChunk[i] = array;
            s.overflows += block.overflows;
            const std::size_t nearCount = filter(block, &xi[0], static_cast<std::uint32_t>(i), h2, near);
            // Phase 2: the pairs within h, dense, in lanes (setUpPairLanes).
            // The warm start of the pairs is gathered: i's own constraint
            // gives i -g lambda_i per neighbour, neighbour j's gives it -g
            // lambda_j (g of the pair seen from j is -g), so i gains -g
            // (lambda_i + lambda_j) from each pair, the same sum the
            // scattered warm start makes when every list is symmetric.
            const float lambdaI = p.pressure[i] * warmFraction;
            const std::size_t paired = std::min<std::size_t>(nearCount, cap);
            s.overflows += nearCount - paired;
            if (out->size() < used + paired) out->resize(std::max(2 * out->size(), used + paired));
            PairArrays<D> arrays{near.index.data(),
                                 {},
                                 &p.velocity[0][0],
                                 p.pressure.data(),
                                 static_cast<std::uint32_t>(i),
                                 {},
                                 lambdaI,
                                 warmFraction,
                                 invH,
                                 invH2};
            for (int a = 0; a < D; ++a) {
                arrays.offset[a] = near.offset[a].data();
                arrays.vi[a] = vi[a];
            }
            PairSums<D> sums = pairsOf(arrays, nearCount, paired, out->data() + used);
            const auto count = static_cast<std::uint32_t>(paired);
            if (closing) s.approach[approachBin(sums.fastest)] += 1;
            o.count[i] = count;
            used += count;
            // The colliders' ghosts (wall_density.cpp): motionless
            // neighbours, so they add to the density and to the particle's
            // own Jacobian entry, -(sum g + wall). W(0) = 1 is the particle
            // itself.
            const float density = 1.0f + sums.density + o.wallDensity[i];
            sums.gSum += Vec<D>(o.wallGradient[i]);
            if (count != 0) sums.warm -= Vec<D>(o.wallGradient[i]) * lambdaI;  // the ghosts take no impulse
            glm::vec3 warm3(0.0f);
            for (int a = 0; a < D; ++a) warm3[a] = sums.warm[a];
            o.warmVelocity[i] = warm3;
            // Effective mass of the Jacobian (fluid.glsl).
            glm::vec3 gSum3(0.0f);
            for (int a = 0; a < D; ++a) gSum3[a] = sums.gSum[a];
            o.invMass[i] = kernels::fluidInverseMass(sums.mass, gSum3, o.relaxation);
            o.bias[i] = kernels::fluidBias(density, o.restDensity, o.baumgarte, o.h, o.invDt);
            const float relative = density * o.invRest;
            o.density[i] = relative;
            s.errorSum += std::max(relative - 1.0f, 0.0f);

            s.maxError = std::max<double>(s.maxError, relative - 1.0f);
            s.neighbourSum += count;
        }
        chunks[chunk] = s;
    });

    ChunkStats all;
    for (const ChunkStats& s : chunks) {  // chunk order: the same sums for any thread count
        all.errorSum += s.errorSum;
        all.maxError = std::max(all.maxError, s.maxError);
        for (std::size_t b = 0; b < all.approach.size(); ++b) all.approach[b] += s.approach[b];
        all.neighbourSum += s.neighbourSum;
        all.overflows += s.overflows;
    }

    const double count = static_cast<double>(std::max<std::size_t>(n, 1));
    stats.meanDensityError = all.errorSum / count;
    stats.maxDensityError = n > 0 ? all.maxError : 0.0;
    for (std::size_t b = 0; b < all.approach.size(); ++b) f.approach[b] += all.approach[b];
    stats.meanNeighbours = static_cast<double>(all.neighbourSum) / count;
    stats.neighbourOverflows += all.overflows;  // summed over the substeps
    c.warmGathered = all.overflows == 0;
}

template void setupConstraints<2>(WorkerPool&, FluidState&, float, bool, FluidStepStats&);
template void setupConstraints<3>(WorkerPool&, FluidState&, float, bool, FluidStepStats&);

}  // namespace spindrift::fluid
