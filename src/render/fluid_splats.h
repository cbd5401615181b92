// Sprinkle-style fluid splats, the CPU side (slides 55-69, "Rendering"): each
// rendered frame turns one fluid's state into per-splat instance data the
// renderer draws as oriented, stretched discs. The rules build on each other in
// the slides' order and each is switched by a FluidRenderDef flag:
//   1 raw       every particle a round splat (slide 62)
//   2 resize    radius from density: strays smaller (slide 63)
//   3 stretch   along the surface tangent and the velocity, temporally
//               smoothed per particle id (slides 57, 60, 64)
//   4 refract   the shader's work: nothing here (slide 65)
//   5 edges     edge factor, upward-facing surface brighter (slides 58, 66)
//   6 splashes  ballistic particles from rising strays (slides 61, 67)
//   7 bubbles   a stable subset of dense particles (slide 68)
// docs/rendering.md ("Fluid splats") lists every constant.
#pragma once

#include "kernels/fluid_look.glsl"
#include "kernels/render_layout.glsl"

#include <spindrift/fluid.h>
#include <spindrift/render.h>

#include <cstdint>
#include <span>
#include <vector>

namespace spindrift::render {

/// One splat as the shader reads it: src/kernels/layout.glsl. 48 bytes.
using SplatInstance = kernels::SplatInstance;

enum class SplatKind : std::uint32_t {
    Water = kernels::SD_SPLAT_WATER,
    Splash = kernels::SD_SPLAT_SPLASH,
    Bubble = kernels::SD_SPLAT_BUBBLE,
};

/// Displayed orientation of one particle, kept between frames (slide 60).
struct SplatOrientation {
    glm::vec3 axis{1.0f, 0.0f, 0.0f};  ///< unit, sign-free (a and -a are the same)
    float stretch = 0.0f;              ///< >= 1; 0: not seen yet
};

/// A splash: ballistic from where it was born, so its position is the closed
/// form origin + v0 age + g age^2 / 2 (no integration error).
struct Splash {
    glm::vec3 origin{0.0f};    ///< m
    glm::vec3 velocity{0.0f};  ///< m/s at birth
    float age = 0.0f;          ///< s
};

/// What one fluid's splats remember between frames.
struct FluidSplatState {
    /// Indexed by particle id (creation serial): ids survive the solver's
    /// reordering into grid order every step.
    std::vector<SplatOrientation> orientation;
    std::vector<Splash> splashes;
    /// Frames advanced (dt > 0): the counter of the splash RNG.
    std::uint32_t frame = 0;
};

/// Most splashes alive at once (slide 61: 800 in the 2nd generation).
inline constexpr std::size_t kMaxSplashes = 800;
/// Fastest turn of a displayed axis (rad/s; fluid_look.glsl).
inline constexpr float kMaxTurnRate = kernels::SD_SPLAT_MAX_TURN_RATE;
/// Rule 3: along the velocity a splat's major semi-axis grows by the distance
/// the particle moves in this time (s), like a short motion blur (slide 64);
/// the liquid surface stretches its kernels the same way (surface_field.cpp).
inline constexpr float kStretchTime = kernels::SD_STRETCH_TIME;

/// Writes fluid `fluid`'s splats into `out` (cleared first): one per particle
/// (in the solver's grid order), then the live splashes. `dt` (s) is world
/// time since the previous rendered frame: smoothing and splashes advance by
/// it; 0 (a repeated frame) changes no state. Throws Error for unknown ids.
void updateFluidSplats(FluidSplatState& state, WorldId world, FluidId fluid, const FluidRenderDef& settings,
                       float dt, std::vector<SplatInstance>& out);

/// Rule 6 alone, for a fluid whose particles stay on the device (issue 16;
/// device_water.h lists who throws there): advances the splashes by `dt`,
/// adds one from each of `throwers` (in particle order) while room is left,
/// and writes the live splashes' instances into `out` (cleared first), as
/// updateFluidSplats does after the water. Reads no particle.
void updateSplashes(FluidSplatState& state, WorldId world, FluidId fluid, const FluidRenderDef& settings, float dt,
                    std::span<const kernels::FluidSplashThrower> throwers, std::vector<SplatInstance>& out);
/// A particle's chance of throwing a splash over a frame of `dt` s.
float splashChance(float dt);
/// The unit vector against fluid `fluid`'s gravity (+y without; 2D: in the
/// plane), along which throwers rise.
glm::vec3 splashUp(WorldId world, FluidId fluid);

// Leaf rules, exposed for tests and the docs.

/// Edge factor from |d| in [0, 1], d = average neighbour direction (slide 57):
/// 0 in the interior (|d| ~ 0), 1 on a flat surface (|d| ~ 0.45 in 2D, 0.3 in 3D).
float edgeFactor(float averageDirectionLength);
/// Radius multiplier from rho / rho0 (slide 63): monotone, clamped.
float densityScale(float density);
/// Rotates `previous` toward `target` (unit, sign-free: target is first
/// flipped into previous's hemisphere) by at most `maxAngle` radians.
glm::vec3 turnToward(glm::vec3 previous, glm::vec3 target, float maxAngle);
/// Temporal smoothing of one particle's orientation (slide 60) over dt seconds.
SplatOrientation smoothOrientation(SplatOrientation previous, SplatOrientation target, float dt);
/// Whether particle `id` at density ratio `density` is drawn as a bubble
/// (slide 68): a pure function, so the choice never flickers.
bool isBubble(std::uint32_t id, float density);
/// The splat steps `settings` turns on, for a frame of `dt` s, splats of
/// `radius` m (splatRadius), `up` against gravity (fluid_look.glsl).
kernels::SplatSteps splatSteps(const FluidRenderDef& settings, float radius, glm::vec3 up, float dt,
                               std::uint32_t dimension);
/// Rule 1's splat radius (m) for particles `spacing` m apart.
float splatRadius(const FluidRenderDef& settings, float spacing);

}  // namespace spindrift::render
