// The fluids of a world: the public API of include/spindrift/fluid.h by world
// and fluid id, and the hub's fluids stage (stepFluids), which hands each
// fluid step what it may see of the world (fluid::StepContext) and the bodies
// through coupling's link.
#include "coupling/body_world.h"
#include "coupling/fluid_link.h"
#include "fluid/body_contacts.h"
#include "fluid/body_link.h"
#include "fluid/fluid_world.h"
#include "fluid/number_density.h"
#include "gpu/gpu_world.h"
#include "gpu/vulkan_device.h"
#include "world/device_fluid.h"
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

/// Fluid i's state with its particle arrays current: a fluid on the device
/// keeps its particles there, and its host arrays are a copy read back only
/// when something on the host reads them (a snapshot, the renderer, a cache,
/// a brush), not after every step.
fluid::FluidState& hostFluid(const World& w, std::size_t i) {
    fluid::FluidState& f = *w.fluids[i];
    if (w.deviceFluids[i] && !deviceFluidOnHost(*w.deviceFluids[i])) readDeviceFluid(*w.deviceFluids[i], f);
    return f;
}

std::size_t fluidIndex(const World& w, FluidId id) {
    if (id.index == 0 || id.index > w.fluids.size()) {
        throw Error(fmt::format("fluid id {} does not exist in this world", id.index));
    }
    return id.index - 1;
}

fluid::FluidState& fluidFromId(World& w, FluidId id) { return hostFluid(w, fluidIndex(w, id)); }

}  // namespace

const fluid::FluidState& fluidStateFromId(const World& world, FluidId fluid) {
    return hostFluid(world, fluidIndex(world, fluid));
}

const fluid::FluidState& fluidSettingsFromId(const World& world, FluidId fluid) {
    return *world.fluids[fluidIndex(world, fluid)];
}

DeviceFluid* deviceFluidFromId(const World& world, FluidId fluid) {
    return world.deviceFluids[fluidIndex(world, fluid)].get();
}

/// Whether fluid `def` is solved on the device of `w` (FluidBackend): Gpu
/// needs a Vulkan world, Auto a Vulkan world on a hardware GPU and a fluid
/// the device runs. Throws Error for Gpu in a CPU world.
bool solvedOnDevice(const World& w, const FluidDef& def) {
    switch (def.backend) {
        case FluidBackend::Cpu:
            return false;
        case FluidBackend::Gpu:
            if (!w.gpu) {
                throw Error(fmt::format("fluid '{}': backend gpu needs a Vulkan world (a scene's [world] backend "
                                        "or --backend vulkan; WorldDef::backend in the API)",
                                        def.name));
            }
            return true;
        case FluidBackend::Auto:
            return w.gpu && gpu::hardwareGpuAvailable() && def.solver == FluidSolver::Parallel;
    }
    return false;
}

/// The bodies near fluid i, whose particles are on the device (null: none):
/// gathered from its box and largest speed as the device last reported
/// them, or from the host's arrays while they hold the particles.
fluid::FluidBodyStep* gatherForDevice(World& w, std::size_t i, coupling::FluidLink& bodies, float dt) {
    const fluid::FluidState& f = *w.fluids[i];
    if (deviceFluidOnHost(*w.deviceFluids[i])) return bodies.gather(f, dt);
    const DeviceFluidExtent e = deviceFluidExtent(*w.deviceFluids[i]);
    return e.count > 0 ? bodies.gatherNear(f, glm::vec2(e.low), glm::vec2(e.high), e.fastest, dt) : nullptr;
}

void stepFluids(World& w, float dt, StepStats& stats) {
    if (w.fluids.empty()) return;
    checkColliders(w);
    coupling::FluidLink bodies(w.bodies.get());
    const fluid::StepContext context{w.pool, w.colliders, w.time, w.stepIndex, w.events, bodies};
    for (std::size_t i = 0; i < w.fluids.size(); ++i) {
        fluid::FluidState& f = *w.fluids[i];
        const FluidId id{static_cast<std::uint32_t>(i + 1)};
        if (!w.deviceFluids[i]) {
            stats.fluids.push_back(fluid::stepFluid(context, f, id, dt));
            continue;
        }
        // The jets' births are emitted on the host (from the jets' own
        // state: no particle is read) and appended to the device's.
        std::uint64_t born = 0;
        if (!f.jets.empty()) {
            fluid::Births births;
            born = fluid::emitStepJets(context, f, deviceFluidCount(*w.deviceFluids[i]), dt, births);
            appendDeviceBirths(*w.deviceFluids[i], births);
        }
        // Bodies near a 2D fluid are gathered from the box and largest speed
        // its last substep reported (the same query as the CPU's gather, no
        // particle read back), and met on the device.
        f.bodies = f.def.dimension == 2 && w.bodies ? gatherForDevice(w, i, bodies, dt) : nullptr;
        FluidStepStats s = stepDeviceFluid(*w.deviceFluids[i], f, w.colliders, id, dt);
        s.born = born;
        fluid::endBodyStep(context, f, id, s);
        stats.fluids.push_back(s);
    }
}

/// After an edit of fluid i's particles on the host: the device's copy
/// replaced by them.
void fluidEdited(World& w, std::size_t i) {
    if (w.deviceFluids[i]) uploadDeviceFluid(*w.deviceFluids[i], *w.fluids[i]);
}

void settleFluids(World& w) {
    if (!w.bodies) return;
    coupling::FluidLink bodies(w.bodies.get());
    for (std::size_t i = 0; i < w.fluids.size(); ++i) {
        fluid::FluidState& f = *w.fluids[i];
        fluid::FluidBodyStep* moved = bodies.gatherMoved(f);
        if (moved == nullptr) continue;
        if (!w.deviceFluids[i]) {
            fluid::carryOutOfMovedBodies(w.pool, f, *moved, w.colliders);
            continue;
        }
        // On the device, the same rule (no particle read back).
        carryDeviceFluid(*w.deviceFluids[i], f, *moved);
    }
}

void validateFluidDef(const FluidDef& def) { fluid::validateFluidDef(def); }

FluidId createFluid(WorldId id, const FluidDef& def) {
    World& w = worldFromId(id);
    // The fluid is solved on the CPU or on the world's device (FluidBackend,
    // solvedOnDevice): both from the rules of src/kernels/fluid.glsl.
    fluid::validateFluidDef(def);
    checkColliders(w);
    fluid::checkBlocksClear(def, w.colliderDefs);
    for (const FluidJetDef& j : def.jets) coupling::checkJetBody(w.bodies.get(), j);
    std::unique_ptr<fluid::FluidState, FluidStateDeleter> f(new fluid::FluidState);
    f->def = def;
    fluid::initialiseFluid(*f);
    for (const FluidBlockDef& b : def.blocks) fluid::addBlock(*f, b);
    for (const FluidJetDef& j : def.jets) f->jets.push_back(fluid::Jet{j, w.time, 0.0, 0});
    DeviceFluidPtr onDevice;
    if (solvedOnDevice(w, def)) onDevice = createDeviceFluid(*w.gpu->device, *f);
    w.fluids.push_back(std::move(f));
    w.deviceFluids.push_back(std::move(onDevice));
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
    fluidEdited(w, fluidId.index - 1);
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
    World& w = worldFromId(id);
    fluid::FluidState& f = fluidFromId(w, fluidId);
    if (!(radius >= 0.0f) || !std::isfinite(radius) || !std::isfinite(centre.x) || !std::isfinite(centre.y) ||
        !std::isfinite(centre.z)) {
        throw Error("removeFluid: expected a finite centre and radius >= 0");
    }
    const std::uint32_t removed = fluid::removeParticles(f, centre, radius);
    if (removed > 0) fluidEdited(w, fluidId.index - 1);
    return removed;
}

std::uint32_t pourFluid(WorldId id, FluidId fluidId, glm::vec3 centre, float radius, glm::vec3 velocity) {
    World& w = worldFromId(id);
    fluid::FluidState& f = fluidFromId(w, fluidId);
    // The radius is bounded so one call is a brush, not a flood: at most
    // about 200^D lattice points are looked at.
    if (!(radius >= 0.0f) || !(radius <= 100.0f * f.def.spacing) || !std::isfinite(centre.x) ||
        !std::isfinite(centre.y) || !std::isfinite(centre.z) || !std::isfinite(velocity.x) ||
        !std::isfinite(velocity.y) || !std::isfinite(velocity.z)) {
        throw Error("pourFluid: expected a finite centre and velocity and a radius from 0 to 100 spacings");
    }
    const std::uint32_t poured = fluid::pourParticles(f, centre, radius, velocity);
    if (poured > 0) fluidEdited(w, fluidId.index - 1);
    return poured;
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
