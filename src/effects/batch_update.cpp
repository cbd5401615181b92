// Run-time dispatch of the vector update: batch_update_body.inc compiled four
// times in this file, once per instruction set, each copy in its own namespace
// under a target pragma. Only functions defined after the pragma get the
// target; the headers above (glm, the kernels) keep the baseline one, and
// always-inline kernels are inlined into each copy, so no AVX2 code can leak
// into a function the baseline build calls.
#include "effects/batch_update.h"

#include <spindrift/errors.h>

#include <algorithm>
#include <bit>
#include <cmath>

// On x86 four copies: SSE2 (the baseline), SSE4.2, AVX2, AVX-512. Elsewhere only the
// baseline copy is built (the compiler's own vector width) and is reported
// under the Sse2 name; the others are unsupported.

namespace spindrift {
namespace {

#define SD_PRAGMA(...) _Pragma(#__VA_ARGS__)
#if defined(__clang__)
#define SD_TARGET_BEGIN(isa) SD_PRAGMA(clang attribute push(__attribute__((target(isa))), apply_to = function))
#define SD_TARGET_END SD_PRAGMA(clang attribute pop)
#else
#define SD_TARGET_BEGIN(isa) SD_PRAGMA(GCC push_options) SD_PRAGMA(GCC target(isa))
#define SD_TARGET_END SD_PRAGMA(GCC pop_options)
#endif

// AVX-512 with 512-bit vectors: g++ would otherwise keep 256-bit ones
// (clang's generic tuning takes 512 bits without being told; its target
// attribute has no such option).
#if defined(__clang__)
#define SD_AVX512 "avx512f,avx512vl,avx512bw,avx512dq"
#else
#define SD_AVX512 "avx512f,avx512vl,avx512bw,avx512dq,prefer-vector-width=512"
#endif

// Each lane loop: vectorise it, the lanes being independent.
#define SD_LANES _Pragma("omp simd")

namespace sse2 {
#include "effects/batch_update_body.inc"
}  // namespace sse2

#if SPINDRIFT_X86
SD_TARGET_BEGIN("sse4.2")
namespace sse4 {
#include "effects/batch_update_body.inc"
}  // namespace sse4
SD_TARGET_END

SD_TARGET_BEGIN("avx2")
namespace avx2 {
#include "effects/batch_update_body.inc"
}  // namespace avx2
SD_TARGET_END

SD_TARGET_BEGIN(SD_AVX512)
namespace avx512 {
#include "effects/batch_update_body.inc"
}  // namespace avx512
SD_TARGET_END
#else
namespace sse4 = sse2;  // never dispatched to: supports() is false
namespace avx2 = sse2;
namespace avx512 = sse2;
#endif

// The largest magnitude evaluateCurve (curves.glsl) can return: a key's value
// or a mix of two keys' values with a weight in [0, 1], x (1 - f) + y f, at
// most twice the larger key in magnitude even with rounding; 1 without keys.
double curveBound(const kernels::CurveParams& c) {
    double largest = c.count == 0u ? 1.0 : 0.0;
    for (kernels::uint i = 0u; i < c.count && i < kernels::SD_MAX_CURVE_KEYS; ++i) {
        for (int k = 0; k < 4; ++k) {
            largest = std::max(largest, 2.0 * std::abs(static_cast<double>(c.values[i][k])));
        }
    }
    return largest;
}

// Whether every particle's colour and size (restoreLook, derived.glsl: a
// start value mixed between two ends, times a curve) stay finite, so that
// finiteParticle can never remove a particle for them and the vector update
// need not compute them. Bounds in double: each mix at most twice its larger
// end, the product at most their product, with a factor 2 of margin for the
// float product's rounding. A NaN bound fails the comparison: not eligible.
bool lookStaysFinite(const kernels::EmitterParams& e) {
    const double limit = 0.5 * static_cast<double>(kernels::SD_FLOAT_MAX);
    double color = 0.0;
    for (int k = 0; k < 4; ++k) {
        color = std::max({color, 2.0 * std::abs(static_cast<double>(e.colorMin[k])),
                          2.0 * std::abs(static_cast<double>(e.colorMax[k]))});
    }
    const double size =
        2.0 * std::max(std::abs(static_cast<double>(e.sizeMin)), std::abs(static_cast<double>(e.sizeMax)));
    return color * curveBound(e.colorOverLife) <= limit && size * curveBound(e.sizeOverLife) <= limit;
}

}  // namespace

bool batchUpdateEligible(const kernels::KernelContext& ctx, const kernels::EmitterParams& e) {
    using namespace kernels;
    if (e.integrator == SD_INTEGRATE_VERLET || e.integrator == SD_INTEGRATE_RK4) {
        return false;
    }
    // The vector update leaves colour and size to their readers; an emitter
    // whose look could overflow runs the scalar kernel, which removes the
    // particles it overflows in.
    if (!lookStaysFinite(e)) {
        return false;
    }
    // Colour and size by speed have no lane loop: the scalar kernel's.
    if (e.colorOverSpeed.count != 0u || e.sizeOverSpeed.count != 0u) {
        return false;
    }
    for (uint i = 0u; i < ctx.forceTotal; ++i) {
        // The kinds the lane loops know; a new kind runs the scalar kernel
        // until it has its lane loop.
        const uint kind = ctx.forces[i].kind;
        const bool known = kind == SD_FORCE_GRAVITY || kind == SD_FORCE_WIND || kind == SD_FORCE_ATTRACTOR ||
                           kind == SD_FORCE_VORTEX || kind == SD_FORCE_DAMPING || kind == SD_FORCE_UNDAMPING;
        if ((e.forceMask & (1u << i)) != 0u && !known) {
            return false;
        }
    }
    if ((e.flags & SD_EMITTER_COLLISIONS) != 0u) {
        for (uint i = 0u; i < ctx.colliderTotal; ++i) {
            if ((e.colliderMask & (1u << i)) != 0u && ctx.colliders[i].kind != SD_COLLIDER_PLANE) {
                return false;
            }
        }
    }
    return true;
}

BatchConstants batchConstants(const kernels::KernelContext& ctx, const kernels::EmitterParams& e, float dt) {
    using namespace kernels;
    BatchConstants out;
    DragSum drag = noDrag();
    for (uint i = 0u; i < forceCount(ctx); ++i) {
        if ((e.forceMask & (1u << i)) == 0u) {
            continue;
        }
        const ForceParams& f = forceAt(ctx, i);
        if (f.kind == SD_FORCE_GRAVITY) {
            out.gravity += glm::vec3(f.vector);
        } else if (f.kind == SD_FORCE_WIND) {
            drag = addDrag(drag, f.strength, glm::vec3(f.vector));
        } else if ((f.kind == SD_FORCE_DAMPING || f.kind == SD_FORCE_UNDAMPING) && f.position.w <= 0.0f) {
            // relaxationRate ignores the position without a range.
            out.relaxationFactor[i] = relaxationFactor(relaxationRate(f, glm::vec3(0.0f)), dt);
        }
    }
    out.drag = linearDrag(drag, e.mass);
    out.weights = dragWeights(out.drag.rate, dt);
    return out;
}

BatchResult updateBatch(UpdateTarget target, const kernels::KernelContext& ctx, const kernels::EmitterParams& e,
                        const BatchConstants& constants, ParticleArrays& a, std::size_t first, float dt) {
    switch (target) {
    case UpdateTarget::Scalar: return BatchResult{};
    case UpdateTarget::Sse2: return sse2::updateBatch(ctx, e, constants, a, first, dt);
    case UpdateTarget::Sse4: return sse4::updateBatch(ctx, e, constants, a, first, dt);
    case UpdateTarget::Avx2: return avx2::updateBatch(ctx, e, constants, a, first, dt);
    case UpdateTarget::Avx512: return avx512::updateBatch(ctx, e, constants, a, first, dt);
    }
    return BatchResult{};
}

}  // namespace spindrift
