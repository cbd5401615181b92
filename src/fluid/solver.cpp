// The fluid constraint solver (slides 36-39): sequential impulses, one visit
// per particle per iteration, warm started with the previous step's pressure.
// Two orders: the slides' single loop over all particles (Sequential), and
// Gauss-Seidel over colour groups of grid cells (Parallel), where cells of one
// colour share no particle and are visited at the same time.
//
// Split impulses (FluidDef::splitImpulse, on by default): most of the
// Baumgarte bias (slide 34) is solved on a second, pseudo velocity that moves
// particles this step and is then forgotten, as rigid-body solvers do for
// penetration; the real velocity keeps a quarter of it (fluid.glsl). With the bias in the real
// velocity (the slides' form) every density fluctuation of a disordered
// packing becomes kinetic energy: a tank at rest keeps boiling at about 0.2
// m/s (measured; docs/performance.md).
#include "core/cpu_target.h"
#include "core/room.h"
#include "fluid/fluid_state.h"

#include <algorithm>
#include <cstring>

#if SPINDRIFT_X86
#include <immintrin.h>
#endif

namespace spindrift::fluid {
namespace {

/// Four floats in one SIMD register (GCC's and Clang's vector extension;
/// plain float operations lane by lane, so the same results as four scalar
/// ones, on any target). glm's vec4 stayed four scalar registers (measured).
typedef float Float4 __attribute__((vector_size(16)));

/// A 2D Motion as four floats (vx, vy, px, py): one load of a neighbour
/// serves both rates, one store both impulses.
inline Float4 bothOf(const Motion<2>& m) {
    Float4 r;
    std::memcpy(&r, &m, sizeof r);
    return r;
}
inline void storeBoth(Motion<2>& m, Float4 r) { std::memcpy(&m, &r, sizeof r); }
/// (gx, gy, gx, gy): a pair's g for both constraints at once.
inline Float4 twice(glm::vec2 g) { return Float4{g.x, g.y, g.x, g.y}; }
/// Lane 0: t[0] + t[1], lane 2: t[2] + t[3], the two dot products of a pair
/// whose products t holds (the sums glm::dot makes: IEEE addition commutes).
inline Float4 pairDots(Float4 t) { return t + __builtin_shufflevector(t, t, 1, 0, 3, 2); }

template <int D>
struct SolverView {
    Motion<D>* motion;  // velocities, and pseudo velocities when split
    bool split;         // false: bias on the real velocity
    float* pressure;
    float* pseudoImpulse;
    const std::vector<Neighbour<D>>* lists;  // per chunk (NeighbourChunks)
    const std::uint32_t* first;
    const std::uint32_t* listChunk;
    const glm::vec3* wall;  // the colliders' ghosts' g (wall_density.cpp)
    const float* bias;
    const float* invMass;
    const std::uint32_t* count;
    float allowanceSlop;  // m/s of bias an under-dense particle's allowance starts above
};

/// Particle i's neighbour list (NeighbourChunks' layout, fluid_state.h).
template <int D>
inline const Neighbour<D>* listOf(const SolverView<D>& s, std::size_t i) {
    return s.lists[s.listChunk[i]].data() + s.first[i];
}

// The order of every sum over a particle's neighbours (both backends; the
// device's fluid_solve.comp makes the same additions): entry k goes to chain
// k % 4, the first chain starting from the particle's own ghost term, and the
// chains are added as (0 + 1) + (2 + 3). One chain of 28 dependent additions
// bound the sweep; four are what a 512-bit register holds of a 2D particle's
// (velocity, pseudo velocity), so the AVX-512 sweep (below) loads four
// neighbours at a time and adds the same numbers in the same order.
constexpr std::uint32_t kChains = 4;

template <class T>
inline T chainSum(const T (&chain)[kChains]) {
    return (chain[0] + chain[1]) + (chain[2] + chain[3]);
}

/// Adds term(k) for every entry k < count into chain k % 4 (four entries an
/// iteration, so the chains stay in registers: indexed by k % 4 in one loop
/// they went through memory, 17 % slower a step with AVX2, measured).
template <class T, class Term>
[[gnu::always_inline]] inline void addInChains(T (&chain)[kChains], std::uint32_t count, Term term) {
    std::uint32_t k = 0;
    for (; k + kChains <= count; k += kChains) {
        chain[0] += term(k);
        chain[1] += term(k + 1);
        chain[2] += term(k + 2);
        chain[3] += term(k + 3);
    }
    for (std::uint32_t c = 0; k + c < count; ++c) chain[c] += term(k + c);
}

/// Applies impulse `delta` of particle i's constraint to the velocities: v_n +=
/// g delta on every neighbour, v_i -= sum g delta (Newton's third law, slide 39).
template <int D>
inline void applyImpulse(const SolverView<D>& s, std::size_t i, float delta) {
    const Neighbour<D>* list = listOf<D>(s, i);
    Motion<D>* m = s.motion;
    Vec<D> self[kChains] = {Vec<D>(s.wall[i]) * delta, Vec<D>(0.0f), Vec<D>(0.0f), Vec<D>(0.0f)};  // ghosts take none
    addInChains(self, s.count[i], [&](std::uint32_t k) {
        const Vec<D> impulse = list[k].g * delta;
        m[list[k].index].velocity += impulse;
        return impulse;
    });
    m[i].velocity -= chainSum(self);
}

/// C' of particle i's constraint over the velocities (slide 36).
template <int D>
inline float rateOf(const SolverView<D>& s, std::size_t i) {
    const Neighbour<D>* list = listOf<D>(s, i);
    const Motion<D>* m = s.motion;
    const Vec<D> vi = m[i].velocity;
    float chain[kChains] = {-glm::dot(Vec<D>(s.wall[i]), vi), 0.0f, 0.0f, 0.0f};  // ghosts at rest
    addInChains(chain, s.count[i],
                [&](std::uint32_t k) { return glm::dot(list[k].g, m[list[k].index].velocity - vi); });
    return chainSum(chain);
}

/// C' of an over-dense particle's two constraints, over the velocities and
/// over the pseudo velocities, in one pass over its neighbours.
struct SplitRates {
    float rate;
    float pseudoRate;
};

template <int D>
inline SplitRates splitRates(const SolverView<D>& s, std::size_t i) {
    const Neighbour<D>* list = listOf<D>(s, i);
    const std::uint32_t count = s.count[i];
    const Motion<D>* m = s.motion;
    const Vec<D> wall(s.wall[i]);
    if constexpr (D == 2) {
        // Both rates two lanes at a time: lane 0 the velocities', lane 2 the
        // pseudo velocities' (the same sums as glm::dot's, bit for bit).
        const Float4 mi = bothOf(m[i]);
        Float4 chain[kChains] = {Float4{-glm::dot(wall, m[i].velocity), 0.0f, -glm::dot(wall, m[i].pseudo), 0.0f},
                                 Float4{}, Float4{}, Float4{}};
        addInChains(chain, count,
                    [&](std::uint32_t k) { return pairDots(twice(list[k].g) * (bothOf(m[list[k].index]) - mi)); });
        const Float4 sum = chainSum(chain);
        return {sum[0], sum[2]};
    } else {
        const Vec<D> vi = m[i].velocity;
        const Vec<D> pi = m[i].pseudo;
        glm::vec2 chain[kChains] = {glm::vec2(-glm::dot(wall, vi), -glm::dot(wall, pi)), glm::vec2(0.0f),
                                    glm::vec2(0.0f), glm::vec2(0.0f)};
        addInChains(chain, count, [&](std::uint32_t k) {
            const Motion<D>& a = m[list[k].index];
            return glm::vec2(glm::dot(list[k].g, a.velocity - vi), glm::dot(list[k].g, a.pseudo - pi));
        });
        const glm::vec2 sum = chainSum(chain);
        return {sum.x, sum.y};
    }
}

/// Applies an over-dense particle's two impulses: `delta` to the velocities,
/// `push` to the pseudo velocities, as applyImpulse does.
template <int D>
inline void applySplitImpulses(const SolverView<D>& s, std::size_t i, float delta, float push) {
    const Neighbour<D>* list = listOf<D>(s, i);
    const std::uint32_t count = s.count[i];
    Motion<D>* m = s.motion;
    const Vec<D> wall(s.wall[i]);
    if constexpr (D == 2) {
        const Float4 both{delta, delta, push, push};
        Float4 self[kChains] = {twice(wall) * both, Float4{}, Float4{}, Float4{}};
        addInChains(self, count, [&](std::uint32_t k) {
            const Float4 impulse = twice(list[k].g) * both;
            Motion<2>& n = m[list[k].index];
            storeBoth(n, bothOf(n) + impulse);
            return impulse;
        });
        storeBoth(m[i], bothOf(m[i]) - chainSum(self));
    } else {
        // (impulse, shift) as the columns of a matrix: one pass over the list.
        using Pair = glm::mat<2, D, float>;
        Pair self[kChains] = {Pair(wall * delta, wall * push), Pair(0.0f), Pair(0.0f), Pair(0.0f)};
        addInChains(self, count, [&](std::uint32_t k) {
            const Pair moved(list[k].g * delta, list[k].g * push);
            Motion<D>& n = m[list[k].index];
            n.velocity += moved[0];
            n.pseudo += moved[1];
            return moved;
        });
        const Pair sum = chainSum(self);
        m[i].velocity -= sum[0];
        m[i].pseudo -= sum[1];
    }
}

/// The neighbour loops of a visit, in plain C++ (every target; the
/// compiler's own vector code for Float4).
template <int D>
struct PlainLoops {
    static constexpr bool kHeld = false;
    static float rate(const SolverView<D>& s, std::size_t i) { return rateOf<D>(s, i); }
    static void apply(const SolverView<D>& s, std::size_t i, float delta) { applyImpulse<D>(s, i, delta); }
    static SplitRates rates(const SolverView<D>& s, std::size_t i) { return splitRates<D>(s, i); }
    static void applySplit(const SolverView<D>& s, std::size_t i, float delta, float push) {
        applySplitImpulses<D>(s, i, delta, push);
    }
};

/// What one visit applies: `delta` to the velocities and, for an
/// over-dense particle with split impulses (`split`), `push` to the pseudo
/// velocities; nothing when `apply` is false.
struct VisitImpulses {
    float delta;
    float push;
    bool split;
    bool apply;
};

/// Whether particle i's visit solves two constraints (visit).
template <int D>
inline bool solvesTwo(const SolverView<D>& s, std::size_t i) {
    return s.split && s.bias[i] < 0.0f;
}

/// The impulses of particle i's visit from its rates (slide 36, signs in
/// fluid.glsl), with its accumulated impulses updated; `pseudoRate` is read
/// only when solvesTwo. Always inlined: the vector visits (AVX-512, AVX2)
/// call it, and a call from them into this function built for the baseline
/// target made the sweeps four times slower (a probe of the eighth session
/// of 2026-12-07, docs/fluid.md, where g++ stopped inlining it).
template <int D>
[[gnu::always_inline]] inline VisitImpulses impulsesOf(const SolverView<D>& s, std::size_t i, float rate,
                                                       float pseudoRate) {
    if (!s.split) {
        const kernels::FluidImpulse r = kernels::fluidSolveImpulse(rate, s.bias[i], s.invMass[i], s.pressure[i]);
        s.pressure[i] = r.accumulated;
        return {r.delta, 0.0f, false, r.delta != 0.0f};
    }
    // The bias splits by sign: an under-dense particle's positive bias lets
    // its neighbours approach (it relaxes the constraint, no energy added) and
    // stays with the real velocity, past a slop; an over-dense particle's
    // negative bias pushes apart, which is the pseudo velocity's job. Only an
    // over-dense particle has a pseudo constraint, so both are solved in one
    // pass over its neighbours (half the memory traffic of two visits).
    const float bias = s.bias[i];
    if (bias >= 0.0f) {
        const kernels::FluidImpulse r = kernels::fluidSolveImpulse(rate, kernels::fluidAllowance(bias, s.allowanceSlop),
                                                                   s.invMass[i], s.pressure[i]);
        s.pressure[i] = r.accumulated;
        return {r.delta, 0.0f, false, r.delta != 0.0f};
    }
    const kernels::FluidImpulse r =
        kernels::fluidSolveImpulse(rate, kernels::fluidRealBias(bias), s.invMass[i], s.pressure[i]);
    const kernels::FluidImpulse q =
        kernels::fluidSolveImpulse(pseudoRate, kernels::fluidPseudoBias(bias), s.invMass[i], s.pseudoImpulse[i]);
    s.pressure[i] = r.accumulated;
    s.pseudoImpulse[i] = q.accumulated;
    return {r.delta, q.delta, true, true};
}

#if SPINDRIFT_X86
#define SD_SOLVE_AVX512 "avx512f,avx512vl,avx512bw,avx512dq"

/// The ghosts' terms of a 2D particle's two rates, where the first chain
/// starts (splitRates): lane 0 over the velocity, lane 2 over the pseudo
/// velocity.
inline __m128 ghostRates(glm::vec2 wall, const Motion<2>& m) {
    return _mm_setr_ps(-glm::dot(wall, m.velocity), 0.0f, -glm::dot(wall, m.pseudo), 0.0f);
}

/// A 2D particle's neighbour loops with AVX-512: four neighbours a register,
/// each in a 128-bit chunk as (vx, vy, px, py), chunk c holding chain c of
/// the sums (kChains), so the same numbers are added in the same order as
/// the plain loops and the results are the same bits. (The masked forms of
/// broadcasts, permutes and extracts throughout: g++ 12 warns, under
/// -Werror, that the plain forms' undefined source is used uninitialised.)
struct Avx512Loops {
    /// Entries k .. k + n - 1 (n <= 4) as (gx, gy, gx, gy) per chunk, 0
    /// past n: one masked load of their 12-byte entries and one permute.
    [[gnu::target(SD_SOLVE_AVX512)]] static __m512 gOf(const Neighbour<2>* e, std::uint32_t n) {
        const __mmask16 floats = static_cast<__mmask16>((1u << (3 * n)) - 1u);
        const __m512 raw = _mm512_maskz_loadu_ps(floats, &e[0].g.x);
        return _mm512_maskz_permutexvar_ps(0xffff, _mm512_setr_epi32(0, 1, 0, 1, 3, 4, 3, 4, 6, 7, 6, 7, 9, 10, 9, 10),
                                           raw);
    }
    /// gOf of four whole entries (48 bytes), by two plain loads. The masked
    /// load was the sweep's costliest instruction at 30k, and unmasked loads
    /// took 4 % off a step there, 2 % off the sweeps at 10k (docs/fluid.md).
    [[gnu::target(SD_SOLVE_AVX512)]] static __m512 gOf4(const Neighbour<2>* e) {
        const float* floats = &e[0].g.x;
        const __m512 raw =
            _mm512_insertf32x4(_mm512_castps256_ps512(_mm256_loadu_ps(floats)), _mm_loadu_ps(floats + 8), 2);
        return _mm512_maskz_permutexvar_ps(0xffff, _mm512_setr_epi32(0, 1, 0, 1, 3, 4, 3, 4, 6, 7, 6, 7, 9, 10, 9, 10),
                                           raw);
    }
    /// Their motions (16 bytes each), 0 past n.
    [[gnu::target(SD_SOLVE_AVX512)]] static __m512 motionOf(const Motion<2>* m, const Neighbour<2>* e,
                                                            std::uint32_t n) {
        __m512 r = _mm512_insertf32x4(_mm512_setzero_ps(), _mm_loadu_ps(&m[e[0].index].velocity.x), 0);
        if (n > 1) r = _mm512_insertf32x4(r, _mm_loadu_ps(&m[e[1].index].velocity.x), 1);
        if (n > 2) r = _mm512_insertf32x4(r, _mm_loadu_ps(&m[e[2].index].velocity.x), 2);
        if (n > 3) r = _mm512_insertf32x4(r, _mm_loadu_ps(&m[e[3].index].velocity.x), 3);
        return r;
    }
    [[gnu::target(SD_SOLVE_AVX512)]] static void storeMotions(Motion<2>* m, const Neighbour<2>* e, std::uint32_t n,
                                                              __m512 r) {
        _mm_storeu_ps(&m[e[0].index].velocity.x, _mm512_maskz_extractf32x4_ps(0xf, r, 0));
        if (n > 1) _mm_storeu_ps(&m[e[1].index].velocity.x, _mm512_maskz_extractf32x4_ps(0xf, r, 1));
        if (n > 2) _mm_storeu_ps(&m[e[2].index].velocity.x, _mm512_maskz_extractf32x4_ps(0xf, r, 2));
        if (n > 3) _mm_storeu_ps(&m[e[3].index].velocity.x, _mm512_maskz_extractf32x4_ps(0xf, r, 3));
    }
    /// Chunks [0, n) of a register.
    static __mmask16 chunks(std::uint32_t n) { return static_cast<__mmask16>((1u << (4 * n)) - 1u); }
    /// chainSum of the four chunks: (0 + 1) + (2 + 3).
    [[gnu::target(SD_SOLVE_AVX512)]] static __m128 chainSum512(__m512 v) {
        const __m128 low = _mm_add_ps(_mm512_maskz_extractf32x4_ps(0xf, v, 0), _mm512_maskz_extractf32x4_ps(0xf, v, 1));
        const __m128 high =
            _mm_add_ps(_mm512_maskz_extractf32x4_ps(0xf, v, 2), _mm512_maskz_extractf32x4_ps(0xf, v, 3));
        return _mm_add_ps(low, high);
    }
    /// The rates over the velocities (lane 0) and the pseudo velocities
    /// (lane 2): splitRates' sums, chunk by chunk.
    [[gnu::target(SD_SOLVE_AVX512)]] static __m128 rates128(const SolverView<2>& s, std::size_t i) {
        const Neighbour<2>* list = listOf<2>(s, i);
        const std::uint32_t count = s.count[i];
        const Motion<2>* m = s.motion;
        const glm::vec2 wall(s.wall[i]);
        const __m128 own = _mm_loadu_ps(&m[i].velocity.x);
        const __m512 mi = _mm512_maskz_broadcast_f32x4(0xffff, own);
        __m512 chain = _mm512_insertf32x4(_mm512_setzero_ps(), ghostRates(wall, m[i]), 0);
        std::uint32_t k = 0;
        for (; k + 4 <= count; k += 4) {
            const __m512 t = _mm512_mul_ps(gOf4(list + k), _mm512_sub_ps(motionOf(m, list + k, 4), mi));
            chain = _mm512_add_ps(chain, _mm512_add_ps(t, _mm512_maskz_permute_ps(0xffff, t, 0xb1)));  // pairDots
        }
        if (k < count) {
            const std::uint32_t n = count - k;
            const __m512 t = _mm512_mul_ps(gOf(list + k, n), _mm512_sub_ps(motionOf(m, list + k, n), mi));
            chain =
                _mm512_mask_add_ps(chain, chunks(n), chain, _mm512_add_ps(t, _mm512_maskz_permute_ps(0xffff, t, 0xb1)));
        }
        return chainSum512(chain);
    }
    [[gnu::target(SD_SOLVE_AVX512)]] static float rate(const SolverView<2>& s, std::size_t i) {
        return _mm_cvtss_f32(rates128(s, i));
    }
    [[gnu::target(SD_SOLVE_AVX512)]] static SplitRates rates(const SolverView<2>& s, std::size_t i) {
        const __m128 r = rates128(s, i);
        return {_mm_cvtss_f32(r), _mm_cvtss_f32(_mm_movehl_ps(r, r))};
    }
    /// Adds g (delta, delta, push, push) to every neighbour's motion (only
    /// the lanes of `lanes`, per chunk: 0x3333 leaves the pseudo velocities'
    /// bits alone) and subtracts the chains' sum from the particle's.
    [[gnu::target(SD_SOLVE_AVX512)]] static void scatter(const SolverView<2>& s, std::size_t i, __m128 both,
                                                         __mmask16 lanes) {
        const Neighbour<2>* list = listOf<2>(s, i);
        const std::uint32_t count = s.count[i];
        Motion<2>* m = s.motion;
        const glm::vec2 wall(s.wall[i]);
        const __m512 both512 = _mm512_maskz_broadcast_f32x4(0xffff, both);
        __m512 self =
            _mm512_insertf32x4(_mm512_setzero_ps(), _mm_mul_ps(_mm_setr_ps(wall.x, wall.y, wall.x, wall.y), both), 0);
        std::uint32_t k = 0;
        for (; k + 4 <= count; k += 4) {
            const __m512 impulse = _mm512_mul_ps(gOf4(list + k), both512);
            const __m512 moved = motionOf(m, list + k, 4);
            storeMotions(m, list + k, 4, _mm512_mask_add_ps(moved, lanes, moved, impulse));
            self = _mm512_add_ps(self, impulse);
        }
        if (k < count) {
            const std::uint32_t n = count - k;
            const __m512 impulse = _mm512_mul_ps(gOf(list + k, n), both512);
            const __m512 moved = motionOf(m, list + k, n);
            storeMotions(m, list + k, n, _mm512_mask_add_ps(moved, lanes, moved, impulse));
            self = _mm512_mask_add_ps(self, chunks(n), self, impulse);
        }
        const __m128 own = _mm_loadu_ps(&m[i].velocity.x);
        _mm_storeu_ps(&m[i].velocity.x,
                      _mm_mask_sub_ps(own, static_cast<__mmask8>(lanes & 0xf), own, chainSum512(self)));
    }
    [[gnu::target(SD_SOLVE_AVX512)]] static void apply(const SolverView<2>& s, std::size_t i, float delta) {
        scatter(s, i, _mm_setr_ps(delta, delta, 0.0f, 0.0f), 0x3333);
    }
    /// The most neighbours a visit holds in registers (visitHeld): g and
    /// motion of four a register each, 20 of AVX-512's 32. Ten groups hold
    /// the 36 to 40 neighbours of an interior particle at the default h
    /// (3.5 spacings); with eight such a visit took the two-pass loops, and
    /// the sweeps cost about a tenth more.
    static constexpr std::uint32_t kHeldGroups = 10;
    static constexpr bool kHeld = true;
    /// A whole visit (rates, impulses, scatter) with its kGroups registers
    /// of entries and motions loaded once: rates128's and scatter's
    /// operations in their order, so the same bits, without the scatter's
    /// second loads of the list and the motions (the visit's own writes are
    /// the only ones between, and no list holds its particle).
    template <std::uint32_t kGroups>
    [[gnu::target(SD_SOLVE_AVX512), gnu::always_inline]] static inline void visitGroups(const SolverView<2>& s,
                                                                                        std::size_t i) {
        const Neighbour<2>* list = listOf<2>(s, i);
        const std::uint32_t tail = s.count[i] - 4 * (kGroups - 1);  // 1 to 4 in the last register
        Motion<2>* m = s.motion;
        __m512 g[kGroups];
        __m512 moved[kGroups];
#pragma GCC unroll 10
        for (std::uint32_t k = 0; k + 1 < kGroups; ++k) {
            g[k] = gOf4(list + 4 * k);
            moved[k] = motionOf(m, list + 4 * k, 4);
        }
        g[kGroups - 1] = gOf(list + 4 * (kGroups - 1), tail);
        moved[kGroups - 1] = motionOf(m, list + 4 * (kGroups - 1), tail);
        const glm::vec2 wall(s.wall[i]);
        const __m128 own = _mm_loadu_ps(&m[i].velocity.x);
        const __m512 mi = _mm512_maskz_broadcast_f32x4(0xffff, own);
        __m512 chain = _mm512_insertf32x4(_mm512_setzero_ps(), ghostRates(wall, m[i]), 0);
#pragma GCC unroll 10
        for (std::uint32_t k = 0; k < kGroups; ++k) {
            const __m512 t = _mm512_mul_ps(g[k], _mm512_sub_ps(moved[k], mi));
            const __m512 dots = _mm512_add_ps(t, _mm512_maskz_permute_ps(0xffff, t, 0xb1));  // pairDots
            chain = k + 1 < kGroups ? _mm512_add_ps(chain, dots) : _mm512_mask_add_ps(chain, chunks(tail), chain, dots);
        }
        const __m128 rates = chainSum512(chain);
        const VisitImpulses v = impulsesOf<2>(s, i, _mm_cvtss_f32(rates), _mm_cvtss_f32(_mm_movehl_ps(rates, rates)));
        if (!v.apply) return;
        const __m128 both =
            v.split ? _mm_setr_ps(v.delta, v.delta, v.push, v.push) : _mm_setr_ps(v.delta, v.delta, 0.0f, 0.0f);
        const __mmask16 lanes = v.split ? 0xffff : 0x3333;
        const __m512 both512 = _mm512_maskz_broadcast_f32x4(0xffff, both);
        __m512 self =
            _mm512_insertf32x4(_mm512_setzero_ps(), _mm_mul_ps(_mm_setr_ps(wall.x, wall.y, wall.x, wall.y), both), 0);
#pragma GCC unroll 10
        for (std::uint32_t k = 0; k < kGroups; ++k) {
            const __m512 impulse = _mm512_mul_ps(g[k], both512);
            const std::uint32_t n = k + 1 < kGroups ? 4 : tail;
            storeMotions(m, list + 4 * k, n, _mm512_mask_add_ps(moved[k], lanes, moved[k], impulse));
            self =
                k + 1 < kGroups ? _mm512_add_ps(self, impulse) : _mm512_mask_add_ps(self, chunks(tail), self, impulse);
        }
        _mm_storeu_ps(&m[i].velocity.x,
                      _mm_mask_sub_ps(own, static_cast<__mmask8>(lanes & 0xf), own, chainSum512(self)));
    }
    /// visitGroups for particle i when its list fits kHeldGroups registers;
    /// false (nothing done) otherwise. Tried from the most registers down:
    /// an interior particle's 36 to 40 neighbours take 9 or 10.
    template <std::uint32_t kGroups = kHeldGroups>
    [[gnu::target(SD_SOLVE_AVX512)]] static bool visitHeld(const SolverView<2>& s, std::size_t i) {
        if constexpr (kGroups == 0) {
            return false;
        } else {
            if ((s.count[i] + 3) / 4 == kGroups) {
                visitGroups<kGroups>(s, i);
                return true;
            }
            return visitHeld<kGroups - 1>(s, i);
        }
    }
    [[gnu::target(SD_SOLVE_AVX512)]] static void applySplit(const SolverView<2>& s, std::size_t i, float delta,
                                                            float push) {
        scatter(s, i, _mm_setr_ps(delta, delta, push, push), 0xffff);
    }
};

#define SD_SOLVE_AVX2 "avx2"

/// Avx512Loops with AVX2: two neighbours a register, each in a 128-bit half
/// as (vx, vy, px, py), and the four chains of the sums in two registers
/// (chains 0 and 1 in `low`'s halves, 2 and 3 in `high`'s), so the same
/// numbers are added in the same order as the plain loops: the same bits.
struct Avx2Loops {
    static constexpr bool kHeld = false;
    /// Entry e's g as (gx, gy, gx, gy).
    [[gnu::target(SD_SOLVE_AVX2)]] static __m128 gOf(const Neighbour<2>& e) {
        const __m128 g = _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&e.g.x)));
        return _mm_movelh_ps(g, g);
    }
    /// Entries e[0] and e[1] (only e[0] when n is 1, the other half 0).
    [[gnu::target(SD_SOLVE_AVX2)]] static __m256 gOf(const Neighbour<2>* e, std::uint32_t n) {
        return _mm256_set_m128(n > 1 ? gOf(e[1]) : _mm_setzero_ps(), gOf(e[0]));
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static __m256 motionOf(const Motion<2>* m, const Neighbour<2>* e, std::uint32_t n) {
        const __m128 first = _mm_loadu_ps(&m[e[0].index].velocity.x);
        return _mm256_set_m128(n > 1 ? _mm_loadu_ps(&m[e[1].index].velocity.x) : _mm_setzero_ps(), first);
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static void storeMotions(Motion<2>* m, const Neighbour<2>* e, std::uint32_t n,
                                                            __m256 r) {
        _mm_storeu_ps(&m[e[0].index].velocity.x, _mm256_castps256_ps128(r));
        if (n > 1) _mm_storeu_ps(&m[e[1].index].velocity.x, _mm256_extractf128_ps(r, 1));
    }
    /// `chain` + `t` in the halves of a pair of n entries: both halves, or
    /// the low one alone.
    [[gnu::target(SD_SOLVE_AVX2)]] static __m256 addTo(__m256 chain, __m256 t, std::uint32_t n) {
        const __m256 sum = _mm256_add_ps(chain, t);
        return n > 1 ? sum : _mm256_blend_ps(chain, sum, 0x0f);
    }
    /// chainSum of the four chains: (0 + 1) + (2 + 3).
    [[gnu::target(SD_SOLVE_AVX2)]] static __m128 chainSum256(__m256 low, __m256 high) {
        return _mm_add_ps(_mm_add_ps(_mm256_castps256_ps128(low), _mm256_extractf128_ps(low, 1)),
                          _mm_add_ps(_mm256_castps256_ps128(high), _mm256_extractf128_ps(high, 1)));
    }
    /// pairDots of the products of n entries (n <= 2) with their motions.
    [[gnu::target(SD_SOLVE_AVX2)]] static __m256 dotsOf(const Motion<2>* m, const Neighbour<2>* e, std::uint32_t n,
                                                        __m256 mi) {
        const __m256 t = _mm256_mul_ps(gOf(e, n), _mm256_sub_ps(motionOf(m, e, n), mi));
        return _mm256_add_ps(t, _mm256_permute_ps(t, 0xb1));
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static __m128 rates128(const SolverView<2>& s, std::size_t i) {
        const Neighbour<2>* list = listOf<2>(s, i);
        const std::uint32_t count = s.count[i];
        const Motion<2>* m = s.motion;
        const glm::vec2 wall(s.wall[i]);
        const __m128 own = _mm_loadu_ps(&m[i].velocity.x);
        const __m256 mi = _mm256_set_m128(own, own);
        __m256 low = _mm256_set_m128(_mm_setzero_ps(), ghostRates(wall, m[i]));
        __m256 high = _mm256_setzero_ps();
        std::uint32_t k = 0;
        for (; k + 4 <= count; k += 4) {
            low = _mm256_add_ps(low, dotsOf(m, list + k, 2, mi));
            high = _mm256_add_ps(high, dotsOf(m, list + k + 2, 2, mi));
        }
        const std::uint32_t n = count - k;
        if (n > 0) low = addTo(low, dotsOf(m, list + k, std::min(n, 2u), mi), n);
        if (n > 2) high = addTo(high, dotsOf(m, list + k + 2, 1, mi), 1);
        return chainSum256(low, high);
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static float rate(const SolverView<2>& s, std::size_t i) {
        return _mm_cvtss_f32(rates128(s, i));
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static SplitRates rates(const SolverView<2>& s, std::size_t i) {
        const __m128 r = rates128(s, i);
        return {_mm_cvtss_f32(r), _mm_cvtss_f32(_mm_movehl_ps(r, r))};
    }
    /// Adds g (delta, delta, push, push) to n neighbours' motions (n <= 2;
    /// `velocityOnly`: leaves the pseudo velocities' bits alone) and
    /// returns the impulses.
    [[gnu::target(SD_SOLVE_AVX2)]] static __m256 pushNeighbours(Motion<2>* m, const Neighbour<2>* e, std::uint32_t n,
                                                                __m256 both, bool velocityOnly) {
        const __m256 impulse = _mm256_mul_ps(gOf(e, n), both);
        const __m256 moved = motionOf(m, e, n);
        const __m256 sum = _mm256_add_ps(moved, impulse);
        storeMotions(m, e, n, velocityOnly ? _mm256_blend_ps(moved, sum, 0x33) : sum);
        return impulse;
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static void scatter(const SolverView<2>& s, std::size_t i, __m128 both,
                                                       bool velocityOnly) {
        const Neighbour<2>* list = listOf<2>(s, i);
        const std::uint32_t count = s.count[i];
        Motion<2>* m = s.motion;
        const glm::vec2 wall(s.wall[i]);
        const __m256 both256 = _mm256_set_m128(both, both);
        __m256 low = _mm256_set_m128(_mm_setzero_ps(), _mm_mul_ps(_mm_setr_ps(wall.x, wall.y, wall.x, wall.y), both));
        __m256 high = _mm256_setzero_ps();
        std::uint32_t k = 0;
        for (; k + 4 <= count; k += 4) {
            low = _mm256_add_ps(low, pushNeighbours(m, list + k, 2, both256, velocityOnly));
            high = _mm256_add_ps(high, pushNeighbours(m, list + k + 2, 2, both256, velocityOnly));
        }
        const std::uint32_t n = count - k;
        if (n > 0) low = addTo(low, pushNeighbours(m, list + k, std::min(n, 2u), both256, velocityOnly), n);
        if (n > 2) high = addTo(high, pushNeighbours(m, list + k + 2, 1, both256, velocityOnly), 1);
        const __m128 own = _mm_loadu_ps(&m[i].velocity.x);
        const __m128 moved = _mm_sub_ps(own, chainSum256(low, high));
        _mm_storeu_ps(&m[i].velocity.x, velocityOnly ? _mm_blend_ps(own, moved, 0x3) : moved);
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static void apply(const SolverView<2>& s, std::size_t i, float delta) {
        scatter(s, i, _mm_setr_ps(delta, delta, 0.0f, 0.0f), true);
    }
    [[gnu::target(SD_SOLVE_AVX2)]] static void applySplit(const SolverView<2>& s, std::size_t i, float delta,
                                                          float push) {
        scatter(s, i, _mm_setr_ps(delta, delta, push, push), false);
    }
};
#endif

/// One visit of particle i's constraint, with the neighbour loops of
/// `Loops`: its rates, then its impulses.
template <int D, class Loops>
[[gnu::always_inline]] inline void visit(const SolverView<D>& s, std::size_t i) {
    if constexpr (Loops::kHeld) {
        if (Loops::visitHeld(s, i)) return;
    }
    float rate = 0.0f;
    float pseudoRate = 0.0f;
    if (solvesTwo<D>(s, i)) {
        const SplitRates r = Loops::rates(s, i);
        rate = r.rate;
        pseudoRate = r.pseudoRate;
    } else {
        rate = Loops::rate(s, i);
    }
    const VisitImpulses v = impulsesOf<D>(s, i, rate, pseudoRate);
    if (!v.apply) return;
    if (v.split) {
        Loops::applySplit(s, i, v.delta, v.push);
    } else {
        Loops::apply(s, i, v.delta);
    }
}

/// Runs fn(i) for the particles of cells[begin, end), cell by cell, each
/// cell's particles in grid order.
template <int D, class Fn>
[[gnu::always_inline]] inline void forParticlesOfCells(const Grid<D>& g, const std::uint32_t* cells,
                                                       std::size_t begin, std::size_t end, Fn&& fn) {
    constexpr std::uint32_t kQuadrants = 1u << D;
    for (std::size_t c = begin; c < end; ++c) {
        const std::uint32_t last = g.keyStart[(cells[c] + 1) * kQuadrants];
        for (std::uint32_t i = g.keyStart[cells[c] * kQuadrants]; i < last; ++i) fn(i);
    }
}

/// The visits of the particles of cells[begin, end) of one colour.
template <int D, class Loops>
[[gnu::always_inline]] inline void visitCells(const SolverView<D>& s, const Grid<D>& g, const std::uint32_t* cells,
                                              std::size_t begin, std::size_t end) {
    // Always inlined, so the AVX-512 loops inline into visitCellsAvx512 (a
    // lambda of its own, without that target, kept them as calls: 4 % slower).
    forParticlesOfCells<D>(g, cells, begin, end,
                           [&](std::uint32_t i) __attribute__((always_inline)) { visit<D, Loops>(s, i); });
}

template <int D>
void visitCellsPlain(const SolverView<D>& s, const Grid<D>& g, const std::uint32_t* cells, std::size_t begin,
                     std::size_t end) {
    visitCells<D, PlainLoops<D>>(s, g, cells, begin, end);
}

#if SPINDRIFT_X86
[[gnu::target(SD_SOLVE_AVX512)]] void visitCellsAvx512(const SolverView<2>& s, const Grid<2>& g,
                                                       const std::uint32_t* cells, std::size_t begin, std::size_t end) {
    visitCells<2, Avx512Loops>(s, g, cells, begin, end);
}
[[gnu::target(SD_SOLVE_AVX2)]] void visitCellsAvx2(const SolverView<2>& s, const Grid<2>& g, const std::uint32_t* cells,
                                                   std::size_t begin, std::size_t end) {
    visitCells<2, Avx2Loops>(s, g, cells, begin, end);
}
#undef SD_SOLVE_AVX512
#undef SD_SOLVE_AVX2
#endif

/// The sweeps' copy for the process's update target (core/cpu_target.h):
/// the AVX-512 or AVX2 loops for a 2D fluid where the CPU has them.
template <int D>
auto visitCellsFor() {
#if SPINDRIFT_X86
    if constexpr (D == 2) {
        if (updateTarget() == UpdateTarget::Avx512) return &visitCellsAvx512;
        if (updateTarget() == UpdateTarget::Avx2) return &visitCellsAvx2;
    }
#endif
    return &visitCellsPlain<D>;
}

/// The accumulated impulse particle i starts the solve with: the previous
/// substep's, scaled, or none for a particle without neighbours. Such a
/// particle has nothing to push, and a pressure kept through its flight was
/// applied in full to the neighbours it met on landing: after a crush
/// (baumgarte near 0) a splash particle carried 2.9e4 m/s of it, and the
/// landing's warm start raised the fluid's kinetic energy from 578 to 1.5e9
/// (J/kg summed; docs/fluid.md, "Launches into tanks").
template <int D>
inline float warmPressure(const SolverView<D>& s, std::size_t i, float fraction) {
    return s.count[i] != 0 ? s.pressure[i] * fraction : 0.0f;
}

/// Warm start: the previous step's pressure, scaled, applied along this step's
/// directions, and taken as the starting accumulated impulse.
template <int D>
inline void warmStart(const SolverView<D>& s, std::size_t i, float fraction) {
    const float start = warmPressure<D>(s, i, fraction);
    s.pressure[i] = start;
    if (start != 0.0f) {
        applyImpulse<D>(s, i, start);
    }
}

/// Runs fn(cells, begin, end) over every colour group's cells, colour by
/// colour: the cells of one colour in parallel chunks (they share no
/// particle), each chunk cells[begin, end).
template <int D, class Fn>
void forEachColourChunk(WorkerPool& pool, const Grid<D>& g, Fn&& fn) {
    for (int colour = 0; colour < (1 << D); ++colour) {
        const std::vector<std::uint32_t>& cells = g.colourCells[colour];
        pool.forChunks(cells.size(), kCellChunk,
                       [&](std::size_t, std::size_t begin, std::size_t end) { fn(cells.data(), begin, end); });
    }
}

}  // namespace

template <int D>
void solveConstraints(WorkerPool& pool, FluidState& f, float dt) {
    Particles<D>& p = f.particles<D>();
    const std::size_t n = p.size();
    assignInRoom(f.pseudoImpulse, n, 0.0f);
    // The working copy of the velocities (Particles::motion), with the warm
    // start the setup gathered (neighbours.cpp) already added.
    const bool gathered = f.constraints.warmGathered && f.def.solver == FluidSolver::Parallel;
    p.motion.resize(n);
    pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        const glm::vec3* warm = f.constraints.warmVelocity.data();
        for (std::size_t i = begin; i < end; ++i) {
            p.motion[i] = Motion<D>{gathered ? p.velocity[i] + Vec<D>(warm[i]) : p.velocity[i], Vec<D>(0.0f)};
        }
    });
    const SolverView<D> s{p.motion.data(),
                          f.def.splitImpulse,
                          p.pressure.data(),
                          f.pseudoImpulse.data(),
                          f.neighbours<D>().data(),
                          f.constraints.first.data(),
                          f.constraints.listChunk.data(),
                          f.constraints.wallGradient.data(),
                          f.constraints.bias.data(),
                          f.constraints.invMass.data(),
                          f.constraints.count.data(),
                          kernels::fluidAllowanceSlop(f.restDensity, f.def.baumgarte, f.h, dt)};
    // The pressure is an impulse per (sub)step: when the substep length
    // changes, the warm start scales with it, or a switch from 1 to 8
    // substeps would apply 8 times the support per unit time and blow up.
    const float fraction = f.constraints.warmFraction;
    f.lastSubstep = dt;
    const std::uint32_t iterations = f.def.iterations;
    if (f.def.solver == FluidSolver::Sequential) {
        for (std::size_t i = 0; i < n; ++i) warmStart<D>(s, i, fraction);
        solveContacts<D>(pool, f, dt);
        for (std::uint32_t it = 0; it < iterations; ++it) {
            for (std::size_t i = 0; i < n; ++i) visit<D, PlainLoops<D>>(s, i);
            solveContacts<D>(pool, f, dt);
        }
    } else {
        const Grid<D>& g = f.grid<D>();
        if (gathered) {
            pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
                for (std::size_t i = begin; i < end; ++i) s.pressure[i] = warmPressure<D>(s, i, fraction);
            });
        } else {
            forEachColourChunk<D>(pool, g, [&](const std::uint32_t* cells, std::size_t begin, std::size_t end) {
                forParticlesOfCells<D>(g, cells, begin, end, [&](std::uint32_t i) { warmStart<D>(s, i, fraction); });
            });
        }
        solveContacts<D>(pool, f, dt);
        const auto sweep = visitCellsFor<D>();
        for (std::uint32_t it = 0; it < iterations; ++it) {
            forEachColourChunk<D>(pool, g, [&](const std::uint32_t* cells, std::size_t begin, std::size_t end) {
                sweep(s, g, cells, begin, end);
            });
            solveContacts<D>(pool, f, dt);
        }
    }
    pool.forChunks(n, kParticleChunk, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) p.velocity[i] = p.motion[i].velocity;
    });
}

template void solveConstraints<2>(WorkerPool&, FluidState&, float);
template void solveConstraints<3>(WorkerPool&, FluidState&, float);

}  // namespace spindrift::fluid
