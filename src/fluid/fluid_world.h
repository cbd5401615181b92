// What fluid_world.cpp offers the hub beyond fluid_state.h: the checks of a
// block or jet added to an existing fluid, and the read-back in creation order.
#pragma once

#include "fluid/fluid_state.h"

#include <spindrift/fluid.h>

#include <cstddef>

namespace spindrift::fluid {

/// Default smoothing length in spacings: 3.5 in 2D (36 lattice neighbours),
/// 2.75 in 3D (80 lattice neighbours, as at 2.5, whose outer shell at sqrt(6)
/// spacings had w = 6e-5 and now has 0.009). In 2D the wider kernel costs
/// about a tenth more a substep and takes a fifth fewer substeps on
/// LiquidFun's dam break (3.69 against 4.60 at 10k, 5.98 against 7.17 at
/// 30k: the compression a substep leaves falls), a step 0.83 to 0.91 of the
/// time at 3 (docs/fluid.md, "Eighth session of 2026-12-07"); 2.5 and 2.2
/// took more substeps than they saved. In 3D 2.75 took a third fewer
/// substeps than 2.5 and a substep about 30 % more (a disordered packing
/// holds more neighbours in the wider sphere): a 3D dam break step 2 to 13 %
/// cheaper; 3 spacings (92 lattice neighbours) took no fewer substeps than
/// 2.75 and cost more (docs/fluid.md, "The 3D kernel at 2.75 spacings").
inline constexpr float kDefaultSmoothing2 = 3.5f;
inline constexpr float kDefaultSmoothing3 = 2.75f;

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
