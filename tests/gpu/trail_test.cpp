// Trails (EmitterDef::trail) on both backends: what readParticles returns as
// a particle's trail is, point for point, the positions the same backend
// returned for that particle over the last steps (its birth position before
// it was born), including slots reused by new particles; and the renderer
// draws the ribbon over exactly that stretch of path.
#include "gpu_test_util.h"
#include "render/render_test_util.h"

#include <spindrift/render.h>
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

namespace spindrift {
namespace {

using test::GpuTest;

class Trails : public GpuTest {};

constexpr float kDt = 1.0f / 60.0f;

// Short-lived particles under gravity from a sphere: slots die and are
// reused (spawn) or re-born in place (recycle) within the run.
EmitterDef churningEmitter(Lifecycle lifecycle) {
    EmitterDef def;
    def.name = "churn";
    def.lifecycle = lifecycle;
    def.capacity = 48;
    def.rate = 300.0f;
    def.shape.kind = SpawnShapeKind::Sphere;
    def.shape.radius = 0.2f;
    def.shape.direction = {0.0f, 1.0f, 0.0f};
    def.shape.spreadAngle = 1.0f;
    def.speed = {1.0f, 3.0f};
    def.lifetime = {0.08f, 0.25f};
    def.trail.points = 7;
    return def;
}

// Exact equality: a trail point is a copy of a stored position, made by the
// same backend in the same step.
TEST_F(Trails, HoldEachParticlesLastPositionsOnBothBackends) {
    for (Backend backend : {Backend::Cpu, Backend::Vulkan}) {
        for (Lifecycle lifecycle : {Lifecycle::Spawn, Lifecycle::Recycle}) {
            SCOPED_TRACE(::testing::Message() << (backend == Backend::Cpu ? "cpu" : "vulkan") << " "
                                              << (lifecycle == Lifecycle::Spawn ? "spawn" : "recycle"));
            test::BackendWorld w(backend);
            ForceDef gravity;
            gravity.kind = ForceKind::Gravity;
            gravity.vector = {0.0f, -9.81f, 0.0f};
            createForce(w.id, gravity);
            const EmitterId id = createEmitter(w.id, churningEmitter(lifecycle));
            const std::uint32_t points = 7;
            // Positions by birth serial, one per step the particle was alive.
            std::map<std::uint32_t, std::vector<glm::vec3>> paths;
            std::size_t checked = 0, young = 0, reused = 0;
            std::map<std::uint32_t, std::uint32_t> serialOfSlot;
            for (int step = 0; step < 40; ++step) {
                stepWorld(w.id, kDt);
                const ParticleSnapshot s = readParticles(w.id, id);
                ASSERT_EQ(s.trailPoints, points);
                ASSERT_EQ(s.trail.size(), s.count() * points);
                for (std::size_t i = 0; i < s.count(); ++i) {
                    std::vector<glm::vec3>& path = paths[s.birth[i]];
                    path.push_back(s.position[i]);
                    auto [it, fresh] = serialOfSlot.try_emplace(s.slot[i], s.birth[i]);
                    if (!fresh && it->second != s.birth[i]) {
                        ++reused;
                        it->second = s.birth[i];
                    }
                    for (std::uint32_t k = 0; k < points; ++k) {
                        const std::size_t back = std::min<std::size_t>(k, path.size() - 1);
                        const glm::vec3 expected = path[path.size() - 1 - back];
                        const glm::vec3 got = s.trail[i * points + k];
                        ASSERT_EQ(got, expected) << "serial " << s.birth[i] << " point " << k << " step " << step;
                    }
                    young += path.size() < points ? 1 : 0;
                    ++checked;
                }
            }
            // The run covered particles younger than their trail and slots
            // that changed particle (a stale ring would fail above).
            EXPECT_GT(checked, 500u);
            EXPECT_GT(young, 100u);
            EXPECT_GT(reused, 20u);
        }
    }
}

// One particle along +x at 1.2 m/s (0.02 m a step) from x = -0.5 m, 11
// points: after 20 steps it is at x = -0.1 m and its ribbon spans the last 10
// steps, x = -0.3 to -0.1 m, 0.1 m wide about y = 0. orthoView(64, 64, 2) has
// 32 px a metre, x = -1 m at the left edge: the ribbon covers pixel columns
// 22.4 to 28.8 and rows 30.4 to 33.6. Its size 0 draws no quad, so every lit
// pixel is the ribbon's. The colour falls from 1 at the head to 0.2 at the
// tail (color_over_length), so the head's end is brighter.
TEST_F(Trails, RibbonCoversTheLastStepsOfThePathOnBothBackends) {
    for (Backend backend : {Backend::Cpu, Backend::Vulkan}) {
        SCOPED_TRACE(backend == Backend::Cpu ? "cpu" : "vulkan");
        test::BackendWorld w(backend);
        test::OneShot o;
        o.start = {-0.5f, 0.0f, 0.0f};
        o.velocity = {1.2f, 0.0f, 0.0f};
        o.size = 0.0f;
        EmitterDef def = test::oneShotEmitter(o);
        def.trail.points = 11;
        def.trail.width = 0.1f;
        def.trail.colorOverLength.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(0.2f, 0.2f, 0.2f, 1.0f)}};
        createEmitter(w.id, def);
        for (int step = 0; step < 20; ++step) {
            stepWorld(w.id, kDt);
        }
        test::ScopedRenderer r(w.id, test::orthoView(64, 64, 2.0f));
        const Frame f = renderFrame(r.id);
        test::dumpFrame(f, backend == Backend::Cpu ? "trail_cpu" : "trail_vulkan");
        auto red = [&](std::uint32_t x, std::uint32_t y) { return static_cast<int>(test::pixel(f, x, y)[0]); };
        for (std::uint32_t x = 23; x <= 28; ++x) {
            EXPECT_GT(red(x, 31), 40) << "on the ribbon, column " << x;
            EXPECT_GT(red(x, 32), 40) << "on the ribbon, column " << x;
        }
        // Outside: before its tail, past the particle, and beside it.
        for (std::uint32_t x : {0u, 10u, 20u, 21u, 30u, 31u, 40u, 63u}) {
            EXPECT_EQ(red(x, 31), 0) << "off the ribbon, column " << x;
            EXPECT_EQ(red(x, 32), 0) << "off the ribbon, column " << x;
        }
        for (std::uint32_t x = 23; x <= 28; ++x) {
            EXPECT_EQ(red(x, 28), 0) << "above the ribbon, column " << x;
            EXPECT_EQ(red(x, 35), 0) << "below the ribbon, column " << x;
        }
        EXPECT_GT(red(28, 32), red(23, 32) + 20) << "brighter at the head than at the tail";
    }
}

// A ribbon far thinner than a pixel (1 cm at 32 px a metre: a third of a
// pixel) is drawn at least 1.5 px wide and fainter, so it stays continuous:
// drawn at its width it fell between pixel centres and broke into dashes.
// A particle along a slanted line; every pixel column the ribbon spans has
// a lit pixel.
TEST_F(Trails, ThinRibbonsStayContinuous) {
    test::BackendWorld w(Backend::Cpu);
    test::OneShot o;
    o.start = {-0.5f, -0.2f, 0.0f};
    o.velocity = {1.2f, 0.5f, 0.0f};
    o.size = 0.0f;
    EmitterDef def = test::oneShotEmitter(o);
    def.color = {glm::vec4(4.0f, 4.0f, 4.0f, 1.0f), glm::vec4(4.0f, 4.0f, 4.0f, 1.0f)};  // HDR: a faint line still shows
    def.trail.points = 31;
    def.trail.width = 0.01f;
    createEmitter(w.id, def);
    for (int step = 0; step < 30; ++step) {
        stepWorld(w.id, kDt);
    }
    // From x = -0.5 to -0.1 m: columns 16 to 28.8.
    test::ScopedRenderer r(w.id, test::orthoView(64, 64, 2.0f));
    const Frame f = renderFrame(r.id);
    test::dumpFrame(f, "trail_thin");
    for (std::uint32_t x = 17; x <= 28; ++x) {
        int brightest = 0;
        for (std::uint32_t y = 0; y < f.height; ++y) {
            brightest = std::max(brightest, static_cast<int>(test::pixel(f, x, y)[0]));
        }
        EXPECT_GT(brightest, 20) << "column " << x;
    }
}

// A newborn's ribbon has points that have not spread yet: segments of zero
// length, whose triangles have no area. Drawn, such a triangle gave NaN
// fragments where its line crossed a pixel centre (llvmpipe), which the
// bloom spread into a black square (seen in scenes/fireworks.toml). 20,000
// ribbons two steps after a burst, seen as the fireworks are, left two black
// pixels with the old shader (one after four steps); the sky is nowhere
// black, so no pixel may be (0, 0, 0). Bloom off: a NaN stays one pixel.
TEST_F(Trails, NewbornRibbonsLeaveNoHoleInTheFrame) {
    const SceneDef scene = parseScene(R"(
[world]
seed = 11
[camera]
eye = [0.0, 6.0, 19.0]
target = [0.0, 8.5, 0.0]
fov = 50
[render]
bloom = 0.0
[[emitter]]
name = "burst"
capacity = 20000
rate = 0
bursts = [{ time = 0.0, count = 20000 }]
lifetime = 5.0
speed = [6.0, 8.0]
size = 0.0
shape = { kind = "sphere", center = [0.0, 8.0, 0.0], radius = 0.05, surface = true, spread = 180 }
trail = { points = 12, width = 0.05, width_over_length = [{ t = 0.0, value = 1.0 }, { t = 1.0, value = 0.0 }] }
)",
                                      "burst.toml");
    const WorldId world = buildWorld(scene);
    stepWorld(world, kDt);  // born: every point at the birth position
    stepWorld(world, kDt);  // the heads moved on; points 1 to 11 still there
    {
        test::ScopedRenderer r(world, scene.render);
        const Frame f = renderFrame(r.id);
        test::dumpFrame(f, "trail_newborn");
        int black = 0;
        for (std::uint32_t y = 0; y < f.height; ++y) {
            for (std::uint32_t x = 0; x < f.width; ++x) {
                const std::uint8_t* p = test::pixel(f, x, y);
                black += p[0] == 0 && p[1] == 0 && p[2] == 0 ? 1 : 0;
            }
        }
        EXPECT_EQ(black, 0);
    }
    destroyWorld(world);
}

}  // namespace
}  // namespace spindrift
