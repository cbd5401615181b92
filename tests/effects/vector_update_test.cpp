// The CPU's vector update (src/effects/batch_update.h) gives the particles the
// scalar kernel gives, bit for bit, at every SIMD width this CPU can run: the
// same operations in the same order per particle. Independent reference: the
// scalar kernel, updateParticle, which the GPU backend runs too.
#include "core/scoped_update_target.h"
#include "effects/batch_update.h"
#include "effects/effects_test_util.h"

#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

namespace spindrift {
namespace {

using test::ScopedTarget;

template <class T>
bool bitEqual(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectSameParticles(const std::vector<ParticleSnapshot>& a, const std::vector<ParticleSnapshot>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t e = 0; e < a.size(); ++e) {
        EXPECT_TRUE(bitEqual(a[e].position, b[e].position)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].velocity, b[e].velocity)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].age, b[e].age)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].lifetime, b[e].lifetime)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].size, b[e].size)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].rotation, b[e].rotation)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].color, b[e].color)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].birth, b[e].birth)) << "emitter " << e;
        EXPECT_TRUE(bitEqual(a[e].slot, b[e].slot)) << "emitter " << e;
    }
}

// What a run reports besides its particles: every step's counts and every
// event, in order. The vector update must leave them as the scalar kernel
// does, impacts included (it takes striking lanes too).
struct RunReport {
    std::vector<std::uint64_t> counts;  // per step: born, died, collisions, hits of each collider
    std::vector<ParticleEvent> events;
    std::uint64_t dropped = 0;  // events past the world's capacity per step
    std::uint64_t offered = 0;  // a collision event per hit, a death event per death
    std::uint64_t keptIfFirst = 0;  // sum over steps of min(capacity, that step's offered)
};

void expectSameReport(const RunReport& a, const RunReport& b) {
    EXPECT_EQ(a.counts, b.counts);
    EXPECT_EQ(a.dropped, b.dropped);
    ASSERT_EQ(a.events.size(), b.events.size());
    for (std::size_t k = 0; k < a.events.size(); ++k) {
        const ParticleEvent& x = a.events[k];
        const ParticleEvent& y = b.events[k];
        EXPECT_TRUE(x.kind == y.kind && x.step == y.step && x.emitter.index == y.emitter.index &&
                    x.collider.index == y.collider.index && x.birth == y.birth &&
                    std::memcmp(&x.position, &y.position, sizeof(glm::vec3)) == 0 &&
                    std::memcmp(&x.speed, &y.speed, sizeof(float)) == 0)
            << "event " << k;
    }
}

// Everything the vector update takes: every force kind but flow fields (with
// each literal falloff and a general one, local damping and un-damping), two
// planes, both Euler integrators, both lifecycles, over-life curves of 1 to 3
// keys, births, deaths and hits in every step, impacts that kill or take life
// in both lifecycles, and a sub-emitter born from one emitter's collisions.
std::vector<ParticleSnapshot> runVectorisable(std::uint32_t threads, std::size_t& live, RunReport& report,
                                              std::uint32_t eventCapacity = WorldDef{}.eventCapacity) {
    test::ScopedWorld w(threads, 5, Backend::Cpu, 1, eventCapacity);
    createForce(w.id, test::gravity({0.0f, -9.81f, 0.0f}));
    ForceDef f;
    f.kind = ForceKind::Wind;
    f.vector = {1.0f, 0.0f, 0.5f};
    f.strength = 0.1f;
    createForce(w.id, f);
    const float falloffs[] = {2.0f, 1.0f, 0.0f, -1.0f, 1.5f};
    for (int k = 0; k < 5; ++k) {
        f = ForceDef{};
        f.kind = k % 2 == 0 ? ForceKind::Attractor : ForceKind::Vortex;
        f.position = {0.5f * static_cast<float>(k) - 1.0f, 2.0f, 0.3f};
        f.strength = k == 3 ? -2.0f : 3.0f;
        f.radius = 0.5f;
        f.falloff = falloffs[k];
        f.range = k == 1 ? 2.0f : 0.0f;
        createForce(w.id, f);
    }
    f = ForceDef{};
    f.kind = ForceKind::Damping;
    f.strength = 0.3f;
    createForce(w.id, f);
    f.range = 3.0f;  // local damping: a rate per particle
    f.position = {0.0f, 1.0f, 0.0f};
    createForce(w.id, f);
    f = ForceDef{};
    f.kind = ForceKind::Undamping;
    f.strength = 0.5f;
    f.targetSpeed = 2.0f;
    createForce(w.id, f);
    createCollider(w.id, test::groundPlane(0.6f, 0.1f));
    ColliderDef wall;
    wall.kind = ColliderKind::Plane;
    wall.position = {1.5f, 0.0f, 0.0f};
    wall.normal = {-1.0f, 0.0f, 0.0f};
    createCollider(w.id, wall);
    std::vector<EmitterId> emitters;
    const Integrator integrators[] = {Integrator::ExplicitEuler, Integrator::SemiImplicitEuler};
    for (int k = 0; k < 6; ++k) {
        EmitterDef e;
        e.lifecycle = k % 2 == 0 ? Lifecycle::Spawn : Lifecycle::Recycle;
        e.capacity = 6000;
        e.rate = 5000.0f;
        e.lifetime = {0.3f, 1.2f};
        e.speed = {1.0f, 5.0f};
        e.shape.kind = SpawnShapeKind::Sphere;
        e.shape.center = {0.0f, 2.0f, 0.0f};
        e.shape.radius = 0.5f;
        e.shape.spreadAngle = 1.5f;
        e.integrator = integrators[(k / 2) % 2];
        e.collision.killOnCollision = k == 3 || k == 4;
        e.collision.lifeLossOnCollision = k == 2 || k == 5 ? 0.3f : 0.0f;
        e.colorOverLife.keys = {{0.0f, glm::vec4(1.0f)}, {0.4f, glm::vec4(0.5f, 0.2f, 0.1f, 0.7f)},
                                {1.0f, glm::vec4(0.0f)}};
        if (k != 1) {
            e.sizeOverLife.keys = {{0.2f, glm::vec4(0.5f)}};
        }
        emitters.push_back(createEmitter(w.id, e));
    }
    EmitterDef sparks;  // two children at each collision of the first emitter
    sparks.lifecycle = Lifecycle::Spawn;
    sparks.capacity = 20000;
    sparks.rate = 0.0f;
    sparks.lifetime = {0.2f, 0.4f};
    sparks.speed = {0.5f, 1.0f};
    sparks.spawnOn.parent = emitters[0];
    sparks.spawnOn.event = SpawnEvent::Collision;
    sparks.spawnOn.count = 2;
    sparks.spawnOn.inheritVelocity = 0.5f;
    emitters.push_back(createEmitter(w.id, sparks));
    report = RunReport{};
    for (int i = 0; i < 50; ++i) {
        const StepStats s = stepWorld(w.id, 1.0f / 60.0f);
        report.counts.insert(report.counts.end(), {s.born, s.died, s.collisions});
        report.offered += s.died + s.collisions;
        report.keptIfFirst += std::min<std::uint64_t>(eventCapacity, s.died + s.collisions);
        for (const ColliderStepStats& c : s.colliderHits) {
            report.counts.push_back(c.hits);
        }
    }
    EventBatch batch = takeEvents(w.id);
    report.events = std::move(batch.events);
    report.dropped = batch.dropped;
    std::vector<ParticleSnapshot> out;
    live = 0;
    for (EmitterId e : emitters) {
        out.push_back(readParticles(w.id, e));
        live += out.back().count() > 0 ? 1 : 0;
    }
    return out;
}

TEST(VectorUpdate, EveryTargetMatchesTheScalarKernel) {
    std::size_t live = 0;
    std::vector<ParticleSnapshot> scalar;
    RunReport scalarReport;
    {
        ScopedTarget t(UpdateTarget::Scalar);
        scalar = runVectorisable(1, live, scalarReport);
    }
    EXPECT_EQ(live, 7u);
    // Not vacuous: the run has impacts, their events and their children.
    std::size_t collisions = 0;
    for (const ParticleEvent& ev : scalarReport.events) {
        collisions += ev.kind == ParticleEventKind::Collision ? 1 : 0;
    }
    EXPECT_GT(collisions, 100u);
    ASSERT_GE(supportedUpdateTargets().size(), 2u);  // scalar and the x86-64 baseline
    for (UpdateTarget target : supportedUpdateTargets()) {
        SCOPED_TRACE(std::string(updateTargetName(target)));
        ScopedTarget t(target);
        RunReport report;
        expectSameParticles(scalar, runVectorisable(target == UpdateTarget::Sse2 ? 2u : 1u, live, report));
        expectSameReport(scalarReport, report);
    }
}

// Colour and size are not stored and the vector update does not compute
// them, so an emitter whose look could overflow runs the scalar kernel, which
// removes a particle in the step its colour leaves the floats
// (finiteParticle). Independent reference: a colour of 1e30 times a curve
// from 1 at half the life to 1e30 at its end passes FLT_MAX (3.4e38) as soon
// as the age passes 0.5 s, so after 1.5 s at 600 particles/s the particles
// born in the first second (600, give or take a step's 10) are removed and
// the rest live, at every target alike.
TEST(VectorUpdate, ALookThatCouldOverflowRunsTheScalarKernel) {
    const kernels::KernelContext ctx{nullptr, 0u, nullptr, 0u, nullptr, 0.0f};
    kernels::EmitterParams params{};
    params.mass = 1.0f;
    params.integrator = kernels::SD_INTEGRATE_SEMI_IMPLICIT_EULER;
    params.colorMax = glm::vec4(1.0e30f);
    params.colorOverLife.count = 2u;
    params.colorOverLife.values[0] = glm::vec4(1.0f);
    params.colorOverLife.values[1] = glm::vec4(1.0f);
    EXPECT_TRUE(batchUpdateEligible(ctx, params));  // 1e30 times at most 1
    params.colorOverLife.values[1] = glm::vec4(1.0e30f);
    EXPECT_FALSE(batchUpdateEligible(ctx, params));
    params.colorOverLife.values[1] = glm::vec4(1.0f);
    params.sizeMax = 1.0e20f;
    params.sizeOverLife.count = 1u;
    params.sizeOverLife.values[0] = glm::vec4(1.0e20f);
    EXPECT_FALSE(batchUpdateEligible(ctx, params));  // size 1e40

    std::vector<std::uint64_t> removedAt;
    for (UpdateTarget target : supportedUpdateTargets()) {
        SCOPED_TRACE(std::string(updateTargetName(target)));
        ScopedTarget t(target);
        test::ScopedWorld w(1);
        EmitterDef e;
        e.lifecycle = Lifecycle::Spawn;
        e.capacity = 2000;
        e.rate = 600.0f;
        e.lifetime = {1.0f, 1.0f};
        e.speed = {0.0f, 0.0f};
        e.color = {glm::vec4(1.0e30f, 1.0e30f, 1.0e30f, 1.0f), glm::vec4(1.0e30f, 1.0e30f, 1.0e30f, 1.0f)};
        e.colorOverLife.keys = {{0.5f, glm::vec4(1.0f)}, {1.0f, glm::vec4(1.0e30f)}};
        const EmitterId id = createEmitter(w.id, e);
        std::uint64_t born = 0, removed = 0, died = 0;
        for (int i = 0; i < 90; ++i) {
            const StepStats s = stepWorld(w.id, 1.0f / 60.0f);
            born += s.born;
            removed += s.nonFinite;
            died += s.died;
        }
        EXPECT_EQ(born, 900u);
        EXPECT_EQ(died, 0u);
        EXPECT_GE(removed, 590u);
        EXPECT_LE(removed, 610u);
        const ParticleSnapshot p = readParticles(w.id, id);
        EXPECT_EQ(p.count() + removed, born);
        for (std::size_t i = 0; i < p.count(); ++i) {
            ASSERT_LE(p.age[i], 0.5f) << i;
            ASSERT_LE(p.color[i].r, 1.0e30f * 1.0001f) << i;  // at most the curve's 1 before half the life
        }
        removedAt.push_back(removed);
    }
    for (std::uint64_t r : removedAt) {
        EXPECT_EQ(r, removedAt.front());
    }
}

// A step's events past the world's capacity are dropped and counted, the
// same ones at every target and thread count: the update's chunks skip
// building the events that lie past the step's room (ChunkPrefix,
// emitter_step.cpp), and which chunks skip depends on the order they run in.
// Independent reference: the scalar kernel's run with the same capacity on
// one thread, and the conservation of the offered events.
TEST(VectorUpdate, EventsPastTheCapacityAreTheScalarKernels) {
    constexpr std::uint32_t kCapacity = 30;  // per step; the run has more events than that in most steps
    std::size_t live = 0;
    RunReport scalarReport;
    {
        ScopedTarget t(UpdateTarget::Scalar);
        runVectorisable(1, live, scalarReport, kCapacity);
    }
    EXPECT_GT(scalarReport.dropped, 1000u);  // not vacuous
    EXPECT_LE(scalarReport.events.size(), 50u * kCapacity);
    // Conservation: every hit and death is an event, kept or counted dropped.
    EXPECT_EQ(scalarReport.events.size() + scalarReport.dropped, scalarReport.offered);
    // Every step keeps as many as it has room for: none dropped while there
    // was room (the vector update's chunks skip building only events past it).
    EXPECT_EQ(scalarReport.events.size(), scalarReport.keptIfFirst);
    for (UpdateTarget target : supportedUpdateTargets()) {
        SCOPED_TRACE(std::string(updateTargetName(target)));
        ScopedTarget t(target);
        RunReport report;
        runVectorisable(2, live, report, kCapacity);
        expectSameReport(scalarReport, report);
    }
}

// Not vacuous: a batch of quiet particles (alive, not dying, above the only
// plane) is taken by the vector update at every target, and so is a lane
// resting on the plane (pushed out at 0.01 m/s, under the plane's rest speed
// of 0.1 m/s: no impact) and a lane striking it at 100 m/s (an impact,
// reported as struck with its hit mask and start velocity), each with the
// scalar kernel's exact result; a lane whose speed squared overflows (the
// scalar kernel removes it) is left to the scalar kernel, and so is the
// striking lane when the impact kills a spawn-mode particle (it dies this
// step), but not a recycle-mode one (re-born next step); the scalar target
// takes none.
TEST(VectorUpdate, TakesQuietAndStrikingLanesAndLeavesTheRest) {
    kernels::ColliderParams plane{};
    plane.kind = kernels::SD_COLLIDER_PLANE;
    plane.normal = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
    plane.restSpeed = 0.1f;
    plane.resilience = 0.5f;
    plane.friction = 0.2f;
    const kernels::KernelContext ctx{nullptr, 0u, &plane, 1u, nullptr, 0.0f};
    constexpr std::size_t kStrike = 3, kResting = 5, kOverflow = 6;
    const float dt = 0.1f;
    const LaneMask all = kAllBatchLanes;
    const std::uint32_t kills = kernels::SD_EMITTER_KILL_ON_COLLISION;
    const std::uint32_t recycle = kernels::SD_EMITTER_RECYCLE;
    for (std::uint32_t flags : {0u, kills, kills | recycle}) {
        SCOPED_TRACE(flags);
        kernels::EmitterParams e{};
        e.mass = 1.0f;
        e.flags = kernels::SD_EMITTER_COLLISIONS | flags;
        e.colliderMask = 1u;
        e.lifeLossOnCollision = 0.25f;
        e.integrator = kernels::SD_INTEGRATE_SEMI_IMPLICIT_EULER;
        ASSERT_TRUE(batchUpdateEligible(ctx, e));
        const bool strikeLeft = flags == kills;
        for (UpdateTarget target : supportedUpdateTargets()) {
            SCOPED_TRACE(std::string(updateTargetName(target)));
            ParticleArrays a;
            a.resize(kBatchLanes);
            for (std::size_t i = 0; i < kBatchLanes; ++i) {
                a.position[i] = glm::vec3(0.0f, 1.0f, 0.0f);
                a.velocity[i] = glm::vec3(0.0f);
                a.age[i] = 0.5f;
                a.lifetime[i] = 2.0f;
            }
            a.velocity[kStrike] = glm::vec3(0.0f, -100.0f, 0.0f);
            a.position[kResting] = glm::vec3(0.3f, 0.0005f, 0.0f);
            a.velocity[kResting] = glm::vec3(0.2f, -0.01f, 0.0f);
            a.velocity[kOverflow] = glm::vec3(2.0e19f, 0.0f, 0.0f);  // |v|^2 = 4e38 > FLT_MAX
            auto scalarUpdate = [&](std::size_t i) {
                kernels::Particle p{};
                p.position = a.position[i];
                p.velocity = a.velocity[i];
                p.age = a.age[i];
                p.lifetime = a.lifetime[i];
                p.mass = e.mass;
                p.alive = 1u;
                return kernels::updateParticle(ctx, e, p, dt);
            };
            const kernels::ParticleUpdate resting = scalarUpdate(kResting);
            const kernels::ParticleUpdate strike = scalarUpdate(kStrike);
            ASSERT_EQ(kernels::eventCountOf(resting), 0u);  // no impact, as the test needs
            ASSERT_NE(resting.particle.position, glm::vec3(0.32f, -0.0005f, 0.0f));  // pushed out
            ASSERT_EQ(strike.hitMask, 1u);                                            // an impact
            const LaneMask left = (LaneMask{1} << kOverflow) | (strikeLeft ? LaneMask{1} << kStrike : LaneMask{0});
            const glm::vec3 strikeStart = a.velocity[kStrike];
            const BatchResult r = updateBatch(target, ctx, e, batchConstants(ctx, e, dt), a, 0, dt);
            EXPECT_EQ(r.finished, target == UpdateTarget::Scalar ? LaneMask{0} : all & ~left);
            EXPECT_EQ(a.velocity[kOverflow].x, 2.0e19f);  // left for the scalar kernel
            if (target == UpdateTarget::Scalar || strikeLeft) {
                EXPECT_EQ(r.struck, 0u);
                EXPECT_EQ(a.position[kStrike], glm::vec3(0.0f, 1.0f, 0.0f));
                EXPECT_EQ(a.age[kStrike], 0.5f);
            } else {
                EXPECT_EQ(r.struck, LaneMask{1} << kStrike);
                EXPECT_EQ(r.hitMask[kStrike], 1u);
                EXPECT_EQ(r.startVelocity[kStrike], strikeStart);
                EXPECT_EQ(std::memcmp(&a.position[kStrike], &strike.particle.position, sizeof(glm::vec3)), 0);
                EXPECT_EQ(std::memcmp(&a.velocity[kStrike], &strike.particle.velocity, sizeof(glm::vec3)), 0);
                EXPECT_EQ(std::memcmp(&a.age[kStrike], &strike.particle.age, sizeof(float)), 0);
                // Independent of the kernel: a kill ends the life, else a
                // quarter of the 1.4 s left (age 0.6 of 2) is lost.
                EXPECT_FLOAT_EQ(a.age[kStrike], (flags & kills) != 0u ? 2.0f : 0.6f + 0.25f * 1.4f);
            }
            if (target != UpdateTarget::Scalar) {
                EXPECT_EQ(a.age[0], 0.5f + dt);
                EXPECT_EQ(std::memcmp(&a.position[kResting], &resting.particle.position, sizeof(glm::vec3)), 0);
                EXPECT_EQ(std::memcmp(&a.velocity[kResting], &resting.particle.velocity, sizeof(glm::vec3)), 0);
            }
        }
    }
}

std::vector<ParticleSnapshot> runScene(const std::string& path) {
    SceneDef scene = loadScene(path);
    scene.world.threads = 1;
    // Only the effect emitters run the update: fluids, the slow part of a
    // scene, are left out (the test stays within a few seconds).
    scene.fluids.clear();
    WorldId world = buildWorld(scene);
    for (int i = 0; i < 40; ++i) {
        stepWorld(world, scene.run.dt);
    }
    std::vector<ParticleSnapshot> out;
    for (std::uint32_t e = 1; e <= emitterCount(world); ++e) {
        out.push_back(readParticles(world, EmitterId{e}));
    }
    destroyWorld(world);
    return out;
}

TEST(VectorUpdate, EveryBundledSceneMatchesTheScalarKernelAtEveryTarget) {
    int scenes = 0;
    std::size_t particles = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(SPINDRIFT_SOURCE_DIR) + "/scenes")) {
        if (entry.path().extension() != ".toml") {
            continue;
        }
        SCOPED_TRACE(entry.path().string());
        std::vector<ParticleSnapshot> scalar;
        {
            ScopedTarget t(UpdateTarget::Scalar);
            scalar = runScene(entry.path().string());
        }
        for (const ParticleSnapshot& s : scalar) particles += s.count();
        for (UpdateTarget target : supportedUpdateTargets()) {
            if (target == UpdateTarget::Scalar) {
                continue;
            }
            SCOPED_TRACE(std::string(updateTargetName(target)));
            ScopedTarget t(target);
            expectSameParticles(scalar, runScene(entry.path().string()));
        }
        ++scenes;
    }
    EXPECT_GE(scenes, 6);
    EXPECT_GT(particles, 1000u);  // not vacuous: the scenes' emitters have live particles (6748 at 40 steps)
}

}  // namespace
}  // namespace spindrift
