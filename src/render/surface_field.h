// The 2D liquid surface, the host side (issue 15): what each particle of a 2D
// fluid adds to the surface's field. The field (src/render/surface_pass.cpp)
// is the sum over particles of a smooth kernel (1 - q^2)^3, q = distance /
// radius, with the radius a fixed multiple of the spacing and the amplitude
// the particle's volume 1 / (rho / rho0) (clamped), normalised so that water
// at rest density on the block lattice sums to 1: an SPH colour field. The
// composite cuts it at kSurfaceThreshold. docs/rendering.md ("Liquid
// surface") lists every constant.
#pragma once

#include "render/fluid_splats.h"

namespace spindrift::render {

/// Kernel radius in spacings: wide enough that the sum is smooth across the
/// lattice (the splats' fish scales come from discs about one spacing wide).
inline constexpr float kSurfaceKernelSpacings = 2.0f;
/// Where the composite draws the edge, as a fraction of the field at rest
/// density: 0.5 would be half a spacing beyond the outer particles' centres on
/// a flat top; lower reaches a little further, so the liquid meets walls and
/// floor (where the field is ~0.5) under their slabs instead of leaving a
/// line of background between them.
inline constexpr float kSurfaceThreshold = 0.35f;
/// Most volume a particle carries (1 / (rho / rho0) is clamped to [1, this]):
/// lone drops stay visible without one stray becoming a large blob.
inline constexpr float kSurfaceMaxVolume = 3.0f;

/// The kernel's amplitude for a particle at density ratio `density`, for a
/// fluid whose kernel radius is kSurfaceKernelSpacings spacings.
float surfaceAmplitude(float density);
/// Foam in [0, 1]: where particles are fast or sparse (white water).
float surfaceFoam(float speed, float density);
/// Major semi-axis / radius of a kernel moving at `speed` (m/s), kernel
/// radius `radius` (m): the slides' velocity stretch (the distance moved in
/// 0.02 s) relative to the wider kernel, at most 2.
float surfaceStretch(float speed, float radius);

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
/// radius in spacings. Wider than half a spacing so that the front layer of a
/// lattice leaves no gap between spheres however it is seen (the cube's
/// half diagonal is 0.87 spacing, the face's 0.71).
inline constexpr float kScreenSphereSpacings = 0.75f;

/// Overwrites the first instances of `out` (fluid `fluid`'s water, one per
/// particle in the solver's order, as updateFluidSplats wrote them) with the
/// screen-space liquid's spheres: shade.y the particle's foam
/// (surfaceFoam). Returns how many (the particles). Throws Error for unknown
/// ids.
std::size_t screenFluidInstances(WorldId world, FluidId fluid, std::vector<SplatInstance>& out);

/// Fluid `fluid`'s spacing (m).
float fluidSpacing(WorldId world, FluidId fluid);

/// Fluid `fluid`'s dimension (2 or 3).
std::uint32_t fluidDimension(WorldId world, FluidId fluid);

}  // namespace spindrift::render
