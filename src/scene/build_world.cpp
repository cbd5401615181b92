// buildWorld(): a validated SceneDef becomes a world. References in the
// SceneDef are 1-based creation indices, so objects are created kind by kind
// in list order and each returned id is checked against that promise.
#include <spindrift/fires.h>
#include <spindrift/scene.h>

#include <fmt/format.h>

namespace spindrift {

namespace {

// Destroys the world if building it fails part way, so nothing half-built
// leaks out of buildWorld().
class WorldGuard {
public:
    explicit WorldGuard(WorldId world) : world_(world) {}
    WorldGuard(const WorldGuard&) = delete;
    WorldGuard& operator=(const WorldGuard&) = delete;
    ~WorldGuard() {
        if (armed_) {
            destroyWorld(world_);
        }
    }
    WorldId get() const { return world_; }
    WorldId release() {
        armed_ = false;
        return world_;
    }

private:
    WorldId world_;
    bool armed_ = true;
};

void expectId(std::uint32_t got, std::size_t position, const char* kind, const std::string& name) {
    const auto expected = static_cast<std::uint32_t>(position + 1);
    if (got != expected) {
        throw Error(
            fmt::format("buildWorld: {} \"{}\" got id {}, expected {} (its position in "
                        "the scene); references between objects would be wrong",
                        kind, name, got, expected));
    }
}

template <class Def, class Create>
void createAll(const std::vector<Def>& defs, const char* kind, Create create) {
    for (std::size_t i = 0; i < defs.size(); ++i) {
        expectId(create(defs[i]).index, i, kind, defs[i].name);
    }
}

}  // namespace

WorldId buildWorld(const SceneDef& scene) {
    WorldGuard guard(createWorld(scene.world));
    const WorldId world = guard.get();
    // Order matters: forces refer to flow fields, emitters to forces,
    // colliders and bodies, fluids' jets to bodies.
    createAll(scene.flowFields, "flow field",
              [&](const FlowFieldDef& d) { return createFlowField(world, d); });
    createAll(scene.forces, "force", [&](const ForceDef& d) { return createForce(world, d); });
    createAll(scene.colliders, "collider",
              [&](const ColliderDef& d) { return createCollider(world, d); });
    createAll(scene.bodies, "body", [&](const BodyDef& d) { return createBody(world, d); });
    createAll(scene.emitters, "emitter",
              [&](const EmitterDef& d) { return createEmitter(world, d); });
    createAll(scene.fluids, "fluid", [&](const FluidDef& d) { return createFluid(world, d); });
    createAll(scene.joints, "joint", [&](const JointDef& d) { return createJoint(world, d); });
    createAll(scene.fires, "fire", [&](const FireDef& d) { return createFire(world, d); });
    return guard.release();
}

}  // namespace spindrift
