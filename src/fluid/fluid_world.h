// What fluid_world.cpp offers the hub beyond fluid_state.h: the checks of a
// block or jet added to an existing fluid, and the read-back in creation order.
#pragma once

#include "fluid/fluid_state.h"

#include <spindrift/fluid.h>

#include <cstddef>

namespace spindrift::fluid {

/// Throws FieldError (field "block[index]...", 0-based as in a scene file) for
/// a block that `def`'s fluid cannot hold.
void validateBlock(const FluidDef& def, const FluidBlockDef& block, std::size_t index);
/// Throws FieldError (field "jet[index]...") for a jet `def`'s fluid cannot run.
void validateJet(const FluidDef& def, const FluidJetDef& jet, std::size_t index);
/// The fluid's particles in creation order (readFluid).
FluidSnapshot snapshotOf(const FluidState& f);
/// removeFluid and pourFluid (fluid.h) on one fluid.
std::uint32_t removeParticles(FluidState& f, glm::vec3 centre, float radius);
std::uint32_t pourParticles(FluidState& f, glm::vec3 centre, float radius, glm::vec3 velocity);

}  // namespace spindrift::fluid
