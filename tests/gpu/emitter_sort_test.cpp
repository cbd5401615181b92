// sortEmitterBackToFront on both backends: on vulkan, exactly the CPU sort of
// the device's own positions, moving only the order back; against the CPU
// backend, the same order up to particles closer in depth than the backends'
// difference in position.
#include "effects/sort.h"
#include "gpu_test_util.h"

#include <cstdio>
#include <limits>
#include <map>

namespace spindrift {
namespace {

using test::BackendWorld;
using test::GpuTest;

class EmitterSortTest : public GpuTest {};

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

EmitterDef fountain(const char* name, Lifecycle lifecycle, std::uint32_t capacity) {
    EmitterDef e;
    e.name = name;
    e.lifecycle = lifecycle;
    e.capacity = capacity;
    e.rate = 300.0f;
    e.shape.kind = SpawnShapeKind::Cone;
    e.shape.center = {0.0f, 0.5f, 0.0f};
    e.shape.radius = 0.3f;
    e.shape.direction = {0.0f, 1.0f, 0.0f};
    e.shape.spreadAngle = 0.6f;
    e.speed = {2.0f, 5.0f};
    e.lifetime = {0.4f, 1.0f};
    return e;
}

struct EmitterRun {
    std::vector<ParticleSnapshot> snapshots;
    std::vector<std::vector<std::uint32_t>> orders;
    TransferStats beforeSort, afterSort;
};

const glm::vec3 kEye(3.0f, 2.0f, -4.0f);
const glm::vec3 kForward(-0.5f, -0.2f, 1.0f);

// A recycle emitter (slots still unborn after 20 steps) and a spawn emitter,
// under gravity over a plane; stepped, then sorted.
EmitterRun runEmitters(Backend backend) {
    BackendWorld w(backend);
    ForceDef gravity;
    gravity.kind = ForceKind::Gravity;
    createForce(w.id, gravity);
    ColliderDef ground;
    ground.kind = ColliderKind::Plane;
    ground.resilience = 0.4f;
    createCollider(w.id, ground);
    std::vector<EmitterId> ids{createEmitter(w.id, fountain("recycle", Lifecycle::Recycle, 700)),
                               createEmitter(w.id, fountain("spawn", Lifecycle::Spawn, 500))};
    for (int i = 0; i < 20; ++i) {
        stepWorld(w.id, 1.0f / 60.0f);
    }
    EmitterRun r;
    r.beforeSort = transferStats(w.id);
    for (EmitterId id : ids) {
        r.orders.push_back(sortEmitterBackToFront(w.id, id, kEye, kForward));
    }
    r.afterSort = transferStats(w.id);
    for (EmitterId id : ids) {
        r.snapshots.push_back(readParticles(w.id, id));
    }
    return r;
}

// The vulkan run, shared by the two tests below (a world's first steps compile
// its update pipelines, which takes seconds on lavapipe).
const EmitterRun& vulkanRun() {
    static const EmitterRun run = runEmitters(Backend::Vulkan);
    return run;
}

// The CPU's sortBackToFront of a snapshot's positions, as slots.
std::vector<std::uint32_t> cpuSlotOrder(const ParticleSnapshot& s) {
    std::vector<std::uint32_t> order = sortBackToFront(s.position, kEye, kForward);
    for (std::uint32_t& i : order) {
        i = s.slot[i];
    }
    return order;
}

// On the device, the order is exactly the CPU sort of the device's own
// positions, and sorting moves only the order back (4 B count + 4 B a slot).
TEST_F(EmitterSortTest, VulkanEmitterOrderIsTheCpuSortOfItsPositions) {
    const EmitterRun& gpu = vulkanRun();
    std::uint64_t live = 0;
    for (std::size_t e = 0; e < gpu.snapshots.size(); ++e) {
        const ParticleSnapshot& s = gpu.snapshots[e];
        ASSERT_GT(s.count(), 0u) << "emitter " << e;
        EXPECT_EQ(gpu.orders[e], cpuSlotOrder(s)) << "emitter " << e;
        live += s.count();
    }
    EXPECT_LT(gpu.snapshots[0].count(), 700u);  // unborn recycle slots are left out
    EXPECT_EQ(gpu.afterSort.bytesUploaded, gpu.beforeSort.bytesUploaded);
    EXPECT_EQ(gpu.afterSort.bytesDownloaded - gpu.beforeSort.bytesDownloaded, 4u * live + 4u * 2u);
}

// Against the CPU backend: the particles are the same (matched by birth
// serial) but their positions differ by up to ~1e-5 m (see
// tests/gpu/gpu_world_test.cpp), so two particles closer in depth than that
// may swap. Everywhere else the orders agree: walking the vulkan order, the
// CPU backend's depths never increase by more than 1e-4 m.
TEST_F(EmitterSortTest, VulkanEmitterOrderMatchesTheCpuBackend) {
    EmitterRun cpu = runEmitters(Backend::Cpu);
    const EmitterRun& gpu = vulkanRun();
    EXPECT_EQ(cpu.afterSort.bytesDownloaded, 0u);
    const glm::vec3 f = normalizeViewDirection(kForward);
    for (std::size_t e = 0; e < cpu.snapshots.size(); ++e) {
        const ParticleSnapshot& a = cpu.snapshots[e];
        const ParticleSnapshot& b = gpu.snapshots[e];
        ASSERT_EQ(a.count(), b.count()) << "emitter " << e;
        ASSERT_EQ(cpu.orders[e].size(), a.count());
        ASSERT_EQ(gpu.orders[e].size(), b.count());
        EXPECT_EQ(cpu.orders[e], cpuSlotOrder(a)) << "emitter " << e;
        std::map<std::uint32_t, float> cpuDepthBySerial;
        std::map<std::uint32_t, std::uint32_t> serialOfGpuSlot, serialOfCpuSlot;
        for (std::size_t i = 0; i < a.count(); ++i) {
            cpuDepthBySerial[a.birth[i]] = glm::dot(a.position[i] - kEye, f);
            serialOfCpuSlot[a.slot[i]] = a.birth[i];
            serialOfGpuSlot[b.slot[i]] = b.birth[i];
        }
        std::size_t same = 0;
        float previous = kInf;
        for (std::size_t k = 0; k < gpu.orders[e].size(); ++k) {
            std::uint32_t serial = serialOfGpuSlot.at(gpu.orders[e][k]);
            float depth = cpuDepthBySerial.at(serial);
            EXPECT_LE(depth, previous + 1e-4f) << "emitter " << e << " rank " << k;
            previous = depth;
            same += serial == serialOfCpuSlot.at(cpu.orders[e][k]) ? 1u : 0u;
        }
        std::printf("emitter %zu: %zu of %zu ranks hold the same particle on both backends\n", e, same,
                    a.count());
        EXPECT_GE(same * 10, a.count() * 9) << "emitter " << e;
    }
}

// No Vulkan needed: the CPU backend sorts stateless emitters from their
// closed form, as readParticles lists them.
TEST(EmitterSortCpu, CpuBackendSortsStatelessEmittersByTheirSnapshot) {
    test::ScopedWorld w(1, 7, Backend::Cpu);
    EmitterDef def = fountain("sparks", Lifecycle::Spawn, 400);
    def.stateless = true;
    EmitterId id = createEmitter(w.id, def);
    for (int i = 0; i < 30; ++i) {
        stepWorld(w.id, 1.0f / 60.0f);
    }
    ParticleSnapshot s = readParticles(w.id, id);
    ASSERT_GT(s.count(), 0u);
    EXPECT_EQ(sortEmitterBackToFront(w.id, id, kEye, kForward), cpuSlotOrder(s));
    EXPECT_THROW(sortEmitterBackToFront(w.id, id, kEye, glm::vec3(0.0f)), Error);
    EXPECT_THROW(sortEmitterBackToFront(w.id, id, glm::vec3(kNaN), kForward), Error);
}

}  // namespace
}  // namespace spindrift
