// The CPU backend's vector update: the common case of a step (a live particle
// that is neither born nor dies, whether it strikes plane colliders or not)
// for kBatchLanes slots at once, with SIMD lanes chosen at run time;
// everything else stays with the scalar kernel, updateParticle. Bit-identical
// to the scalar kernel at every SIMD width (docs/performance.md, "Vectorised
// update"; tests/effects/vector_update_test.cpp).
#pragma once

#include "core/cpu_target.h"
#include "kernels/layout.glsl"
#include "particles/cpu_kernels.h"
#include "particles/emitter_state.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spindrift {

/// Slots per batch: a multiple of every SIMD width dispatched to (4, 8 and 16
/// floats), and at most 64 (a LaneMask's bits).
inline constexpr std::size_t kBatchLanes = 64;
/// One bit per slot of a batch (bit l: slot first + l).
using LaneMask = std::uint64_t;
static_assert(kBatchLanes % 16 == 0 && kBatchLanes <= 8 * sizeof(LaneMask));
/// The lane mask with every lane of a batch set.
inline constexpr LaneMask kAllBatchLanes = ~LaneMask{0} >> (8 * sizeof(LaneMask) - kBatchLanes);

/// Whether the vector update can take emitter e's slots this step: Euler
/// integrators, no flow fields, only plane colliders, no over-speed curves,
/// a colour and size that cannot overflow (they are not stored, and the
/// vector update does not compute them); anything else runs the scalar
/// kernel, as before.
bool batchUpdateEligible(const kernels::KernelContext& ctx, const kernels::EmitterParams& e);

/// What every batch of an emitter's step shares (forcingAt's gravity and
/// drag, the drag's weights over dt, and the factor of each damping force
/// without range), computed once per step by batchConstants with the same
/// kernel calls in the same order as the scalar kernel makes them per slot.
struct BatchConstants {
    glm::vec3 gravity{0.0f};
    kernels::LinearDrag drag{};
    kernels::DragWeights weights{};
    float relaxationFactor[kernels::SD_MAX_FORCES] = {};  // by force index; damping without range only
};
BatchConstants batchConstants(const kernels::KernelContext& ctx, const kernels::EmitterParams& e, float dt);

/// What updateBatch did with a batch of slots (bit l: slot first + l).
struct BatchResult {
    /// Lanes updated here, the others left untouched for the scalar kernel.
    LaneMask finished = 0;
    /// Finished lanes that struck a collider this step: their updates still
    /// owe the step's counts, events and spawn requests (impacts only: a lane
    /// that dies of it is left to the scalar kernel).
    LaneMask struck = 0;
    std::uint32_t hitMask[kBatchLanes] = {};      ///< colliders struck (bit i: collider i), where struck
    glm::vec3 startVelocity[kBatchLanes] = {};    ///< m/s, at the start of the step, where struck
};

/// Updates the slots first .. first + kBatchLanes - 1 that take the common case
/// (see BatchResult); the other slots are untouched, for the scalar kernel.
/// Requires batchUpdateEligible.
BatchResult updateBatch(UpdateTarget target, const kernels::KernelContext& ctx, const kernels::EmitterParams& e,
                        const BatchConstants& constants, ParticleArrays& a, std::size_t first, float dt);

}  // namespace spindrift
