// The effect update on the Vulkan backend next to the CPU backend, in the same
// binary, on the same world (docs/performance.md, "Vulkan backend").
//
//   build/release/bench_gpu --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true --benchmark_format=json
// (one command line).
//
// World: one recycle-mode emitter (the GPU particle talk's fixed slots) with
// lifetimes of 0.5 to 1 s, warmed up for 1 s so that every slot is alive and
// slots are re-born every step; gravity, wind, damping, an attractor and a
// repeller, a ground plane, colour and size over-life curves: the standard
// stack of bench_effects in recycle mode. Argument 0: particles; argument 1:
// backend (0 = cpu with 2 threads, 1 = vulkan); argument 2: the Vulkan
// world's frames in flight (1: every step waits for the device; 2: the host
// records step n + 1 while the device runs step n); argument 3: on the CPU, 1
// runs the old scalar update for every slot (UpdateTarget::Scalar, the
// baseline of the vector update, src/effects/batch_update.h), 0 the best
// vector target of this CPU. On a machine without a GPU the
// Vulkan backend runs on Mesa's lavapipe, a CPU implementation, so the numbers
// here measure the path, not a GPU; 1M particles on lavapipe take about a
// second per step, too long to repeat here, so the Vulkan case is 100k only.
// BM_SubEmit, BM_FluidDeviceSubstep, BM_FluidDeviceStep: see their comments.
#include "core/parallel.h"
#include "effects/batch_update.h"
#include "fluid/fluid_state.h"
#include "gpu/gpu_fluid_contacts.h"
#include "gpu/gpu_fluid_grid.h"
#include "gpu/gpu_fluid_integrate.h"
#include "gpu/gpu_fluid_setup.h"
#include "gpu/gpu_fluid_solve.h"
#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_device.h"
#include "particles/params.h"

#include <spindrift/bodies.h>
#include <spindrift/world.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <random>
#include <utility>
#include <string>

namespace {

constexpr float kDt = 1.0f / 60.0f;

spindrift::WorldId makeWorld(std::uint32_t particles, spindrift::Backend backend, std::uint32_t frames) {
    using namespace spindrift;
    WorldDef def;
    def.backend = backend;
    def.threads = 2;
    def.framesInFlight = frames;
    WorldId w = createWorld(def);
    ForceDef f;
    f.kind = ForceKind::Gravity;
    createForce(w, f);
    f = ForceDef{};
    f.kind = ForceKind::Wind;
    f.vector = {2.0f, 0.0f, 0.0f};
    f.strength = 0.05f;
    createForce(w, f);
    f = ForceDef{};
    f.kind = ForceKind::Damping;
    f.strength = 0.2f;
    createForce(w, f);
    f = ForceDef{};
    f.kind = ForceKind::Attractor;
    f.position = {2.0f, 2.0f, 0.0f};
    f.strength = 5.0f;
    createForce(w, f);
    f.position = {-2.0f, 1.0f, 0.0f};
    f.strength = -3.0f;
    f.falloff = 1.0f;
    createForce(w, f);
    ColliderDef floor;
    floor.kind = ColliderKind::Plane;
    floor.resilience = 0.4f;
    floor.friction = 0.2f;
    createCollider(w, floor);
    EmitterDef e;
    e.lifecycle = Lifecycle::Recycle;
    e.capacity = particles;
    e.lifetime = {0.5f, 1.0f};
    e.shape.kind = SpawnShapeKind::Sphere;
    e.shape.center = {0.0f, 1.0f, 0.0f};
    e.shape.radius = 0.5f;
    e.shape.spreadAngle = 0.8f;
    e.speed = {2.0f, 6.0f};
    e.colorOverLife.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(1.0f, 0.5f, 0.2f, 0.0f)}};
    e.sizeOverLife.keys = {{0.0f, glm::vec4(0.5f)}, {1.0f, glm::vec4(2.0f)}};
    createEmitter(w, e);
    for (int i = 0; i < 60; ++i) {
        stepWorld(w, kDt);
    }
    return w;
}

void BM_RecycleStack(benchmark::State& state) {
    const auto particles = static_cast<std::uint32_t>(state.range(0));
    const auto backend = state.range(1) == 0 ? spindrift::Backend::Cpu : spindrift::Backend::Vulkan;
    spindrift::WorldId w;
    const spindrift::UpdateTarget saved = spindrift::updateTarget();
    spindrift::setUpdateTarget(state.range(3) != 0 ? spindrift::UpdateTarget::Scalar
                                                   : spindrift::bestUpdateTarget());
    state.SetLabel(std::string(spindrift::updateTargetName(spindrift::updateTarget())));
    try {
        w = makeWorld(particles, backend, static_cast<std::uint32_t>(state.range(2)));
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return;
    }
    double deviceMs = 0.0;
    std::uint64_t counted = 0;
    for (auto _ : state) {
        spindrift::StepStats s = spindrift::stepWorld(w, kDt);
        deviceMs += s.deviceMilliseconds;
        counted += s.countedSteps;
        if (s.countedSteps > 0 && s.alive != particles) {
            state.SkipWithError("not every slot is alive");
            break;
        }
    }
    spindrift::flushWorld(w);  // drains the step still in flight (untimed: one of many)
    state.SetItemsProcessed(state.iterations() * particles);
    // Device time per step from the Vulkan world's timestamps (0 on the CPU).
    state.counters["device_ms_per_step"] = counted > 0 ? deviceMs / static_cast<double>(counted) : 0.0;
    state.counters["particle_steps_per_second"] =
        benchmark::Counter(static_cast<double>(particles), benchmark::Counter::kIsIterationInvariantRate);
    spindrift::destroyWorld(w);
    spindrift::setUpdateTarget(saved);
}

// Sub-emitters: a recycle emitter of 100k particles living 0.5 to 1 s (about
// 2,200 deaths a step) with, argument 1: 0 nothing more; 1 a sub-emitter
// making 4 particles at each death (about 8,900 births a step, born and
// updated for 0.2 s: about 100k alive); 2 the same emitter fed by a rate of
// the same mean births instead (the births' cost without the events').
// Argument 0: backend as above. Counters: child births per step.
void BM_SubEmit(benchmark::State& state) {
    using namespace spindrift;
    const auto backend = state.range(0) == 0 ? Backend::Cpu : Backend::Vulkan;
    constexpr std::uint32_t kParents = 100'000;
    WorldId w;
    EmitterId child{0};
    try {
        w = makeWorld(kParents, backend, 1);
        if (state.range(1) != 0) {
            EmitterDef c;
            c.name = "children";
            c.capacity = 200'000;
            c.rate = state.range(1) == 2 ? 4.0f * kParents / 0.75f : 0.0f;  // mean deaths/s x 4
            c.shape.kind = SpawnShapeKind::Sphere;
            c.shape.radius = 0.02f;
            c.shape.spreadAngle = 3.14f;
            c.speed = {0.5f, 1.0f};
            c.lifetime = {0.2f, 0.2f};
            c.size = {0.01f, 0.02f};
            if (state.range(1) == 1) {
                c.spawnOn = {EmitterId{1}, SpawnEvent::Death, 4, 0.5f};
            }
            child = createEmitter(w, c);
            for (int i = 0; i < 30; ++i) {
                stepWorld(w, kDt);
            }
        }
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
        return;
    }
    std::uint64_t born = 0;
    for (auto _ : state) {
        born += stepWorld(w, kDt).born;
    }
    flushWorld(w);
    state.counters["births_per_step"] =
        benchmark::Counter(static_cast<double>(born), benchmark::Counter::kAvgIterations);
    state.counters["child_alive"] = child.index != 0 ? static_cast<double>(readParticles(w, child).count()) : 0.0;
    destroyWorld(w);
}

/// The constraint fluid's substep on the device (issue 16; grid, gather with
/// gravity, the contacts with a floor and two walls, the constraints, the
/// solve's warm start and 4 Gauss-Seidel iterations colour by colour with
/// the contacts after each, the integration with sleeping and path tests):
/// one substep of a block of water at rest on the lattice with velocities of
/// up to 0.5 m/s at random, the CPU's FluidState placing the grid, every
/// substep recorded and waited for (each from the same state). Argument 0:
/// particles; 1: dimension. Counters: list entries per particle. The whole
/// step through the world: BM_FluidDeviceStep. On lavapipe the time measures
/// the path only.
void BM_FluidDeviceSubstep(benchmark::State& state) {
    using namespace spindrift;
    const auto n = static_cast<std::uint32_t>(state.range(0));
    const int dimension = static_cast<int>(state.range(1));
    try {
        fluid::FluidState f;
        f.def.dimension = static_cast<std::uint32_t>(dimension);
        f.def.spacing = dimension == 2 ? 0.01f : 0.02f;
        f.def.capacity = 2 * n;
        fluid::initialiseFluid(f);
        // A square (cube) block of about n particles.
        const float side = f.def.spacing * std::pow(static_cast<float>(n), 1.0f / static_cast<float>(dimension));
        fluid::addBlock(f, {glm::vec3(0.0f), glm::vec3(side, side, dimension == 3 ? side : 0.0f), glm::vec3(0.0f)});
        const std::size_t count = f.size();
        std::vector<float> x(count * dimension), v(count * dimension), p(count, 0.0f);
        std::vector<glm::vec4> wall(count, glm::vec4(0.0f));
        std::mt19937 rng(3u);
        std::uniform_real_distribution<float> speed(-0.5f, 0.5f);
        if (dimension == 2) {
            std::memcpy(x.data(), f.p2.position.data(), x.size() * 4);
        } else {
            std::memcpy(x.data(), f.p3.position.data(), x.size() * 4);
        }
        for (float& c : v) c = speed(rng);
        WorkerPool pool(1);
        gpu::FluidGridParams grid;
        grid.dimension = static_cast<std::uint32_t>(dimension);
        if (dimension == 2) {
            fluid::placeGrid<2>(pool, f.p2.position, f.h, f.g2);
            grid.origin = glm::vec3(f.g2.origin, 0.0f);
            grid.cells = glm::ivec3(f.g2.cells[0], f.g2.cells[1], f.g2.cells[2]);
        } else {
            fluid::placeGrid<3>(pool, f.p3.position, f.h, f.g3);
            grid.origin = f.g3.origin;
            grid.cells = glm::ivec3(f.g3.cells[0], f.g3.cells[1], f.g3.cells[2]);
        }
        grid.invH = 1.0f / f.h;
        const float dt = 1.0f / 60.0f / 4.0f;  // a substep of four
        gpu::FluidSetupParams setup{f.subCellReadLimit, f.maxNeighbours, f.h, f.restDensity, f.def.baumgarte, dt,
                                    f.def.warmStart};
        setup.velocityChange = glm::vec3(f.def.gravity) * dt;
        const gpu::FluidIntegrateParams integrate{f.def.gravity, dt, f.def.sleepSpeed, f.def.sleepTime, f.def.spacing,
                                                  f.def.splitImpulse};
        gpu::FluidSolveParams solve{f.def.iterations, f.def.splitImpulse, f.def.warmStart, f.restDensity,
                                    f.def.baumgarte, f.h, dt};

        std::unique_ptr<gpu::Device> d = gpu::createDevice({});
        {
            auto gridPasses = gpu::createGpuFluidGrid(*d);
            auto setupPasses = gpu::createGpuFluidSetup(*d);
            auto solvePasses = gpu::createGpuFluidSolve(*d);
            auto contactPasses = gpu::createGpuFluidContacts(*d);
            auto integratePasses = gpu::createGpuFluidIntegrate(*d);
            // A floor under the block and a wall on each side of it.
            std::vector<kernels::ColliderParams> walls3;
            for (const auto& [point, normal] : {std::pair{glm::vec3(0.0f), glm::vec3(0, 1, 0)},
                                                std::pair{glm::vec3(0.0f), glm::vec3(1, 0, 0)},
                                                std::pair{glm::vec3(side), glm::vec3(-1, 0, 0)}}) {
                ColliderDef c;
                c.position = point - normal * (0.5f * f.def.spacing);  // half a spacing from the lattice
                c.normal = normal;
                walls3.push_back(makeColliderParams(c, 0));
            }
            std::vector<glm::vec2> table(fluid::WallTable::kSize);
            for (int e = 0; e < fluid::WallTable::kSize; ++e) {
                table[e] = glm::vec2(f.wallTable.density[e], f.wallTable.push[e]);
            }
            gpu::setFluidSurfaces(*contactPasses, {walls3, {}, table, f.wallTable.start, f.wallTable.step});
            const gpu::FluidContactParams contactParams{f.radius, f.def.spacing, dt, f.def.friction,
                                                        f.def.splitImpulse};
            gpu::Buffer xs = gpu::createStorageBuffer(*d, x.size() * 4);
            gpu::Buffer vs = gpu::createStorageBuffer(*d, v.size() * 4);
            gpu::Buffer ps = gpu::createStorageBuffer(*d, p.size() * 4);
            gpu::Buffer walls = gpu::createStorageBuffer(*d, wall.size() * 16);
            gpu::Buffer anchors = gpu::createStorageBuffer(*d, x.size() * 4);  // each particle's own position
            gpu::Buffer stills = gpu::createStorageBuffer(*d, p.size() * 4);   // 0 s still
            const std::vector<gpu::Transfer> up{{&xs, x.data(), x.size() * 4},
                                                {&vs, v.data(), v.size() * 4},
                                                {&ps, p.data(), p.size() * 4},
                                                {&walls, wall.data(), wall.size() * 16},
                                                {&anchors, x.data(), x.size() * 4},
                                                {&stills, p.data(), p.size() * 4}};
            gpu::upload(*d, up);
            const auto substep = [&] {
                gpu::submitOnce(*d, [&](VkCommandBuffer cmd) {
                    gpu::recordFluidGrid(cmd, *gridPasses, xs, static_cast<std::uint32_t>(count), grid);
                    gpu::recordFluidGather(cmd, *setupPasses, *gridPasses,
                                           {&xs, &vs, &ps, &walls, static_cast<std::uint32_t>(count)}, setup);
                    gpu::recordFluidContactsFind(cmd, *contactPasses, *setupPasses, walls, contactParams);
                    gpu::recordFluidConstraints(cmd, *setupPasses, *gridPasses, setup);
                    gpu::recordFluidSolve(cmd, *solvePasses, *gridPasses, *setupPasses, walls, solve,
                                          contactPasses.get());
                    gpu::recordFluidIntegrate(cmd, *integratePasses, *gridPasses, *setupPasses, *solvePasses,
                                              *contactPasses, {&anchors, &stills}, integrate);
                });
            };
            substep();  // the first allocates
            const gpu::FluidSetupReadback r = gpu::readFluidSetup(*setupPasses);
            for (auto _ : state) {
                substep();
            }
            state.counters["particles"] = static_cast<double>(count);
            state.counters["entries_per_particle"] = static_cast<double>(r.entries) / static_cast<double>(count);
            for (gpu::Buffer* b : {&xs, &vs, &ps, &walls, &anchors, &stills}) gpu::destroyBuffer(*d, *b);
        }
        gpu::destroyDevice(*d);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}

/// The constraint fluid's whole step on the device through the public API
/// (issue 16): a Vulkan world, a fluid with backend gpu, a block of water
/// (argument 0: particles; 1: dimension) on the floor of a closed box twice
/// its width, released at rest; each step the automatic substeps (the CPU's
/// rule on the statistics read back), every substep's passes and its
/// read-back of a few hundred bytes; no particle comes back (nothing on the
/// host reads them here). Argument 2 (2D): 1 makes the box's floor and
/// side walls one static Box2D body of three boxes instead of planes (the
/// usual Box2D level), which the device meets from shapes the host uploads
/// each substep. One warm-up step, untimed. Counters: substeps a step,
/// particles, body contacts a step. On lavapipe the time measures the path
/// only.
void BM_FluidDeviceStep(benchmark::State& state) {
    using namespace spindrift;
    const auto n = static_cast<std::uint32_t>(state.range(0));
    const auto dimension = static_cast<std::uint32_t>(state.range(1));
    const bool bodyWalls = state.range(2) != 0;
    try {
        WorldDef wd;
        wd.backend = Backend::Vulkan;
        const WorldId w = createWorld(wd);
        FluidDef def;
        def.name = "water";
        def.dimension = dimension;
        def.spacing = dimension == 2 ? 0.01f : 0.02f;
        def.backend = FluidBackend::Gpu;
        const float side = def.spacing * std::pow(static_cast<float>(n), 1.0f / static_cast<float>(dimension));
        const glm::vec3 box(2.0f * side, 2.0f * side, dimension == 3 ? side : 0.0f);
        def.blocks.push_back({glm::vec3(0.0f), glm::vec3(side, side, dimension == 3 ? side : 0.0f), glm::vec3(0.0f)});
        if (bodyWalls) {
            BodyDef tank;
            tank.type = BodyType::Static;
            const float width = box.x, height = box.y;
            tank.shapes = {boxShape(glm::vec2(0.5f * width + 0.1f, 0.05f), glm::vec2(0.5f * width, -0.05f)),
                           boxShape(glm::vec2(0.05f, 0.5f * height + 0.1f), glm::vec2(-0.05f, 0.5f * height)),
                           boxShape(glm::vec2(0.05f, 0.5f * height + 0.1f), glm::vec2(width + 0.05f, 0.5f * height))};
            createBody(w, tank);
        }
        for (int a = 0; a < static_cast<int>(dimension) && !bodyWalls; ++a) {
            for (const float sign : {1.0f, -1.0f}) {
                ColliderDef c;
                c.kind = ColliderKind::Plane;
                c.normal = glm::vec3(0.0f);
                c.normal[a] = sign;
                c.position = sign > 0.0f ? glm::vec3(0.0f) : box;
                createCollider(w, c);
            }
        }
        const FluidId f = createFluid(w, def);
        stepWorld(w, kDt);  // the first allocates
        double substeps = 0.0, contacts = 0.0;
        for (auto _ : state) {
            const FluidStepStats s = stepWorld(w, kDt).fluids.at(0);
            substeps += s.substeps;
            contacts += static_cast<double>(s.bodyContacts);
        }
        state.counters["substeps"] = substeps / static_cast<double>(state.iterations());
        state.counters["body_contacts"] = contacts / static_cast<double>(state.iterations());
        state.counters["particles"] = static_cast<double>(readFluid(w, f).count());
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}

/// The device fluid substep's cases: 2D and 3D at 100k particles, 3
/// iterations (each is seconds on lavapipe).
void fluidDeviceCases(benchmark::internal::Benchmark* b) {
    b->ArgNames({"particles", "dimension"})
        ->Args({100'000, 2})
        ->Args({100'000, 3})
        ->Iterations(3)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

}  // namespace

BENCHMARK(BM_FluidDeviceStep)
    ->ArgNames({"particles", "dimension", "body_walls"})
    ->Args({100'000, 2, 0})
    ->Args({100'000, 3, 0})
    ->Args({100'000, 2, 1})
    ->Iterations(3)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FluidDeviceSubstep)->Apply(fluidDeviceCases);

BENCHMARK(BM_SubEmit)
    ->ArgNames({"vulkan", "child"})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({0, 2})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({1, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BM_RecycleStack)
    ->ArgNames({"particles", "vulkan", "frames", "scalar"})
    ->Args({100'000, 0, 1, 1})
    ->Args({100'000, 0, 1, 0})
    ->Args({100'000, 1, 1, 0})
    ->Args({100'000, 1, 2, 0})
    ->Args({1'000'000, 0, 1, 1})
    ->Args({1'000'000, 0, 1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
