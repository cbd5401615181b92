// A slot of an emitter's ParticleArrays as the kernels' Particle, and back:
// the CPU backend's storage of what changes after birth, with colour and size
// restored by the kernel the renderer and the Vulkan backend use
// (kernels::restoreLook, src/kernels/derived.glsl).
#pragma once

#include "particles/cpu_kernels.h"
#include "particles/emitter_state.h"

#include <cstddef>

namespace spindrift {

/// Slot i as stored: colour and size left zero (events and spawn requests,
/// which read neither).
kernels::Particle storedParticle(const ParticleArrays& a, const kernels::EmitterParams& e, std::size_t i);

/// Slot i with its colour and size restored (readers).
kernels::Particle loadParticle(const ParticleArrays& a, const kernels::EmitterParams& e, std::size_t i);

/// Slot i as the scalar kernel reads it (kernels::restoreUpdateLook).
kernels::Particle loadForUpdate(const ParticleArrays& a, const kernels::EmitterParams& e, std::size_t i);

/// Stores what the slot keeps of p (not its colour and size).
void storeParticle(ParticleArrays& a, std::size_t i, const kernels::Particle& p);

}  // namespace spindrift
