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
/// Rules 2, 3, 5 and 7 are fluid_look.glsl's (splatOfParticle and its
/// constants), which a fluid drawn from the device's buffers shares
/// (device_water.h).
/// Rule 6 (slide 61): which particles throw splashes, and how fast, is
/// fluid_look.glsl's (throwsSplash, splashSpeedFactor), shared with the
/// device's liquid (device_water.h). Smaller and brighter (slide 61), gone
/// after this age (s).
constexpr float kSplashRadius = 0.5f;
constexpr float kSplashBrightness = 1.6f;
constexpr float kSplashMaxAge = 2.0f;
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
    return kernels::splatAverageDirection(to3<D>(sum), weights);
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
    const kernels::SplatSteps steps = splatSteps(s, c.radius, c.up, c.dt, D);
    const glm::vec3 d = s.stretch || s.edges ? averageDirection<D>(v, i) : glm::vec3(0.0f);
    if (!s.stretch) {
        return kernels::splatOfParticle(to3<D>(v.position[i]), to3<D>(v.velocity[i]), v.density[i], v.id[i], d,
                                        glm::vec4(0.0f), steps)
            .instance;
    }
    SplatOrientation& shown = orientationOf(state, v.id[i]);
    const kernels::WaterSplat out = kernels::splatOfParticle(
        to3<D>(v.position[i]), to3<D>(v.velocity[i]), v.density[i], v.id[i], d, glm::vec4(shown.axis, shown.stretch),
        steps);
    shown = SplatOrientation{glm::vec3(out.shown), out.shown.w};
    return out.instance;
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
                   splatRadius(settings, f.def.spacing), gravity, upOf(gravity), {}};
    if (dimension == 2 && settings.splashes && dt > 0.0f) c.bodies = readBodies(worldId);
    return c;
}

}  // namespace

float edgeFactor(float averageDirectionLength) { return kernels::splatEdgeFactor(averageDirectionLength); }

float densityScale(float density) { return kernels::splatDensityScale(density); }

glm::vec3 turnToward(glm::vec3 previous, glm::vec3 target, float maxAngle) {
    return kernels::splatTurnToward(previous, target, maxAngle);
}

SplatOrientation smoothOrientation(SplatOrientation previous, SplatOrientation target, float dt) {
    const glm::vec4 shown = kernels::splatSmoothOrientation(glm::vec4(previous.axis, previous.stretch),
                                                            glm::vec4(target.axis, target.stretch), dt);
    return SplatOrientation{glm::vec3(shown), shown.w};
}

bool isBubble(std::uint32_t id, float density) { return kernels::splatIsBubble(id, density) != 0u; }

kernels::SplatSteps splatSteps(const FluidRenderDef& settings, float radius, glm::vec3 up, float dt,
                               std::uint32_t dimension) {
    kernels::SplatSteps s{};
    s.up = glm::vec4(up, std::max(dt, 0.0f));
    s.radius = radius;
    s.sizeFromDensity = settings.sizeFromDensity ? 1u : 0u;
    s.stretch = settings.stretch ? 1u : 0u;
    s.edges = settings.edges ? 1u : 0u;
    s.bubbles = settings.bubbles ? 1u : 0u;
    s.dimension = dimension;
    return s;
}

float splatRadius(const FluidRenderDef& settings, float spacing) {
    return settings.radiusScale * spacing * kRadiusPerSpacing;
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
