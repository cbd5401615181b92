// Back-to-front sort: view-depth keys and an LSD radix sort of (key, index)
// pairs. See sort.h for the key map and the guarantees.
//
// Shape of the radix sort (n pairs, digits of 8 or 11 bits, the pairs cut
// into at most kMaxBlocks blocks of a power-of-two size, one task each):
//   1. count:   one read of the keys fills, per block, the digit histograms of
//               every pass at once; a pass whose digit is the same for all n
//               keys does nothing and is skipped;
//   2. passes:  per remaining pass: exclusive scan of the per-block counts over
//               (digit, block) in that order, then every block scatters its
//               pairs, in order, from its own offsets: the stable LSD order
//               whatever the number of blocks or threads. Then, unless it was
//               the last pass, every block counts the next pass's digit in the
//               new arrangement. (Counting during the scatter instead, per
//               destination block, measured no faster, and was more code.)
// The scatter goes through software write-combining: per digit, a cache line
// of keys and one of indices are filled in a small buffer and written out as
// whole lines with streaming stores. Plain scattered stores to 2 x 256 streams
// cost a read-for-ownership miss per line; measured on the 2-core benchmark
// machine, a pass of 1M pairs took about 7 ms plain, 2.2 ms like this
// (docs/performance.md).
//
// Over 500 lines: the exact sort and the quantised one (16-bit keys, two
// passes) share the radix machinery above (partition, tables, write-combined
// scatter), which is most of the file; split, it would be an internal header
// of templates for two short callers.
//
// sortBackToFront fuses the depth computation into step 1, does not read the
// indices in the first pass (they are 0, 1, 2 ...), and writes only indices,
// straight into the returned vector, in the last.
// Over 500 lines: the key map, the block layout, the counting, the scan and
// the write-combined scatter share one set of constants and scratch buffers;
// apart they would need a header of internals for a single caller.
#include "effects/sort.h"

#include <spindrift/effects.h>
#include <spindrift/world.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <numeric>
#include <string>

namespace spindrift {

namespace {

/// Blocks hold 2^shift pairs, shift >= kMinBlockShift, and there are at most
/// kMaxBlocks of them: enough tasks for a few threads, and small count tables.
/// The partition depends on n only; the stable result does not depend on it
/// at all.
constexpr unsigned kMinBlockShift = 16;
constexpr std::size_t kMaxBlocks = 32;

struct Partition {
    std::size_t n = 0;
    unsigned shift = kMinBlockShift;
    std::size_t blocks = 0;

    explicit Partition(std::size_t count) : n(count) {
        while (blockCount() > kMaxBlocks) {
            ++shift;
        }
        blocks = blockCount();
    }
    std::size_t blockCount() const { return (n + (std::size_t{1} << shift) - 1) >> shift; }
    std::size_t begin(std::size_t b) const { return b << shift; }
    std::size_t end(std::size_t b) const { return std::min(n, (b + 1) << shift); }
};

/// Calls fn(block, begin, end) for every block; in parallel when there is more
/// than one.
template <class Fn>
void forBlocks(const Partition& part, Fn&& fn) {
    if (part.blocks == 1) {
        fn(std::size_t{0}, std::size_t{0}, part.n);
    } else if (part.blocks > 1) {
#if defined(__SANITIZE_THREAD__)
        // ThreadSanitizer builds: oneTBB's synchronisation is invisible to
        // the sanitizer (core/plain_threads.h); the blocks run in order.
        for (std::size_t b = 0; b < part.blocks; ++b) fn(b, part.begin(b), part.end(b));
#else
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, part.blocks, 1),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              for (std::size_t b = r.begin(); b != r.end(); ++b) {
                                  fn(b, part.begin(b), part.end(b));
                              }
                          });
#endif
    }
}

/// Digits of Bits bits of keys of KeyBits bits (32, or 16 for the quantised
/// depths of sortBackToFrontQuantised: two passes instead of four).
template <int Bits, int KeyBits = 32>
struct Radix {
    static constexpr int kBits = Bits;
    static constexpr std::uint32_t kRadix = 1u << Bits;
    static constexpr std::uint32_t kMask = kRadix - 1;
    static constexpr int kPasses = (KeyBits + Bits - 1) / Bits;
    static std::uint32_t digit(std::uint32_t key, int pass) {
        return (key >> (pass * Bits)) & kMask;
    }
};

/// The count tables, in one allocation:
///   counts[block][pass][digit]: step 1 fills every pass for the input
///       arrangement; later, [block][p] is overwritten with the counts of pass
///       p for the arrangement pass p sorts from;
///   offsets[block][digit]: scatter offsets of the current pass.
template <class R>
struct Tables {
    std::size_t blocks;
    std::uint32_t* base;

    static std::size_t size(std::size_t blocks) {
        return blocks * (R::kPasses + 1) * std::size_t{R::kRadix};
    }
    std::uint32_t* counts(std::size_t block, int pass) const {
        return base + (block * R::kPasses + static_cast<std::size_t>(pass)) * R::kRadix;
    }
    std::uint32_t* offsets(std::size_t block) const {
        return base + (blocks * R::kPasses + block) * R::kRadix;
    }
};

template <class R>
Tables<R> makeTables(std::vector<std::uint32_t>& storage, std::size_t blocks) {
    storage.assign(Tables<R>::size(blocks), 0u);
    return {blocks, storage.data()};
}

/// Adds the digits of keys[begin, end) to the block's histograms of every pass.
template <class R>
void countAllPasses(const std::uint32_t* keys, std::size_t begin, std::size_t end,
                    std::uint32_t* blockCounts) {
    for (std::size_t i = begin; i < end; ++i) {
        std::uint32_t k = keys[i];
        for (int p = 0; p < R::kPasses; ++p) {
            ++blockCounts[static_cast<std::size_t>(p) * R::kRadix + R::digit(k, p)];
        }
    }
}

/// Passes whose digit differs between keys, least significant first.
template <class R>
std::vector<int> activePasses(const Tables<R>& t, std::size_t n) {
    std::vector<int> passes;
    std::vector<std::uint64_t> total(R::kRadix);
    for (int p = 0; p < R::kPasses; ++p) {
        std::fill(total.begin(), total.end(), 0u);
        for (std::size_t b = 0; b < t.blocks; ++b) {
            const std::uint32_t* c = t.counts(b, p);
            for (std::uint32_t d = 0; d < R::kRadix; ++d) {
                total[d] += c[d];
            }
        }
        bool constant = std::any_of(total.begin(), total.end(),
                                    [n](std::uint64_t c) { return c == n; });
        if (!constant) {
            passes.push_back(p);
        }
    }
    return passes;
}

/// Blocks shorter than this scatter directly, longer ones write-combine.
constexpr std::size_t kWriteCombineMinimum = 4096;

/// One cache line of 16 uint32 values.
struct alignas(64) Line {
    std::uint32_t v[16];
};

/// Position of 64-byte boundaries in an array of uint32: element p starts a
/// line when (p + phase) % 16 == 0.
std::uint32_t linePhase(const std::uint32_t* array) {
    return static_cast<std::uint32_t>(reinterpret_cast<std::uintptr_t>(array) / 4) & 15u;
}

/// Writes a buffered line to a 64-byte aligned line of the output with
/// streaming stores: a whole line needs no read-for-ownership.
inline void streamLine(std::uint32_t* out, const Line& line) {
#if defined(__SSE2__)
    auto* dst = reinterpret_cast<__m128i*>(out);
    const auto* src = reinterpret_cast<const __m128i*>(line.v);
    _mm_stream_si128(dst + 0, _mm_load_si128(src + 0));
    _mm_stream_si128(dst + 1, _mm_load_si128(src + 1));
    _mm_stream_si128(dst + 2, _mm_load_si128(src + 2));
    _mm_stream_si128(dst + 3, _mm_load_si128(src + 3));
#else
    std::memcpy(out, line.v, sizeof(line.v));
#endif
}

/// One pass's sources and destinations. indicesIn == nullptr: pair i has index
/// i. keysOut == nullptr: keys are not written.
struct PassIo {
    const std::uint32_t* keysIn;
    const std::uint32_t* indicesIn;
    std::uint32_t* keysOut;
    std::uint32_t* indicesOut;
    int shift;
};

/// Scatters the pairs [begin, end) of one block, in order, from the block's
/// offsets.
template <class R, bool Identity, bool WriteKeys>
void scatterBlock(const PassIo& io, std::size_t begin, std::size_t end,
                  const std::uint32_t* offsets) {
    const std::uint32_t* keysIn = io.keysIn;
    const std::uint32_t* indicesIn = io.indicesIn;
    std::uint32_t* keysOut = io.keysOut;
    std::uint32_t* indicesOut = io.indicesOut;
    const int shift = io.shift;
    auto indexAt = [indicesIn](std::size_t i) {
        if constexpr (Identity) {
            (void)indicesIn;  // clang's -Wunused-lambda-capture (the fuzz preset)
            return static_cast<std::uint32_t>(i);
        } else {
            return indicesIn[i];
        }
    };

    struct Buffers {
        std::uint32_t position[R::kRadix];
        Line keys[WriteKeys ? R::kRadix : 1];
        Line indices[R::kRadix];
    };
    const std::uint32_t phase = linePhase(indicesOut);
    const bool combine = end - begin >= kWriteCombineMinimum &&
                         (!WriteKeys || linePhase(keysOut) == phase);
    if (!combine) {
        std::vector<std::uint32_t> position(offsets, offsets + R::kRadix);
        for (std::size_t i = begin; i < end; ++i) {
            std::uint32_t k = keysIn[i];
            std::uint32_t at = position[(k >> shift) & R::kMask]++;
            if constexpr (WriteKeys) {
                keysOut[at] = k;
            }
            indicesOut[at] = indexAt(i);
        }
        return;
    }

    std::unique_ptr<Buffers> buffers(new Buffers);
    std::uint32_t* position = buffers->position;
    Line* keyLines = buffers->keys;
    Line* indexLines = buffers->indices;
    std::memcpy(position, offsets, sizeof(buffers->position));
    for (std::size_t i = begin; i < end; ++i) {
        std::uint32_t k = keysIn[i];
        std::uint32_t d = (k >> shift) & R::kMask;
        std::uint32_t at = position[d]++;
        std::uint32_t slot = (at + phase) & 15u;
        if constexpr (WriteKeys) {
            keyLines[d].v[slot] = k;
        }
        indexLines[d].v[slot] = indexAt(i);
        if (slot == 15u) {
            if (at - offsets[d] >= 15u) {  // the whole line is this block's
                if constexpr (WriteKeys) {
                    streamLine(keysOut + (at - 15u), keyLines[d]);
                }
                streamLine(indicesOut + (at - 15u), indexLines[d]);
            } else {  // the line starts in the range of another digit or block
                for (std::uint32_t q = offsets[d]; q <= at; ++q) {
                    if constexpr (WriteKeys) {
                        keysOut[q] = keyLines[d].v[(q + phase) & 15u];
                    }
                    indicesOut[q] = indexLines[d].v[(q + phase) & 15u];
                }
            }
        }
    }
    // What is left in the buffers: the last, partial line of every digit.
    for (std::uint32_t d = 0; d < R::kRadix; ++d) {
        std::uint32_t stop = position[d];
        std::uint32_t pending = std::min((stop + phase) & 15u, stop - offsets[d]);
        for (std::uint32_t q = stop - pending; q < stop; ++q) {
            if constexpr (WriteKeys) {
                keysOut[q] = keyLines[d].v[(q + phase) & 15u];
            }
            indicesOut[q] = indexLines[d].v[(q + phase) & 15u];
        }
    }
#if defined(__SSE2__)
    _mm_sfence();  // streaming stores are weakly ordered: publish before the join
#endif
}

/// Where the passes read and write. The first pass reads the input, the last
/// writes the output, the ones between alternate between the two 64-byte
/// aligned temporaries (pass j < last writes temporary j % 2).
struct PassPlan {
    const std::uint32_t* keysIn;
    const std::uint32_t* indicesIn;  // nullptr: 0, 1, 2 ...
    std::uint32_t* keysOut;          // nullptr: only indices are wanted
    std::uint32_t* indicesOut;
    std::uint32_t* keysTemp[2];
    std::uint32_t* indicesTemp[2];
};

/// Runs the passes; `t` holds the counts of every pass for the input
/// arrangement (step 1).
template <class R>
void runPasses(const Partition& part, const std::vector<int>& passes, const Tables<R>& t,
               const PassPlan& plan) {
    const std::size_t m = passes.size();
    for (std::size_t j = 0; j < m; ++j) {
        const int pass = passes[j];
        const bool last = j + 1 == m;
        PassIo io{};
        io.keysIn = j == 0 ? plan.keysIn : plan.keysTemp[(j - 1) % 2];
        io.indicesIn = j == 0 ? plan.indicesIn : plan.indicesTemp[(j - 1) % 2];
        io.keysOut = last ? plan.keysOut : plan.keysTemp[j % 2];
        io.indicesOut = last ? plan.indicesOut : plan.indicesTemp[j % 2];
        io.shift = pass * R::kBits;

        // Offsets: digit-major, block-minor exclusive scan (stability).
        std::uint32_t running = 0;
        for (std::uint32_t d = 0; d < R::kRadix; ++d) {
            for (std::size_t b = 0; b < part.blocks; ++b) {
                t.offsets(b)[d] = running;
                running += t.counts(b, pass)[d];
            }
        }

        const bool identity = io.indicesIn == nullptr;
        const bool writeKeys = io.keysOut != nullptr;
        forBlocks(part, [&](std::size_t b, std::size_t begin, std::size_t end) {
            const std::uint32_t* offsets = t.offsets(b);
            if (identity && writeKeys) {
                scatterBlock<R, true, true>(io, begin, end, offsets);
            } else if (identity) {
                scatterBlock<R, true, false>(io, begin, end, offsets);
            } else if (writeKeys) {
                scatterBlock<R, false, true>(io, begin, end, offsets);
            } else {
                scatterBlock<R, false, false>(io, begin, end, offsets);
            }
        });

        // The next pass's per-block counts, on the new arrangement.
        if (!last) {
            const int nextShift = passes[j + 1] * R::kBits;
            const std::uint32_t* keys = io.keysOut;
            forBlocks(part, [&](std::size_t b, std::size_t begin, std::size_t end) {
                std::uint32_t* counts = t.counts(b, passes[j + 1]);
                std::fill(counts, counts + R::kRadix, 0u);
                for (std::size_t i = begin; i < end; ++i) {
                    ++counts[(keys[i] >> nextShift) & R::kMask];
                }
            });
        }
    }
}

void checkSize(std::size_t n, const char* what) {
    if (n > std::numeric_limits<std::uint32_t>::max()) {
        throw Error(std::string(what) + ": " + std::to_string(n) +
                    " elements; at most 4294967295 (indices are 32-bit)");
    }
}

template <class R>
void radixSortKeyIndexImpl(std::span<std::uint32_t> keys, std::span<std::uint32_t> indices,
                           RadixSortScratch& scratch) {
    const Partition part(keys.size());
    Tables<R> t = makeTables<R>(scratch.counts(), part.blocks);
    forBlocks(part, [&](std::size_t b, std::size_t begin, std::size_t end) {
        countAllPasses<R>(keys.data(), begin, end, t.counts(b, 0));
    });
    std::vector<int> passes = activePasses<R>(t, part.n);
    if (passes.empty()) {
        return;
    }
    scratch.reserve(part.n);
    PassPlan plan{keys.data(), indices.data(), keys.data(), indices.data(),
                  {scratch.keys(0), scratch.keys(1)}, {scratch.indices(0), scratch.indices(1)}};
    if (passes.size() == 1) {
        // One pass cannot scatter in place: go through a temporary.
        plan.keysOut = scratch.keys(0);
        plan.indicesOut = scratch.indices(0);
    }
    runPasses<R>(part, passes, t, plan);
    if (passes.size() == 1) {
        forBlocks(part, [&](std::size_t, std::size_t begin, std::size_t end) {
            std::memcpy(keys.data() + begin, scratch.keys(0) + begin, (end - begin) * 4);
            std::memcpy(indices.data() + begin, scratch.indices(0) + begin, (end - begin) * 4);
        });
    }
}

/// keys[i] = backToFrontKey(dot(p[i] - eye, f)) for i in [begin, end), with the
/// depth and key of src/kernels/sort_key.glsl that the GPU sort uses too: a
/// separate loop from the counting, so that it vectorises.
void computeKeys(const glm::vec3* __restrict p, glm::vec3 eye, glm::vec3 f,
                 std::uint32_t* __restrict keys, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
        keys[i] = backToFrontKey(kernels::viewDepth(p[i], eye, f));
    }
}

/// sortBackToFront's working memory, kept per thread between calls (a renderer
/// sorts every frame): fresh multi-megabyte buffers on every call cost page
/// faults, about a fifth of the time of a 1M sort on the benchmark machine.
/// 16 bytes per position of the largest sort the thread has done, until the
/// thread ends.
RadixSortScratch& backToFrontScratch() {
    thread_local RadixSortScratch scratch;
    return scratch;
}

template <class R>
std::vector<std::uint32_t> sortBackToFrontImpl(std::span<const glm::vec3> positions,
                                               glm::vec3 eye, glm::vec3 forward) {
    const std::size_t n = positions.size();
    checkSize(n, "sortBackToFront");
    if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z)) {
        throw Error("sortBackToFront: eye must be finite");
    }
    const glm::vec3 f = normalizeViewDirection(forward);
    if (n == 0) {
        return {};
    }

    // Keys and the histograms of every pass, in one read of the positions. The
    // keys go to temporary 1: the first pass writes temporary 0, the second
    // overwrites temporary 1.
    RadixSortScratch& scratch = backToFrontScratch();
    scratch.reserve(n);
    const Partition part(n);
    Tables<R> t = makeTables<R>(scratch.counts(), part.blocks);
    const glm::vec3* p = positions.data();
    std::uint32_t* keys = scratch.keys(1);
    forBlocks(part, [&](std::size_t b, std::size_t begin, std::size_t end) {
        computeKeys(p, eye, f, keys, begin, end);
        countAllPasses<R>(keys, begin, end, t.counts(b, 0));
    });

    std::vector<int> passes = activePasses<R>(t, n);
    std::vector<std::uint32_t> order(n);
    if (passes.empty()) {  // every depth has the same key: index order
        std::iota(order.begin(), order.end(), 0u);
        return order;
    }
    PassPlan plan{keys, nullptr, nullptr, order.data(),
                  {scratch.keys(0), scratch.keys(1)}, {scratch.indices(0), scratch.indices(1)}};
    runPasses<R>(part, passes, t, plan);
    return order;
}

/// Depths of positions [begin, end) into `depthBits` (as float bits), and
/// the smallest and largest finite depth among them (+inf and -inf if none).
void computeDepths(const glm::vec3* __restrict p, glm::vec3 eye, glm::vec3 f,
                   std::uint32_t* __restrict depthBits, std::size_t begin, std::size_t end, float& lo,
                   float& hi) {
    float smallest = std::numeric_limits<float>::infinity();
    float largest = -std::numeric_limits<float>::infinity();
    for (std::size_t i = begin; i < end; ++i) {
        const float d = kernels::viewDepth(p[i], eye, f);
        depthBits[i] = std::bit_cast<std::uint32_t>(d);
        const bool finite = std::fabs(d) <= std::numeric_limits<float>::max();
        smallest = finite && d < smallest ? d : smallest;
        largest = finite && d > largest ? d : largest;
    }
    lo = smallest;
    hi = largest;
}

/// The 16-bit key of a depth: (hi - d) scale, truncated, clamped to
/// [0, 65534]; +inf 0, -inf 65534, NaN 65535. Non-increasing in d, so a
/// smaller key is never a nearer depth.
std::uint32_t quantisedKey(float d, float hi, float scale) {
    if (d != d) {
        return 65535u;
    }
    if (std::fabs(d) > std::numeric_limits<float>::max()) {
        return d > 0.0f ? 0u : 65534u;
    }
    const float x = (hi - d) * scale;  // finite, >= 0: hi - d <= hi - lo
    return static_cast<std::uint32_t>(std::min(x, 65534.0f));
}

std::vector<std::uint32_t> sortBackToFrontQuantisedImpl(std::span<const glm::vec3> positions, glm::vec3 eye,
                                                        glm::vec3 forward) {
    using R = Radix<8, 16>;
    const std::size_t n = positions.size();
    checkSize(n, "sortBackToFront");
    if (!std::isfinite(eye.x) || !std::isfinite(eye.y) || !std::isfinite(eye.z)) {
        throw Error("sortBackToFront: eye must be finite");
    }
    const glm::vec3 f = normalizeViewDirection(forward);
    if (n == 0) {
        return {};
    }
    RadixSortScratch& scratch = backToFrontScratch();
    scratch.reserve(n);
    const Partition part(n);
    Tables<R> t = makeTables<R>(scratch.counts(), part.blocks);
    std::uint32_t* keys = scratch.keys(1);
    std::vector<float> blockLo(part.blocks), blockHi(part.blocks);
    forBlocks(part, [&](std::size_t b, std::size_t begin, std::size_t end) {
        computeDepths(positions.data(), eye, f, keys, begin, end, blockLo[b], blockHi[b]);
    });
    const float lo = *std::min_element(blockLo.begin(), blockLo.end());
    const float hi = *std::max_element(blockHi.begin(), blockHi.end());
    // 65534 buckets over [lo, hi]; an overflowing or empty span: one bucket.
    const float span = hi - lo;
    const float scale = span > 0.0f && span <= std::numeric_limits<float>::max() ? 65534.0f / span : 0.0f;
    forBlocks(part, [&](std::size_t b, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            keys[i] = quantisedKey(std::bit_cast<float>(keys[i]), hi, scale);
        }
        countAllPasses<R>(keys, begin, end, t.counts(b, 0));
    });
    std::vector<int> passes = activePasses<R>(t, n);
    std::vector<std::uint32_t> order(n);
    if (passes.empty()) {
        std::iota(order.begin(), order.end(), 0u);
        return order;
    }
    PassPlan plan{keys, nullptr, nullptr, order.data(),
                  {scratch.keys(0), scratch.keys(1)}, {scratch.indices(0), scratch.indices(1)}};
    runPasses<R>(part, passes, t, plan);
    return order;
}

}  // namespace

std::vector<std::uint32_t> sortBackToFrontQuantised(std::span<const glm::vec3> positions, glm::vec3 eye,
                                                    glm::vec3 forward) {
    return sortBackToFrontQuantisedImpl(positions, eye, forward);
}

void RadixSortScratch::AlignedDelete::operator()(std::uint32_t* p) const {
    ::operator delete[](p, std::align_val_t{64});
}

void RadixSortScratch::reserve(std::size_t n) {
    if (n <= capacity_) {
        return;
    }
    auto allocate = [n] {
        return Buffer(static_cast<std::uint32_t*>(
            ::operator new[](n * sizeof(std::uint32_t), std::align_val_t{64})));
    };
    for (int which = 0; which < 2; ++which) {
        keys_[which].reset();
        indices_[which].reset();
        keys_[which] = allocate();
        indices_[which] = allocate();
    }
    capacity_ = n;
}

glm::vec3 normalizeViewDirection(glm::vec3 forward) {
    auto finite = [](glm::vec3 v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite(forward)) {
        throw Error("sortBackToFront: forward must be finite");
    }
    glm::vec3 unit = glm::normalize(forward);
    if (finite(unit) && glm::dot(unit, unit) > 0.5f) {
        return unit;
    }
    // |forward|^2 overflowed or underflowed: rescale first.
    float largest = std::max({std::fabs(forward.x), std::fabs(forward.y), std::fabs(forward.z)});
    if (largest == 0.0f) {
        throw Error("sortBackToFront: forward must be a non-zero vector");
    }
    return glm::normalize(forward / largest);
}

void radixSortKeyIndex(std::span<std::uint32_t> keys, std::span<std::uint32_t> indices,
                       RadixSortScratch& scratch, RadixDigitBits digitBits) {
    if (keys.size() != indices.size()) {
        throw Error("radixSortKeyIndex: " + std::to_string(keys.size()) + " keys but " +
                    std::to_string(indices.size()) + " indices; expected the same count");
    }
    checkSize(keys.size(), "radixSortKeyIndex");
    switch (digitBits) {
        case RadixDigitBits::Eight: radixSortKeyIndexImpl<Radix<8>>(keys, indices, scratch); return;
        case RadixDigitBits::Eleven: radixSortKeyIndexImpl<Radix<11>>(keys, indices, scratch); return;
    }
    throw Error("radixSortKeyIndex: digit width must be 8 or 11 bits");
}

std::vector<std::uint32_t> sortBackToFront(std::span<const glm::vec3> positions, glm::vec3 eye,
                                           glm::vec3 forward, RadixDigitBits digitBits) {
    switch (digitBits) {
        case RadixDigitBits::Eight: return sortBackToFrontImpl<Radix<8>>(positions, eye, forward);
        case RadixDigitBits::Eleven: return sortBackToFrontImpl<Radix<11>>(positions, eye, forward);
    }
    throw Error("sortBackToFront: digit width must be 8 or 11 bits");
}

std::vector<std::uint32_t> sortBackToFront(std::span<const glm::vec3> positions, glm::vec3 eye,
                                           glm::vec3 forward) {
    return sortBackToFront(positions, eye, forward, kDefaultRadixDigitBits);
}

}  // namespace spindrift
