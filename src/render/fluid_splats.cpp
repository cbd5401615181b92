// Sprinkle-style fluid splats (slides 55-69): one fluid's state -> per-splat
// instances, each frame. See fluid_splats.h for the rules and
// docs/rendering.md ("Fluid splats") for the constants.
#include "render/fluid_splats.h"

#include "world/world.h"
#include "fluid/fluid_view.h"
#include "kernels/fluid_look.glsl"
#include "kernels/random.glsl"

#include <algorithm>
#include <cmath>

namespace spindrift::render {
namespace {

// --- Constants of the rules (docs/rendering.md ("Fluid splats")) ----------------

/// Rule 1: splat radius = radiusScale * spacing / 2 (m); radiusScale 1 gives
/// discs that touch on the block lattice (FluidRenderDef::radiusScale).
constexpr float kRadiusPerSpacing = 0.5f;
/// Rule 2: radius multiplier sqrt(rho / rho0) clamped to this range: a lone
/// particle (rho / rho0 ~ 0.1 at the default h) shrinks to 0.3, a compressed
/// one grows by at most 20%.
constexpr float kDensityScaleMin = 0.3f;
constexpr float kDensityScaleMax = 1.2f;
/// Rule 3/5: |d| (average neighbour direction) at or below which a particle is
/// interior, and at or above which it is surface. On the block lattice |d| is
/// 0.45 on a flat top in 2D (h = 3 spacings) and 0.30 in 3D (h = 2.5), one
/// row below the top 0.06 (2D) and 0.009 (3D), and 0 deeper.
constexpr float kEdgeInterior = 0.08f;
constexpr float kEdgeSurface = 0.25f;
/// Rule 3: extra stretch along the surface tangent at edge factor 1 (slide
/// 57: "stretch and rotate in direction of edge tangent").
constexpr float kEdgeStretch = 0.8f;
/// Rule 3: most stretch (major semi-axis / radius) of the combined axis.
constexpr float kMaxStretch = 3.0f;
/// Rule 3: time constant (s) with which the displayed stretch follows its
/// target (slide 60: temporal coherence).
constexpr float kStretchTau = 0.1f;
/// Rule 5: brightness 1 + kSunHighlight on a surface facing straight up
/// (slide 58: "render upward facing particles in brighter color").
constexpr float kSunHighlight = 0.5f;
/// Rule 6 (slide 61): which particles throw splashes, and how fast, is
/// fluid_look.glsl's (throwsSplash, splashSpeedFactor), shared with the
/// device's liquid (device_water.h). Smaller and brighter (slide 61), gone
/// after this age (s).
constexpr float kSplashRadius = 0.5f;
constexpr float kSplashBrightness = 1.6f;
constexpr float kSplashMaxAge = 2.0f;
/// Rule 7 (slide 68): one in kBubbleOneIn particles (by id) denser than
/// kBubbleDensity x rho0 is drawn as a bubble.
constexpr float kBubbleDensity = 1.02f;
constexpr std::uint32_t kBubbleOneIn = 8;
/// The bubbles' salt of the counter-based RNG (src/kernels/random.glsl).
constexpr std::uint32_t kBubbleSalt = 0xB0BB1Eu;

// --- Helpers -----------------------------------------------------------------

template <int D>
glm::vec3 to3(fluid::Vec<D> v) {
    if constexpr (D == 2) return glm::vec3(v.x, v.y, 0.0f); else return v;
}

/// Unit "up" for highlights and rising splashes: against gravity (+y without
/// gravity). In 2D only the xy part counts.
glm::vec3 upOf(glm::vec3 gravity) {
    const float len = glm::length(gravity);
    return len > 0.0f ? -gravity / len : glm::vec3(0.0f, 1.0f, 0.0f);
}

glm::vec3 flatIf2D(glm::vec3 v, std::uint32_t dimension) {
    return dimension == 2 ? glm::vec3(v.x, v.y, 0.0f) : v;
}

/// Average neighbour direction d = sum g / sum w (slide 57; g = w * unit
/// direction from the particle to the neighbour): |d| ~ 0 inside, large at
/// the surface, pointing into the fluid. 0 without neighbour lists.
template <int D>
glm::vec3 averageDirection(const fluid::FluidView<D>& v, std::size_t i) {
    if (i >= v.count.size()) return glm::vec3(0.0f);
    const fluid::Neighbour<D>* list = v.neighbourList(i);
    fluid::Vec<D> sum(0.0f);
    float weights = 0.0f;
    for (std::uint32_t k = 0; k < v.count[i]; ++k) {
        sum += list[k].g;
        weights += glm::length(list[k].g);
    }
    return weights > 0.0f ? to3<D>(sum / weights) : glm::vec3(0.0f);
}

/// Unit tangent of the surface whose inward direction is d (|d| > 0): in 2D
/// d turned by 90 degrees; in 3D the previous axis projected onto the tangent
/// plane (the most stable choice), else any tangent.
glm::vec3 surfaceTangent(glm::vec3 d, glm::vec3 previousAxis, std::uint32_t dimension) {
    const glm::vec3 n = glm::normalize(d);
    if (dimension == 2) return glm::vec3(-n.y, n.x, 0.0f);
    const glm::vec3 projected = previousAxis - n * glm::dot(previousAxis, n);
    if (glm::length(projected) > 0.3f) return glm::normalize(projected);
    const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    return glm::normalize(glm::cross(n, helper));
}

/// Rule 3's target orientation: surface stretch along the tangent (growing
/// with the edge factor) plus velocity stretch along the velocity (growing
/// with speed), summed as sign-free vectors (the velocity flipped into the
/// tangent's hemisphere), capped at kMaxStretch.
SplatOrientation targetOrientation(glm::vec3 tangent, float edge, glm::vec3 velocity, float radius,
                                   glm::vec3 previousAxis) {
    glm::vec3 sum = tangent * (kEdgeStretch * edge);
    const float speed = glm::length(velocity);
    if (speed > 0.0f && radius > 0.0f) {
        glm::vec3 along = velocity / speed;
        if (glm::dot(along, sum) < 0.0f) along = -along;
        sum += along * std::min(speed * kStretchTime / radius, kMaxStretch - 1.0f);
    }
    const float len = glm::length(sum);
    if (!(len > 1e-6f)) return SplatOrientation{previousAxis, 1.0f};
    return SplatOrientation{sum / len, std::min(1.0f + len, kMaxStretch)};
}

/// Exact ballistic position of a splash at its age.
glm::vec3 splashPosition(const Splash& s, glm::vec3 gravity, float age) {
    return s.origin + s.velocity * age + gravity * (0.5f * age * age);
}

struct FrameContext {
    const World* world;
    const fluid::FluidState* fluid;
    const FluidRenderDef* settings;
    float dt;
    float radius;       // m, rule 1's splat radius
    glm::vec3 gravity;  // m/s^2 (2D: z = 0)
    glm::vec3 up;
    std::vector<BodySnapshot> bodies;  // at their poses now (2D fluids only: splashes stop at them)
};

SplatOrientation& orientationOf(FluidSplatState& state, std::uint32_t id) {
    if (id >= state.orientation.size()) state.orientation.resize(static_cast<std::size_t>(id) + 1);
    return state.orientation[id];
}

/// Rules 1, 2, 3, 5, 7 for one fluid particle.
template <int D>
SplatInstance waterSplat(FluidSplatState& state, const FrameContext& c, const fluid::FluidView<D>& v,
                         std::size_t i) {
    const FluidRenderDef& s = *c.settings;
    const glm::vec3 x = to3<D>(v.position[i]);
    const float density = v.density[i];
    const std::uint32_t id = v.id[i];
    // Rule 1: round, base colour (slide 62).
    SplatInstance out{glm::vec4(x, c.radius), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f),
                      glm::vec4(1.0f, 0.0f, static_cast<float>(SplatKind::Water), density)};
    // Rule 2: strays smaller (slide 63).
    if (s.sizeFromDensity) out.centre.w = c.radius * densityScale(density);
    glm::vec3 d(0.0f);
    float edge = 0.0f;
    if (s.stretch || s.edges) {
        d = averageDirection<D>(v, i);
        edge = edgeFactor(glm::length(d));
    }
    // Rule 3: stretch along surface and velocity, smoothed (slides 57, 60, 64).
    if (s.stretch) {
        SplatOrientation& shown = orientationOf(state, id);
        const glm::vec3 previousAxis = shown.stretch > 0.0f ? shown.axis : glm::vec3(1.0f, 0.0f, 0.0f);
        const glm::vec3 tangent = edge > 0.0f ? surfaceTangent(d, previousAxis, D) : glm::vec3(0.0f);
        const SplatOrientation target = targetOrientation(tangent, edge, to3<D>(v.velocity[i]), c.radius, previousAxis);
        shown = shown.stretch > 0.0f ? smoothOrientation(shown, target, c.dt) : target;
        out.axis = glm::vec4(shown.axis, shown.stretch);
    }
    // Rule 5: edge factor; upward-facing surface brighter (slides 57-58, 66).
    if (s.edges) {
        out.shade.y = edge;
        const float len = glm::length(d);
        if (len > 0.0f) out.shade.x = 1.0f + kSunHighlight * std::max(glm::dot(-d / len, c.up), 0.0f) * edge;
    }
    // Rule 7: a stable subset of dense particles as bubbles (slide 68).
    if (s.bubbles && isBubble(id, density)) out.shade.z = static_cast<float>(SplatKind::Bubble);
    return out;
}

/// Rule 6, motion: each splash flies its exact parabola for dt and is removed
/// when that step's chord meets an obstacle or it is older than kSplashMaxAge
/// (slide 61: "removed upon collision"). Re-entering the water does not remove
/// it. Order kept, for determinism.
void advanceSplashes(FluidSplatState& state, const FrameContext& c) {
    if (c.dt <= 0.0f) return;
    std::erase_if(state.splashes, [&](Splash& s) {
        const glm::vec3 x0 = splashPosition(s, c.gravity, s.age);
        s.age += c.dt;
        const glm::vec3 x1 = splashPosition(s, c.gravity, s.age);
        return s.age > kSplashMaxAge || fluid::pathMeetsObstacle(c.world->colliders, *c.fluid, c.bodies, x0, x1);
    });
}

/// Rule 6, who throws: the particles below SD_SPLASH_MAX_DENSITY rising
/// faster than SD_SPLASH_MIN_RISE, each with probability 1 - exp(-SD_SPLASH_RATE
/// dt) from a counter-based hash of (particle id, frame) (fluid_look.glsl),
/// in particle order.
template <int D>
std::vector<kernels::FluidSplashThrower> throwersOf(const FluidSplatState& state, const FrameContext& c,
                                                    const fluid::FluidView<D>& v) {
    std::vector<kernels::FluidSplashThrower> out;
    if (c.dt <= 0.0f) return out;
    const float chance = splashChance(c.dt);
    for (std::size_t i = 0; i < v.position.size(); ++i) {
        const glm::vec3 velocity = to3<D>(v.velocity[i]);
        if (kernels::throwsSplash(v.density[i], velocity, c.up, v.id[i], state.frame, chance) == 0u) continue;
        kernels::FluidSplashThrower t{};
        t.position = glm::vec4(to3<D>(v.position[i]), 0.0f);
        t.velocity = glm::vec4(velocity, 0.0f);
        t.index = static_cast<std::uint32_t>(i);
        t.id = v.id[i];
        out.push_back(t);
    }
    return out;
}

/// Rule 6, birth: a splash from each thrower in turn, until kMaxSplashes
/// are alive.
void emitSplashes(FluidSplatState& state, const FrameContext& c,
                  std::span<const kernels::FluidSplashThrower> throwers) {
    if (c.dt <= 0.0f) return;
    for (const kernels::FluidSplashThrower& t : throwers) {
        if (state.splashes.size() >= kMaxSplashes) break;
        const float speedFactor = kernels::splashSpeedFactor(t.id, state.frame);
        state.splashes.push_back(Splash{glm::vec3(t.position), glm::vec3(t.velocity) * speedFactor, 0.0f});
    }
}

SplatInstance splashSplat(const Splash& s, const FrameContext& c) {
    return SplatInstance{glm::vec4(splashPosition(s, c.gravity, s.age), c.radius * kSplashRadius),
                         glm::vec4(1.0f, 0.0f, 0.0f, 1.0f),
                         glm::vec4(kSplashBrightness, 0.0f, static_cast<float>(SplatKind::Splash), 0.0f)};
}

template <int D>
void update(FluidSplatState& state, const FrameContext& c, std::vector<SplatInstance>& out) {
    const fluid::FluidView<D> v = fluid::viewFluid<D>(*c.fluid);
    out.reserve(v.position.size() + kMaxSplashes);
    for (std::size_t i = 0; i < v.position.size(); ++i) out.push_back(waterSplat<D>(state, c, v, i));
    if (!c.settings->splashes) {
        state.splashes.clear();  // off means none, and none frozen for later
        return;
    }
    advanceSplashes(state, c);
    emitSplashes(state, c, throwersOf<D>(state, c, v));
    for (const Splash& s : state.splashes) out.push_back(splashSplat(s, c));
    if (c.dt > 0.0f) state.frame += 1;
}

FrameContext frameContext(const World& world, WorldId worldId, const fluid::FluidState& f,
                          const FluidRenderDef& settings, float dt) {
    const std::uint32_t dimension = f.def.dimension;
    const glm::vec3 gravity = flatIf2D(f.def.gravity, dimension);
    FrameContext c{&world, &f, &settings, std::max(dt, 0.0f),
                   settings.radiusScale * f.def.spacing * kRadiusPerSpacing, gravity, upOf(gravity), {}};
    if (dimension == 2 && settings.splashes && dt > 0.0f) c.bodies = readBodies(worldId);
    return c;
}

}  // namespace

float edgeFactor(float averageDirectionLength) {
    return std::clamp((averageDirectionLength - kEdgeInterior) / (kEdgeSurface - kEdgeInterior), 0.0f, 1.0f);
}

float densityScale(float density) {
    return std::clamp(std::sqrt(std::max(density, 0.0f)), kDensityScaleMin, kDensityScaleMax);
}

glm::vec3 turnToward(glm::vec3 previous, glm::vec3 target, float maxAngle) {
    if (!(maxAngle > 0.0f)) return previous;  // bit for bit: a repeated frame changes nothing
    const float cosine = glm::dot(previous, target);
    if (cosine < 0.0f) target = -target;  // sign-free: the nearer of +-target
    const float c = std::min(std::abs(cosine), 1.0f);
    const float angle = std::acos(c);
    if (angle <= maxAngle) return target;
    const glm::vec3 offAxis = target - previous * c;
    const float offLength = glm::length(offAxis);
    if (!(offLength > 0.0f)) return target;
    const glm::vec3 across = offAxis / offLength;
    return glm::normalize(previous * std::cos(maxAngle) + across * std::sin(maxAngle));
}

SplatOrientation smoothOrientation(SplatOrientation previous, SplatOrientation target, float dt) {
    const float follow = 1.0f - std::exp(-std::max(dt, 0.0f) / kStretchTau);
    return SplatOrientation{turnToward(previous.axis, target.axis, kMaxTurnRate * std::max(dt, 0.0f)),
                            previous.stretch + (target.stretch - previous.stretch) * follow};
}

bool isBubble(std::uint32_t id, float density) {
    return density > kBubbleDensity && kernels::pcgHash(id ^ kBubbleSalt) % kBubbleOneIn == 0u;
}

float splashChance(float dt) { return 1.0f - std::exp(-kernels::SD_SPLASH_RATE * std::max(dt, 0.0f)); }

glm::vec3 splashUp(WorldId worldId, FluidId fluidId) {
    const fluid::FluidState& f = fluidSettingsFromId(worldFromId(worldId), fluidId);
    return upOf(flatIf2D(f.def.gravity, f.def.dimension));
}

void updateFluidSplats(FluidSplatState& state, WorldId worldId, FluidId fluidId, const FluidRenderDef& settings,
                       float dt, std::vector<SplatInstance>& out) {
    out.clear();
    const World& world = worldFromId(worldId);
    const fluid::FluidState& f = fluidStateFromId(world, fluidId);
    const FrameContext c = frameContext(world, worldId, f, settings, dt);
    if (f.def.dimension == 2) update<2>(state, c, out); else update<3>(state, c, out);
}

void updateSplashes(FluidSplatState& state, WorldId worldId, FluidId fluidId, const FluidRenderDef& settings,
                    float dt, std::span<const kernels::FluidSplashThrower> throwers, std::vector<SplatInstance>& out) {
    out.clear();
    if (!settings.splashes) {
        state.splashes.clear();  // as updateFluidSplats
        return;
    }
    const World& world = worldFromId(worldId);
    const FrameContext c = frameContext(world, worldId, fluidSettingsFromId(world, fluidId), settings, dt);
    advanceSplashes(state, c);
    emitSplashes(state, c, throwers);
    for (const Splash& s : state.splashes) out.push_back(splashSplat(s, c));
    if (c.dt > 0.0f) state.frame += 1;
}

}  // namespace spindrift::render
