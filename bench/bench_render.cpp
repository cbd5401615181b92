// Frame time of the renderer at 1080p (docs/performance.md, "Renderer").
//
//   build/release/bench_render --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true --benchmark_format=json
// (one command line).
//
// Sprites: one recycle emitter of N particles (a fountain under gravity with
// a ground plane, every slot alive after 1.5 s of warm-up), drawn additive,
// alpha-blended (then sorted back to front on the device every frame) or with
// weighted blended OIT (no sort; an accumulation pass and a composite).
// Argument 0: particles (1: the baseline frame with nothing to draw but the
// background and the floor); argument 1: world backend (0 cpu: one upload per
// frame, 1 vulkan: drawn from the world's buffers); argument 2: blend (0
// additive, 1 alpha sorted, 2 OIT).
// Trails: 10,000 of the same fountain's particles with 0 or 16 trail points
// (argument 0), CPU or Vulkan world (argument 1); step_ms is the world step.
// Fluid: a 2D block of 100k particles at 1 cm after one step (so neighbour
// data exists), every splat step on, refraction included.
// Fluid look at 960x540: the 2D dam break of scenes/fluid_dam_break_2d.toml
// (about 2,900 particles at 2 cm in a 3.2 m tank) after 2 s, as the liquid
// surface (argument 0: 0; argument 1: the field's resolution in percent of the
// frame's side) or as Sprinkle's seven splat steps (argument 0: 1).
// 3D fluid look at 960x540: the 3D dam break of scenes/fluid_dam_break_3d.toml
// (1,050 particles at 4 cm in a 1.2 x 0.4 m channel) after 1 s, seen as in
// the scene, as the screen-space liquid (argument 0: 0; argument 1: the
// field's resolution in percent of the frame's side) or as the seven splat
// steps (argument 0: 1).
// A device fluid's look at 960x540: the same dam break's tank with a column
// of 11,250 particles at 8 mm solved on the device (backend gpu), stepped
// between frames (the step not timed), drawn as the liquid surface
// (argument 1: 0) or as the seven splat steps (1), from the device's buffers
// (argument 0: 1) or from the particles read back (0, the CPU fluid's path);
// bytes_down_per_frame is what a frame reads back.
// Light at 960x540: 2,000 additive sprites of an HDR flame colour over a
// floor; argument 0: 0 no tone map and no bloom (the tone map's pass is a
// clamp), 1 the ACES curve without bloom, 2 ACES with bloom (the default).
// Each iteration is renderFrame: host preparation, the device's passes, and
// the read-back of the 8 MB frame. The world is not stepped in the loop. The
// counters are the last frame's device time per pass (timestamps). Without a
// GPU this runs on Mesa's lavapipe, on the same two cores as everything else.
#include "render/renderer.h"

#include <spindrift/fluid.h>
#include <spindrift/render.h>
#include <spindrift/world.h>

#include <cmath>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <exception>
#include <initializer_list>
#include <utility>

namespace {

using namespace spindrift;

RenderDef fullHd(bool orthographic) {
    RenderDef def;
    def.width = 1920;
    def.height = 1080;
    def.camera.eye = orthographic ? glm::vec3(0.0f, 0.0f, 5.0f) : glm::vec3(0.0f, 3.0f, 12.0f);
    def.camera.target = {0.0f, orthographic ? 0.0f : 2.0f, 0.0f};
    def.camera.orthographic = orthographic;
    def.camera.orthoHeight = 1.2f;
    return def;
}

void report(benchmark::State& state, RendererId r) {
    RenderStats s = renderStats(r);
    state.counters["device_ms"] = s.totalDeviceMs;
    state.counters["background_ms"] = s.backgroundMs;
    state.counters["colliders_ms"] = s.collidersMs;
    state.counters["copy_ms"] = s.refractionCopyMs;
    state.counters["splats_ms"] = s.fluidMs;  // the liquid surface's composite included
    state.counters["surface_field_ms"] = s.surfaceFieldMs;
    state.counters["sprites_ms"] = s.spritesMs;
    state.counters["sort_ms"] = s.sortMs;
    state.counters["oit_ms"] = s.oitAccumulateMs;
    state.counters["light_ms"] = s.lightMs;  // bloom and the tone map
    state.counters["host_ms"] = s.cpuMs;
    state.counters["sprites"] = static_cast<double>(s.sprites);
    state.counters["splats"] = static_cast<double>(s.splats);
}

// The measured loop: renderFrame of `world` drawn as `def`, then the last
// frame's per-pass times as counters.
void measureFrames(benchmark::State& state, WorldId world, const RenderDef& def) {
    RendererId r = createRenderer(world, def);
    renderFrame(r);  // warm-up: first-use costs
    for (auto _ : state) {
        Frame f = renderFrame(r);
        benchmark::DoNotOptimize(f.rgba.data());
    }
    report(state, r);
    destroyRenderer(r);
}

// The sprites' and trails' fountain: n recycle slots launched up a cone,
// every slot alive after 1.5 s.
EmitterDef fountain(std::uint32_t n) {
    EmitterDef e;
    e.lifecycle = Lifecycle::Recycle;
    e.capacity = n;
    e.shape.kind = SpawnShapeKind::Cone;
    e.shape.radius = 0.2f;
    e.shape.spreadAngle = 0.35f;
    e.speed = {6.0f, 8.0f};
    e.lifetime = {1.0f, 1.5f};
    e.size = {0.03f, 0.05f};
    e.color = {{1.0f, 0.6f, 0.2f, 0.5f}, {0.3f, 0.6f, 1.0f, 0.8f}};
    return e;
}

void BM_Sprites(benchmark::State& state) {
    try {
        const auto n = static_cast<std::uint32_t>(state.range(0));
        WorldDef wd;
        wd.backend = state.range(1) == 1 ? Backend::Vulkan : Backend::Cpu;
        wd.threads = 2;
        wd.framesInFlight = 1;
        WorldId w = createWorld(wd);
        ForceDef g;
        createForce(w, g);
        ColliderDef floor;
        createCollider(w, floor);
        EmitterDef e = fountain(n);
        const SpriteBlend blends[3] = {SpriteBlend::Additive, SpriteBlend::Alpha, SpriteBlend::WeightedOit};
        e.sprite.blend = blends[state.range(2)];
        createEmitter(w, e);
        for (int i = 0; i < 90; ++i) {
            stepWorld(w, 1.0f / 60.0f);
        }
        measureFrames(state, w, fullHd(false));
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
BENCHMARK(BM_Sprites)
    ->ArgNames({"particles", "vulkan", "blend"})
    ->Args({1, 0, 0})  // the frame without sprites: background, floor, read-back
    ->Args({100000, 0, 0})
    ->Args({100000, 1, 0})
    ->Args({100000, 0, 1})
    ->Args({100000, 0, 2})  // sorted "over" against OIT, side by side
    ->Args({100000, 1, 1})
    ->Args({100000, 1, 2})
    ->Args({1000000, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// Trails (EmitterDef::trail): 10,000 recycle particles of BM_Sprites' fountain
// with 0 or 16 trail points, CPU world or Vulkan (the ribbons read from the
// device buffers), additive. Counters: the frame's per-pass times as
// BM_Sprites, and step_ms, the mean world step before the frames (the
// update's trail writes included).
void BM_Trails(benchmark::State& state) {
    try {
        WorldDef wd;
        wd.backend = state.range(1) == 1 ? Backend::Vulkan : Backend::Cpu;
        wd.threads = 2;
        wd.framesInFlight = 1;
        WorldId w = createWorld(wd);
        createForce(w, ForceDef{});
        EmitterDef e = fountain(10000);
        e.trail.points = static_cast<std::uint32_t>(state.range(0));
        e.trail.width = 0.02f;
        createEmitter(w, e);
        const auto start = std::chrono::steady_clock::now();
        for (int i = 0; i < 90; ++i) {
            stepWorld(w, 1.0f / 60.0f);
        }
        flushWorld(w);
        state.counters["step_ms"] =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / 90.0;
        measureFrames(state, w, fullHd(false));
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
BENCHMARK(BM_Trails)
    ->ArgNames({"points", "vulkan"})
    ->Args({0, 0})
    ->Args({16, 0})
    ->Args({0, 1})
    ->Args({16, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

void BM_FluidSplats(benchmark::State& state) {
    try {
        WorldDef wd;
        wd.threads = 2;
        WorldId w = createWorld(wd);
        FluidDef fluid;
        fluid.spacing = 0.01f;
        // 100k particles: 5 m x 2 m at 1 cm.
        fluid.blocks = {FluidBlockDef{{-2.5f, -0.5f, 0.0f}, {2.5f, 1.5f, 0.0f}, glm::vec3(0.0f)}};
        createFluid(w, fluid);
        stepWorld(w, 1.0f / 60.0f);
        RenderDef def = fullHd(true);
        def.camera.orthoHeight = 2.4f;
        def.camera.target = {0.0f, 0.5f, 0.0f};
        def.camera.eye = {0.0f, 0.5f, 5.0f};
        def.fluid = FluidRenderDef::upTo(static_cast<int>(state.range(0)));
        measureFrames(state, w, def);
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
BENCHMARK(BM_FluidSplats)->ArgNames({"steps"})->Arg(1)->Arg(7)->Unit(benchmark::kMillisecond)->Iterations(5);

// Plane colliders through each point with each (inward) normal.
void addWalls(WorldId w, std::initializer_list<std::pair<glm::vec3, glm::vec3>> walls) {
    for (const auto& [point, normal] : walls) {
        ColliderDef wall;
        wall.kind = ColliderKind::Plane;
        wall.position = point;
        wall.normal = normal;
        createCollider(w, wall);
    }
}

void BM_FluidLook(benchmark::State& state) {
    try {
        WorldDef wd;
        wd.threads = 2;
        WorldId w = createWorld(wd);
        addWalls(w, {std::pair{glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)},
                     std::pair{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)},
                     std::pair{glm::vec3(3.2f, 0.0f, 0.0f), glm::vec3(-1.0f, 0.0f, 0.0f)}});
        FluidDef fluid;
        fluid.spacing = 0.02f;
        fluid.iterations = 4;
        fluid.blocks = {FluidBlockDef{{0.0f, 0.0f, 0.0f}, {0.6f, 1.2f, 0.0f}, glm::vec3(0.0f)}};
        createFluid(w, fluid);
        for (int i = 0; i < 120; ++i) stepWorld(w, 1.0f / 60.0f);
        RenderDef def;
        def.width = 960;
        def.height = 540;
        def.camera.eye = {1.6f, 0.8f, 4.0f};
        def.camera.target = {1.6f, 0.8f, 0.0f};
        def.camera.orthographic = true;
        def.camera.orthoHeight = 2.0f;
        if (state.range(0) == 1) {
            def.fluid = FluidRenderDef::upTo(7);
        } else {
            def.fluid.surfaceScale = static_cast<float>(state.range(1)) / 100.0f;
        }
        measureFrames(state, w, def);
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
BENCHMARK(BM_FluidLook)
    ->ArgNames({"splats", "field_percent"})
    ->Args({0, 50})
    ->Args({0, 25})
    ->Args({0, 100})
    ->Args({1, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

void BM_FluidLook3D(benchmark::State& state) {
    try {
        WorldDef wd;
        wd.threads = 2;
        WorldId w = createWorld(wd);
        addWalls(w, {std::pair{glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)},
                     std::pair{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)},
                     std::pair{glm::vec3(1.2f, 0.0f, 0.0f), glm::vec3(-1.0f, 0.0f, 0.0f)},
                     std::pair{glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f)},
                     std::pair{glm::vec3(0.0f, 0.0f, 0.4f), glm::vec3(0.0f, 0.0f, -1.0f)}});
        FluidDef fluid;
        fluid.dimension = 3;
        fluid.spacing = 0.04f;
        fluid.iterations = 4;
        fluid.blocks = {FluidBlockDef{{0.0f, 0.0f, 0.0f}, {0.3f, 0.6f, 0.4f}, glm::vec3(0.0f)}};
        createFluid(w, fluid);
        for (int i = 0; i < 60; ++i) stepWorld(w, 1.0f / 60.0f);
        RenderDef def;
        def.width = 960;
        def.height = 540;
        def.camera.eye = {1.0f, 0.7f, 1.5f};
        def.camera.target = {0.5f, 0.15f, 0.2f};
        if (state.range(0) == 1) {
            def.fluid = FluidRenderDef::upTo(7);
        } else {
            def.fluid.surfaceScale = static_cast<float>(state.range(1)) / 100.0f;
        }
        measureFrames(state, w, def);
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
BENCHMARK(BM_FluidLook3D)
    ->ArgNames({"splats", "field_percent"})
    ->Args({0, 50})
    ->Args({0, 25})
    ->Args({0, 100})
    ->Args({1, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

void BM_DeviceFluidLook(benchmark::State& state) {
    try {
        WorldDef wd;
        wd.backend = Backend::Vulkan;
        wd.threads = 2;
        WorldId w = createWorld(wd);
        addWalls(w, {std::pair{glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)},
                     std::pair{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)},
                     std::pair{glm::vec3(3.2f, 0.0f, 0.0f), glm::vec3(-1.0f, 0.0f, 0.0f)}});
        FluidDef fluid;
        fluid.spacing = 0.008f;
        fluid.backend = FluidBackend::Gpu;
        fluid.blocks = {FluidBlockDef{{0.0f, 0.0f, 0.0f}, {0.6f, 1.2f, 0.0f}, glm::vec3(0.0f)}};
        const FluidId f = createFluid(w, fluid);
        for (int i = 0; i < 10; ++i) stepWorld(w, 1.0f / 60.0f);
        RenderDef def;
        def.width = 960;
        def.height = 540;
        def.camera.eye = {1.6f, 0.8f, 4.0f};
        def.camera.target = {1.6f, 0.8f, 0.0f};
        def.camera.orthographic = true;
        def.camera.orthoHeight = 2.0f;
        if (state.range(1) == 1) def.fluid = FluidRenderDef::upTo(7);
        RendererId r = createRenderer(w, def);
        render::rendererOf(r).drawDeviceWater = state.range(0) == 1;
        renderFrame(r);  // warm-up: first-use costs
        std::uint64_t down = 0;
        for (auto _ : state) {
            state.PauseTiming();
            stepWorld(w, 1.0f / 60.0f);  // the particles move on the device between frames
            const TransferStats before = transferStats(w);
            state.ResumeTiming();
            Frame frame = renderFrame(r);
            benchmark::DoNotOptimize(frame.rgba.data());
            state.PauseTiming();
            down += transferStats(w).bytesDownloaded - before.bytesDownloaded;
            state.ResumeTiming();
        }
        report(state, r);
        state.counters["particles"] = static_cast<double>(readFluid(w, f).count());
        state.counters["bytes_down_per_frame"] = static_cast<double>(down) / static_cast<double>(state.iterations());
        destroyRenderer(r);
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
BENCHMARK(BM_DeviceFluidLook)
    ->ArgNames({"device_water", "splats"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

void BM_Light(benchmark::State& state) {
    try {
        WorldDef wd;
        wd.threads = 2;
        WorldId w = createWorld(wd);
        ColliderDef floor;
        createCollider(w, floor);
        EmitterDef e;
        e.lifecycle = Lifecycle::Recycle;
        e.capacity = 2000;
        e.shape.kind = SpawnShapeKind::Disk;
        e.shape.radius = 0.5f;
        e.speed = {0.2f, 0.6f};
        e.lifetime = {1.0f, 1.5f};
        e.size = {0.3f, 0.5f};
        e.color = {{4.0f, 1.2f, 0.3f, 0.5f}, {2.0f, 0.6f, 0.15f, 0.5f}};
        e.sprite.blend = SpriteBlend::Additive;
        createEmitter(w, e);
        for (int i = 0; i < 90; ++i) {
            stepWorld(w, 1.0f / 60.0f);
        }
        RenderDef def;
        def.width = 960;
        def.height = 540;
        def.camera.eye = {0.0f, 1.5f, 5.0f};
        def.camera.target = {0.0f, 0.8f, 0.0f};
        def.toneMap = state.range(0) == 0 ? ToneMap::None : ToneMap::Aces;
        def.bloom = state.range(0) >= 2 ? RenderDef{}.bloom : 0.0f;
        if (state.range(0) == 3) {
            // The most point lights a frame carries, all reaching the floor
            // under the sprites: what they add is in colliders_ms.
            for (std::uint32_t i = 0; i < kRenderMaxLights; ++i) {
                LightDef light;
                const float angle = 0.785f * static_cast<float>(i);
                light.position = {1.5f * std::cos(angle), 0.3f, 1.5f * std::sin(angle)};
                light.radius = 4.0f;
                def.lights.push_back(light);
            }
        }
        measureFrames(state, w, def);
        destroyWorld(w);
    } catch (const std::exception& e) {
        state.SkipWithError(e.what());
    }
}
// light: 0 a clamp, 1 ACES, 2 ACES and bloom (the default), 3 the default
// with 8 point lights.
BENCHMARK(BM_Light)
    ->ArgNames({"light"})
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);

}  // namespace

BENCHMARK_MAIN();
