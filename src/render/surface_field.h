// The 2D liquid surface, the host side (issue 15): what each particle of a 2D
// fluid adds to the surface's field. The field (src/render/surface_pass.cpp)
// is the sum over particles of a smooth kernel (1 - q^2)^3, q = distance /
// radius, with the radius a fixed multiple of the spacing and the amplitude
// the particle's volume 1 / (rho / rho0) (clamped), normalised so that water
// at rest density on the block lattice sums to 1: an SPH colour field. The
// composite cuts it at kSurfaceThreshold. docs/rendering.md ("Liquid
// surface") lists every constant.
#pragma once

#include "kernels/fluid_look.glsl"
#include "render/fluid_splats.h"

namespace spindrift {
struct World;
}

namespace spindrift::render {

/// Kernel radius in spacings (fluid_look.glsl).
inline constexpr float kSurfaceKernelSpacings = kernels::SD_SURFACE_KERNEL_SPACINGS;
/// Where the composite draws the edge, as a fraction of the field at rest
/// density: 0.5 would be half a spacing beyond the outer particles' centres on
/// a flat top; lower reaches a little further, so the liquid meets walls and
/// floor (where the field is ~0.5) under their slabs instead of leaving a
/// line of background between them.
inline constexpr float kSurfaceThreshold = 0.35f;
/// Most volume a particle carries (fluid_look.glsl).
inline constexpr float kSurfaceMaxVolume = kernels::SD_SURFACE_MAX_VOLUME;

/// The kernel's amplitude, foam and velocity stretch (fluid_look.glsl: the
/// host's instances and the device's, src/render/device_water.h, share them).
using kernels::surfaceAmplitude;
using kernels::surfaceFoam;
using kernels::surfaceStretch;

/// Overwrites the first instances of `out` (fluid `fluid`'s water, one per
/// particle in the solver's order, as updateFluidSplats wrote them) with the
/// surface's kernels: centre.w the kernel radius, axis the velocity stretch
/// (when `stretch`), shade.x the amplitude, shade.y the foam. Then inserts,
/// before the splashes that follow, a mirror image behind each world plane of
/// every particle closer to it than the kernel radius, so the field does not
/// fall off at walls and floor (the edge would show there as a line).
/// Returns how many kernels lead `out` (particles and mirror images). Throws
/// Error for unknown ids.
std::size_t surfaceInstances(WorldId world, FluidId fluid, bool stretch, std::vector<SplatInstance>& out);

/// The screen-space liquid of 3D fluids (screen_fluid_pass.cpp): sphere
/// radius in spacings (fluid_look.glsl).
inline constexpr float kScreenSphereSpacings = kernels::SD_SCREEN_SPHERE_SPACINGS;

/// Overwrites the first instances of `out` (fluid `fluid`'s water, one per
/// particle in the solver's order, as updateFluidSplats wrote them) with the
/// screen-space liquid's spheres: shade.y the particle's foam
/// (surfaceFoam). Returns how many (the particles). Throws Error for unknown
/// ids.
std::size_t screenFluidInstances(WorldId world, FluidId fluid, std::vector<SplatInstance>& out);

/// The world's wall planes, as the mirror images meet them: a point, then
/// the unit normal, each a vec4 (w 0), in the colliders' order.
std::vector<glm::vec4> wallPlanes(const World& world);

/// Fluid `fluid`'s spacing (m).
float fluidSpacing(WorldId world, FluidId fluid);

/// Fluid `fluid`'s dimension (2 or 3).
std::uint32_t fluidDimension(WorldId world, FluidId fluid);

}  // namespace spindrift::render
