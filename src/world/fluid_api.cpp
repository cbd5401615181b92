// The fluids of a world: the public API of include/spindrift/fluid.h by world
// and fluid id, and the hub's fluids stage (stepFluids), which hands each
// fluid step what it may see of the world (fluid::StepContext) and the bodies
// through coupling's link.
#include "coupling/body_world.h"
#include "coupling/fluid_link.h"
#include "fluid/body_link.h"
#include "fluid/fluid_world.h"
#include "fluid/number_density.h"
#include "world/world.h"

#include <fmt/format.h>

#include <cmath>

namespace spindrift {
namespace {

void checkColliders(const World& w) {
    for (const ColliderDef& c : w.colliderDefs) {
        if (c.kind == ColliderKind::Terrain || c.kind == ColliderKind::CubeMap) {
            throw Error(fmt::format("collider '{}': fluids collide with plane, sphere and box colliders and "
                                    "their own polygons only; terrain and cube maps are not supported for fluids",
                                    c.name));
        }
    }
}

fluid::FluidState& fluidFromId(World& w, FluidId id) {
    if (id.index == 0 || id.index > w.fluids.size()) {
        throw Error(fmt::format("fluid id {} does not exist in this world", id.index));
    }
    return *w.fluids[id.index - 1];
}

}  // namespace

const fluid::FluidState& fluidStateFromId(const World& world, FluidId fluid) {
    if (fluid.index == 0 || fluid.index > world.fluids.size()) {
        throw Error(fmt::format("fluid id {} does not exist in this world", fluid.index));
    }
    return *world.fluids[fluid.index - 1];
}

void stepFluids(World& w, float dt, StepStats& stats) {
    if (w.fluids.empty()) return;
    checkColliders(w);
    coupling::FluidLink bodies(w.bodies.get());
    const fluid::StepContext context{w.pool, w.colliders, w.time, w.stepIndex, w.events, bodies};
    for (std::size_t i = 0; i < w.fluids.size(); ++i) {
        stats.fluids.push_back(
            fluid::stepFluid(context, *w.fluids[i], FluidId{static_cast<std::uint32_t>(i + 1)}, dt));
    }
}

void settleFluids(World& w) {
    if (!w.bodies) return;
    coupling::FluidLink bodies(w.bodies.get());
    for (const auto& f : w.fluids) {
        if (fluid::FluidBodyStep* moved = bodies.gatherMoved(*f)) {
            fluid::carryOutOfMovedBodies(w.pool, *f, *moved, w.colliders);
        }
    }
}

void validateFluidDef(const FluidDef& def) { fluid::validateFluidDef(def); }

FluidId createFluid(WorldId id, const FluidDef& def) {
    World& w = worldFromId(id);
    // The fluid has one solver, on the CPU, whichever backend runs the world's
    // emitters: a Vulkan world keeps its effects on the device and its fluids
    // here (the kernels in src/kernels/fluid.glsl are ready for a GPU port).
    fluid::validateFluidDef(def);
    checkColliders(w);
    fluid::checkBlocksClear(def, w.colliderDefs);
    for (const FluidJetDef& j : def.jets) coupling::checkJetBody(w.bodies.get(), j);
    std::unique_ptr<fluid::FluidState, FluidStateDeleter> f(new fluid::FluidState);
    f->def = def;
    fluid::initialiseFluid(*f);
    for (const FluidBlockDef& b : def.blocks) fluid::addBlock(*f, b);
    for (const FluidJetDef& j : def.jets) f->jets.push_back(fluid::Jet{j, w.time, 0.0, 0});
    w.fluids.push_back(std::move(f));
    return {static_cast<std::uint32_t>(w.fluids.size())};
}

void addFluidBlock(WorldId id, FluidId fluidId, const FluidBlockDef& block) {
    World& w = worldFromId(id);
    fluid::FluidState& f = fluidFromId(w, fluidId);
    fluid::validateBlock(f.def, block, f.def.blocks.size());
    FluidDef withBlock = f.def;
    withBlock.blocks.push_back(block);
    fluid::checkBlocksClear(withBlock, w.colliderDefs, f.def.blocks.size());
    fluid::addBlock(f, block);
    f.def.blocks.push_back(block);
}

void addFluidJet(WorldId id, FluidId fluidId, const FluidJetDef& jet) {
    World& w = worldFromId(id);
    fluid::FluidState& f = fluidFromId(w, fluidId);
    fluid::validateJet(f.def, jet, f.def.jets.size());
    coupling::checkJetBody(w.bodies.get(), jet);
    f.jets.push_back(fluid::Jet{jet, w.time, 0.0, 0});
    f.def.jets.push_back(jet);
}

namespace {

fluid::Jet& jetFromIndex(fluid::FluidState& f, std::uint32_t jet) {
    if (jet >= f.jets.size()) {
        throw Error(fmt::format("fluid '{}' has no jet {} (it has {})", f.def.name, jet, f.jets.size()));
    }
    if (f.def.dimension != 2) {
        throw Error(fmt::format("fluid '{}': only 2D jets aim", f.def.name));
    }
    return f.jets[jet];
}

}  // namespace

void setFluidSolver(WorldId id, FluidId fluidId, std::uint32_t iterations, float baumgarte) {
    fluid::FluidState& f = fluidFromId(worldFromId(id), fluidId);
    FluidDef def = f.def;
    def.iterations = iterations;
    def.baumgarte = baumgarte;
    validateFluidDef(def);
    f.def.iterations = iterations;
    f.def.baumgarte = baumgarte;
}

void aimFluidJet(WorldId id, FluidId fluidId, std::uint32_t jet, float angle) {
    if (!std::isfinite(angle)) throw Error("aimFluidJet: the angle must be finite");
    fluid::Jet& j = jetFromIndex(fluidFromId(worldFromId(id), fluidId), jet);
    j.aimOverride = true;
    j.overrideAngle = angle;
}

void releaseFluidJetAim(WorldId id, FluidId fluidId, std::uint32_t jet) {
    jetFromIndex(fluidFromId(worldFromId(id), fluidId), jet).aimOverride = false;
}

FluidJetPose fluidJetPose(WorldId id, FluidId fluidId, std::uint32_t jet) {
    World& w = worldFromId(id);
    const fluid::Jet& j = jetFromIndex(fluidFromId(w, fluidId), jet);
    const fluid::JetMount mount = coupling::jetMount(w.bodies.get(), j.def.body);
    const float c = std::cos(mount.angle), s = std::sin(mount.angle);
    const glm::vec2 p(j.def.position);
    return {mount.origin + glm::vec2(c * p.x - s * p.y, s * p.x + c * p.y), mount.angle};
}

std::uint32_t fluidCount(WorldId id) { return static_cast<std::uint32_t>(worldFromId(id).fluids.size()); }

const FluidDef& fluidDef(WorldId id, FluidId fluidId) {
    return fluidFromId(worldFromId(id), fluidId).def;
}

float fluidRestDensity(WorldId id, FluidId fluidId) {
    return fluidFromId(worldFromId(id), fluidId).restDensity;
}

std::uint32_t removeFluid(WorldId id, FluidId fluidId, glm::vec3 centre, float radius) {
    fluid::FluidState& f = fluidFromId(worldFromId(id), fluidId);
    if (!(radius >= 0.0f) || !std::isfinite(radius) || !std::isfinite(centre.x) || !std::isfinite(centre.y) ||
        !std::isfinite(centre.z)) {
        throw Error("removeFluid: expected a finite centre and radius >= 0");
    }
    return fluid::removeParticles(f, centre, radius);
}

std::uint32_t pourFluid(WorldId id, FluidId fluidId, glm::vec3 centre, float radius, glm::vec3 velocity) {
    fluid::FluidState& f = fluidFromId(worldFromId(id), fluidId);
    // The radius is bounded so one call is a brush, not a flood: at most
    // about 200^D lattice points are looked at.
    if (!(radius >= 0.0f) || !(radius <= 100.0f * f.def.spacing) || !std::isfinite(centre.x) ||
        !std::isfinite(centre.y) || !std::isfinite(centre.z) || !std::isfinite(velocity.x) ||
        !std::isfinite(velocity.y) || !std::isfinite(velocity.z)) {
        throw Error("pourFluid: expected a finite centre and velocity and a radius from 0 to 100 spacings");
    }
    return fluid::pourParticles(f, centre, radius, velocity);
}

FluidSnapshot readFluid(WorldId id, FluidId fluidId) {
    return fluid::snapshotOf(fluidFromId(worldFromId(id), fluidId));
}

FluidNumberDensity measureFluidNumberDensity(WorldId id, FluidId fluidId) {
    const fluid::FluidState& f = fluidFromId(worldFromId(id), fluidId);
    std::vector<glm::vec3> position;
    if (f.def.dimension == 2) {
        position.reserve(f.p2.size());
        for (const glm::vec2& p : f.p2.position) position.emplace_back(p, 0.0f);
    } else {
        position.assign(f.p3.position.begin(), f.p3.position.end());
    }
    return fluid::measureNumberDensity(position, f.def.dimension, f.def.spacing);
}

}  // namespace spindrift
