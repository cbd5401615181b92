// Determinism (docs/design.md): the same inputs give bit-identical state for any
// thread count and from run to run.
#include "effects/effects_test_util.h"

#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

namespace spindrift {
namespace {

// A world using every feature, with more particles than one parallel chunk
// (4096) so that two threads really split the work.
std::vector<ParticleSnapshot> runEverything(std::uint32_t threads) {
    test::ScopedWorld w(threads, 11);
    FlowFieldDef flow;
    flow.boundsMin = glm::vec3(-5.0f);
    flow.boundsMax = glm::vec3(5.0f);
    flow.nx = flow.ny = flow.nz = 4;
    for (int i = 0; i < 64; ++i) {
        flow.velocities.push_back(glm::vec3(std::sin(i * 0.7f), std::cos(i * 1.3f), std::sin(i * 2.1f)));
    }
    FlowFieldId field = createFlowField(w.id, flow);
    createForce(w.id, test::gravity({0.0f, -9.81f, 0.0f}));
    ForceDef f;
    f.kind = ForceKind::Wind;
    f.vector = {1.0f, 0.0f, 0.5f};
    f.strength = 0.1f;
    createForce(w.id, f);
    f = ForceDef{};
    f.kind = ForceKind::Attractor;
    f.position = {1.0f, 2.0f, 0.0f};
    f.strength = 3.0f;
    createForce(w.id, f);
    f.kind = ForceKind::Vortex;
    createForce(w.id, f);
    f = ForceDef{};
    f.kind = ForceKind::Damping;
    f.strength = 0.2f;
    createForce(w.id, f);
    f = ForceDef{};
    f.kind = ForceKind::FlowField;
    f.flowField = field;
    f.viscosity = 0.01f;
    createForce(w.id, f);
    f = ForceDef{};
    f.kind = ForceKind::CurlNoise;
    f.strength = 1.5f;
    f.frequency = 0.8f;
    f.speed = 0.7f;
    f.octaves = 2;
    f.viscosity = 0.01f;
    createForce(w.id, f);
    createCollider(w.id, test::groundPlane(0.6f, 0.1f));
    ColliderDef sphere;
    sphere.kind = ColliderKind::Sphere;
    sphere.position = {0.0f, 1.0f, 0.0f};
    sphere.radius = 0.7f;
    createCollider(w.id, sphere);
    std::vector<EmitterId> emitters;
    const Integrator integrators[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler, Integrator::Verlet,
                                      Integrator::Rk4};
    for (int k = 0; k < 4; ++k) {
        EmitterDef e;
        e.lifecycle = k % 2 == 0 ? Lifecycle::Spawn : Lifecycle::Recycle;
        e.capacity = 9000;
        e.rate = 6000.0f;
        e.lifetime = {0.5f, 1.5f};
        e.speed = {1.0f, 5.0f};
        e.shape.kind = SpawnShapeKind::Sphere;
        e.shape.center = {0.0f, 3.0f, 0.0f};
        e.shape.radius = 0.5f;
        e.shape.spreadAngle = 1.0f;
        e.integrator = integrators[k];
        e.colorOverLife.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(0.0f)}};
        emitters.push_back(createEmitter(w.id, e));
    }
    for (int i = 0; i < 60; ++i) {
        stepWorld(w.id, 1.0f / 60.0f);
    }
    std::vector<ParticleSnapshot> out;
    for (EmitterId e : emitters) {
        out.push_back(readParticles(w.id, e));
    }
    return out;
}

template <class T>
bool bitEqual(const std::vector<T>& a, const std::vector<T>& b) {
    // memcmp must not see the null data() of an empty vector.
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every emitter's particles agree bit for bit; unless told otherwise, each
// emitter has more than `minimumCount` live particles, so the comparison is
// not vacuous.
void expectBitIdentical(const std::vector<ParticleSnapshot>& a, const std::vector<ParticleSnapshot>& b,
                        std::size_t minimumCount, bool everyEmitterAlive = true) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t e = 0; e < a.size(); ++e) {
        if (everyEmitterAlive) {
            EXPECT_GT(a[e].count(), minimumCount) << "emitter " << e;
        }
        EXPECT_TRUE(bitEqual(a[e].position, b[e].position)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].velocity, b[e].velocity)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].age, b[e].age)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].color, b[e].color)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].birth, b[e].birth)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].slot, b[e].slot)) << "emitter " << e;
    }
}

// More live particles than one parallel chunk (4096 slots): two threads split the work.
constexpr std::size_t kSeveralChunks = 4096;

TEST(Determinism, BitIdenticalForOneAndTwoThreads) {
    expectBitIdentical(runEverything(1), runEverything(2), kSeveralChunks);
}

TEST(Determinism, BitIdenticalRunToRun) {
    expectBitIdentical(runEverything(2), runEverything(2), kSeveralChunks);
}

}  // namespace
}  // namespace spindrift

// Every bundled scene, through the scene loader: 1 and 2 threads agree bit for bit.
namespace spindrift {
namespace {

std::vector<ParticleSnapshot> runScene(const std::string& path, std::uint32_t threads) {
    SceneDef scene = loadScene(path);
    scene.world.threads = threads;
    WorldId world = buildWorld(scene);
    for (int i = 0; i < 120; ++i) {
        stepWorld(world, scene.run.dt);
    }
    std::vector<ParticleSnapshot> out;
    for (std::uint32_t e = 1; e <= emitterCount(world); ++e) {
        out.push_back(readParticles(world, EmitterId{e}));
    }
    // Fluids compared through the same fields: density as age, pressure in
    // the colour, creation id as birth and slot.
    for (std::uint32_t f = 1; f <= fluidCount(world); ++f) {
        const FluidSnapshot fluid = readFluid(world, FluidId{f});
        ParticleSnapshot p;
        p.position = fluid.position;
        p.velocity = fluid.velocity;
        p.age = fluid.density;
        for (float pressure : fluid.pressure) p.color.emplace_back(pressure);
        p.birth = fluid.id;
        p.slot = fluid.id;
        out.push_back(std::move(p));
    }
    destroyWorld(world);
    return out;
}

TEST(Determinism, EveryBundledSceneIsBitIdenticalForOneAndTwoThreads) {
    int scenes = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(SPINDRIFT_SOURCE_DIR) + "/scenes")) {
        if (entry.path().extension() != ".toml") {
            continue;
        }
        SCOPED_TRACE(entry.path().string());
        std::vector<ParticleSnapshot> a = runScene(entry.path().string(), 1);
        std::vector<ParticleSnapshot> b = runScene(entry.path().string(), 2);
        // Not vacuous: the scene has live particles after 2 s (an emitter
        // may have none yet, as the showcase's steam before water arrives).
        std::size_t alive = 0;
        for (const ParticleSnapshot& p : a) alive += p.count();
        EXPECT_GT(alive, 0u);
        expectBitIdentical(a, b, 0, false);
        ++scenes;
    }
    EXPECT_GE(scenes, 6);
}

}  // namespace
}  // namespace spindrift
