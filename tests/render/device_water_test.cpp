// A device fluid's liquid drawn from the device's buffers (issue 16; src/
// render/device_water.h) against the same liquid built on the host from the
// particles read back (Renderer::drawDeviceWater false, the CPU fluid's
// path), on lavapipe with validation on: the same world state, the same
// frames. Both build every instance with the rules of
// src/kernels/fluid_look.glsl and draw them in the same order (the device
// leaves a radius-0 instance where a particle has no mirror image), so the
// frames may differ only by what GLSL's and C++'s float operations round
// differently in an instance (length, division, the smoothstep), a last
// bit of a kernel's amplitude or foam: at most 2 of 255 in a channel, on
// at most 0.5 % of the pixels (measured: see each test's printout).
#include "fluid/fluid_test_util.h"
#include "fluid/fluid_state.h"
#include "gpu/vulkan_buffer.h"
#include "kernels/fluid.glsl"
#include "kernels/fluid_look.glsl"
#include "render/render_test_util.h"
#include "render/renderer.h"
#include "world/device_fluid.h"
#include "world/world.h"

#include <spindrift/fluid.h>
#include <spindrift/render.h>
#include <spindrift/world.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace spindrift::test {
namespace {

constexpr float kDt = 1.0f / 60.0f;

class DeviceWater : public GpuTest {};

/// A Vulkan world whose fluid is solved on the device (lavapipe).
struct DeviceFluidWorld {
    explicit DeviceFluidWorld(std::uint32_t dimension) {
        WorldDef wd;
        wd.backend = Backend::Vulkan;
        wd.threads = 1;
        id = createWorld(wd);
        const glm::vec3 box = dimension == 2 ? glm::vec3(1.2f, 1.0f, 0.0f) : glm::vec3(0.6f, 0.6f, 0.2f);
        closedBox(id, glm::vec3(0.0f), box, dimension);
        FluidDef def;
        def.name = "water";
        def.dimension = dimension;
        def.spacing = dimension == 2 ? 0.02f : 0.04f;
        def.backend = FluidBackend::Gpu;
        // A dam break: a column in the left corner, whose front throws
        // splashes where it meets the far wall.
        const glm::vec3 column = dimension == 2 ? glm::vec3(0.4f, 0.5f, 0.0f) : glm::vec3(0.2f, 0.32f, 0.2f);
        def.blocks.push_back({glm::vec3(0.0f), column, glm::vec3(0.0f)});
        fluid = createFluid(id, def);
    }
    ~DeviceFluidWorld() { destroyWorld(id); }
    DeviceFluidWorld(const DeviceFluidWorld&) = delete;
    DeviceFluidWorld& operator=(const DeviceFluidWorld&) = delete;
    WorldId id;
    FluidId fluid;
};

RenderDef view(std::uint32_t dimension) {
    RenderDef def = orthoView(240, 200, dimension == 2 ? 1.1f : 0.7f, glm::vec3(0.05f, 0.05f, 0.1f));
    def.camera.target = dimension == 2 ? glm::vec3(0.6f, 0.5f, 0.0f) : glm::vec3(0.3f, 0.3f, 0.1f);
    def.camera.eye = def.camera.target + glm::vec3(0.0f, 0.0f, 3.0f);
    def.drawColliders = false;
    return def;
}

/// Channels differing by more than `tolerance`, and the largest difference.
struct FrameDifference {
    std::size_t channels = 0;
    int most = 0;
};
FrameDifference compare(const Frame& a, const Frame& b, int tolerance) {
    FrameDifference d;
    for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) {
        const int diff = std::abs(int(a.rgba[i]) - int(b.rgba[i]));
        d.most = std::max(d.most, diff);
        if (diff > tolerance) ++d.channels;
    }
    return d;
}

/// Renders `frames` frames of the world from two renderers, one drawing the
/// device's buffers and one the particles read back, stepping `stepsBetween`
/// steps before each; checks each pair of frames and that the two
/// renderers hold the same splashes. Returns the device renderer's bytes
/// read back per frame, largest.
std::uint64_t compareFrames(DeviceFluidWorld& w, std::uint32_t dimension, int frames, int stepsBetween,
                            std::size_t& splashesSeen) {
    ScopedRenderer onDevice(w.id, view(dimension));
    ScopedRenderer onHost(w.id, view(dimension));
    render::rendererOf(onHost.id).drawDeviceWater = false;
    std::uint64_t mostDown = 0;
    splashesSeen = 0;
    for (int f = 0; f < frames; ++f) {
        for (int s = 0; s < stepsBetween; ++s) stepWorld(w.id, kDt);
        const TransferStats before = transferStats(w.id);
        const Frame a = renderFrame(onDevice.id);
        mostDown = std::max(mostDown, transferStats(w.id).bytesDownloaded - before.bytesDownloaded);
        const Frame b = renderFrame(onHost.id);
        const FrameDifference d = compare(a, b, 2);
        std::printf("%uD frame %d: %zu channels over 2 of 255 (largest %d)\n", dimension, f, d.channels, d.most);
        EXPECT_LE(d.channels, a.rgba.size() / 200) << "frame " << f;
        dumpFrame(a, "device_water_" + std::to_string(dimension) + "d_device_" + std::to_string(f));
        dumpFrame(b, "device_water_" + std::to_string(dimension) + "d_host_" + std::to_string(f));
        const auto& x = render::rendererOf(onDevice.id).fluids.at(0).state.splashes;
        const auto& y = render::rendererOf(onHost.id).fluids.at(0).state.splashes;
        EXPECT_EQ(x.size(), y.size()) << "frame " << f;
        for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
            // Both from the same device buffers' floats (read back whole, or
            // as a thrower), through the same RNG: equal.
            EXPECT_EQ(x[i].origin, y[i].origin) << "frame " << f << " splash " << i;
            EXPECT_EQ(x[i].velocity, y[i].velocity) << "frame " << f << " splash " << i;
        }
        splashesSeen = std::max(splashesSeen, x.size());
    }
    return mostDown;
}

/// compareFrames on a dam break of `dimension` from t = 0.1 s; returns the
/// most splashes alive. A frame reads back the throwers' count (16 bytes)
/// and 48 bytes a thrower: under a quarter of the particles' own bytes
/// (about 1,000 particles, 20 bytes each: position, velocity, serial) while
/// fewer than 100 throw in a frame (measured: see the printout).
std::size_t compareDamBreak(std::uint32_t dimension, int frames, int stepsBetween) {
    DeviceFluidWorld w(dimension);
    for (int s = 0; s < 6; ++s) stepWorld(w.id, kDt);
    std::size_t splashes = 0;
    const std::uint64_t down = compareFrames(w, dimension, frames, stepsBetween, splashes);
    std::printf("%uD: largest read-back of a device-drawn frame %llu bytes; most splashes alive %zu\n", dimension,
                static_cast<unsigned long long>(down), splashes);
    EXPECT_LT(down, 16u + 48u * 100u);
    return splashes;
}

TEST_F(DeviceWater, A2DLiquidFromTheDevicesBuffersIsTheHostsAndReadsNoParticlesBack) {
    // The 2D surface (kernels, their mirror images behind the box's walls,
    // splashes), 8 frames 6 steps apart, through the front's strike on the
    // far wall (splashes).
    EXPECT_GT(compareDamBreak(2, 8, 6), 0u) << "the dam break threw no splash: the throwers were not tested";
}

TEST_F(DeviceWater, OnlyWallsNearTheWaterGetMirrorSlots) {
    // At t = 0.1 s the column (0.4 m wide, 0.5 m high) touches the left wall
    // and the floor of its 1.2 x 1.0 m box and is far (more than a kernel
    // radius, 4 cm) from the right wall and the top: a slot per particle
    // for itself and for each of the two near walls.
    DeviceFluidWorld w(2);
    for (int s = 0; s < 6; ++s) stepWorld(w.id, kDt);
    ScopedRenderer r(w.id, view(2));
    renderFrame(r.id);
    const std::size_t n = readFluid(w.id, w.fluid).count();
    EXPECT_EQ(render::rendererOf(r.id).fluids.at(0).onDevice, 3 * n);
}

TEST_F(DeviceWater, A3DScreenLiquidFromTheDevicesBuffersIsTheHosts) {
    compareDamBreak(3, 4, 8);
}

TEST_F(DeviceWater, ATankAtRestReadsBackOnlyTheThrowersCount) {
    // No particle rises: each frame reads back 16 bytes (the count), and the
    // host's arrays are never filled from the device.
    WorldDef wd;
    wd.backend = Backend::Vulkan;
    wd.threads = 1;
    const WorldId id = createWorld(wd);
    closedBox(id, glm::vec3(0.0f), glm::vec3(1.0f, 0.6f, 0.0f), 2);
    FluidDef def;
    def.spacing = 0.025f;
    def.backend = FluidBackend::Gpu;
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(1.0f, 0.25f, 0.0f), glm::vec3(0.0f)});
    createFluid(id, def);
    {
        ScopedRenderer r(id, view(2));
        for (int f = 0; f < 5; ++f) {
            stepWorld(id, kDt);
            const TransferStats before = transferStats(id);
            renderFrame(r.id);
            EXPECT_EQ(transferStats(id).bytesDownloaded - before.bytesDownloaded, f == 0 ? 0u : 16u)
                << "frame " << f << " (the first has no frame time: no splashes, nothing read)";
        }
        EXPECT_FALSE(deviceFluidOnHost(*deviceFluidFromId(worldFromId(id), FluidId{1})));
    }
    destroyWorld(id);
}

/// What the splat pass should have written for the device's particles now:
/// the same rules (fluid_look.glsl) on the device's positions, velocities,
/// densities and lists read back, with the shown orientations replayed on
/// the host frame by frame.
struct SplatReplay {
    std::vector<glm::vec4> shown;  // by serial

    std::vector<render::SplatInstance> frame(gpu::Device& d, const DeviceFluidBuffers& b, const fluid::FluidState& f,
                                             const FluidRenderDef& settings, float dt) {
        const std::uint32_t n = b.count, dim = b.dimension;
        auto grab = [&](const gpu::Buffer* buffer, std::size_t count) {
            return gpu::downloadArray<std::uint32_t>(d, *const_cast<gpu::Buffer*>(buffer), count);
        };
        const std::vector<float> x = gpu::downloadArray<float>(d, *const_cast<gpu::Buffer*>(b.x), n * dim);
        const std::vector<float> v = gpu::downloadArray<float>(d, *const_cast<gpu::Buffer*>(b.v), n * dim);
        const std::vector<glm::vec4> c =
            gpu::downloadArray<glm::vec4>(d, *const_cast<gpu::Buffer*>(b.constraints), n);
        const std::vector<std::uint32_t> ids = grab(b.ids, n), counts = grab(b.counts, n), first = grab(b.first, n);
        std::uint32_t entries = 0;
        for (std::uint32_t i = 0; i < n; ++i) entries = std::max(entries, first[i] + counts[i]);
        const std::vector<std::uint32_t> list = grab(b.list, entries);
        auto at = [&](const std::vector<float>& a, std::uint32_t i) {
            return glm::vec3(a[i * dim], a[i * dim + 1], dim == 3 ? a[i * dim + 2] : 0.0f);
        };
        const glm::vec3 up(0.0f, 1.0f, 0.0f);  // gravity -y
        const kernels::SplatSteps steps =
            render::splatSteps(settings, render::splatRadius(settings, f.def.spacing), up, dt, dim);
        const float invH2 = 1.0f / (f.h * f.h);
        std::vector<render::SplatInstance> out;
        for (std::uint32_t i = 0; i < n; ++i) {
            const glm::vec3 xi = at(x, i);
            glm::vec3 sum(0.0f);
            float weights = 0.0f;
            for (std::uint32_t k = 0; k < counts[i]; ++k) {
                const std::uint32_t j = list[first[i] + k];
                const glm::vec3 offset = at(x, j) - xi;
                float r2 = offset.x * offset.x + offset.y * offset.y;
                if (dim == 3) r2 += offset.z * offset.z;
                const glm::vec3 g = kernels::fluidPairG(offset, r2, i, j, invH2);
                sum += g;
                weights += glm::length(g);
            }
            const glm::vec3 dir = kernels::splatAverageDirection(sum, weights);
            if (ids[i] >= shown.size()) shown.resize(ids[i] + 1, glm::vec4(0.0f));
            const kernels::WaterSplat w = kernels::splatOfParticle(xi, at(v, i), c[i].z, ids[i], dir, shown[ids[i]], steps);
            shown[ids[i]] = w.shown;
            out.push_back(w.instance);
        }
        return out;
    }
};

TEST_F(DeviceWater, SplatsFromTheDevicesBuffersAreTheRulesOnItsListsAndPositions) {
    // Sprinkle's seven steps on a 2D dam break on the device: each frame,
    // every splat the pass wrote against the rules evaluated on the host on
    // the same particles and lists read back, with the orientations
    // replayed. Tolerance 2e-5 (relative on radius and shade, absolute on
    // the unit axis and the stretch): the two evaluate the same operations,
    // but GLSL may fuse a multiply-add and lavapipe's acos, cos, sin and exp
    // are not glibc's, a few units in the last place that the smoothing
    // carries from frame to frame (measured largest: see the printout).
    DeviceFluidWorld w(2);
    for (int s = 0; s < 6; ++s) stepWorld(w.id, kDt);
    RenderDef def = view(2);
    def.fluid = FluidRenderDef::upTo(7);
    ScopedRenderer r(w.id, def);
    render::Renderer& renderer = render::rendererOf(r.id);
    const World& world = worldFromId(w.id);
    SplatReplay replay;
    float worst = 0.0f;
    std::size_t edges = 0;
    for (int frame = 0; frame < 6; ++frame) {
        if (frame > 0) {
            for (int s = 0; s < 4; ++s) stepWorld(w.id, kDt);
        }
        renderFrame(r.id);
        const DeviceFluidBuffers b = deviceFluidBuffers(*deviceFluidFromId(world, w.fluid));
        ASSERT_NE(b.list, nullptr);
        const std::vector<render::SplatInstance> expected =
            replay.frame(*renderer.device, b, fluidSettingsFromId(world, w.fluid), def.fluid, frame == 0 ? 0.0f : 4 * kDt);
        const render::SplatFluid& sf = renderer.fluids.at(0);
        ASSERT_EQ(sf.onDevice, b.count);
        const auto* got = static_cast<const render::SplatInstance*>(renderer.splatBuffer.mapped) + sf.first;
        for (std::uint32_t i = 0; i < b.count; ++i) {
            const render::SplatInstance& e = expected[i];
            const render::SplatInstance& g = got[i];
            for (int c = 0; c < 4; ++c) {
                const float scale = c < 3 ? 1.0f : std::max(std::abs(e.centre.w), 1e-3f);
                worst = std::max({worst, std::abs(g.centre[c] - e.centre[c]) / scale, std::abs(g.axis[c] - e.axis[c]),
                                  std::abs(g.shade[c] - e.shade[c]) / std::max(std::abs(e.shade[c]), 1.0f)});
            }
            ASSERT_NEAR(g.centre.w, e.centre.w, 2e-5f * e.centre.w) << "frame " << frame << " particle " << i;
            for (int c = 0; c < 4; ++c) {
                ASSERT_NEAR(g.axis[c], e.axis[c], 2e-5f) << "frame " << frame << " particle " << i << " axis " << c;
                ASSERT_NEAR(g.shade[c], e.shade[c], 2e-5f * std::max(std::abs(e.shade[c]), 1.0f))
                    << "frame " << frame << " particle " << i << " shade " << c;
            }
            if (g.shade.y > 0.5f) ++edges;
        }
    }
    std::printf("largest difference of a splat's numbers: %g; %zu surface splats seen\n", worst, edges);
    EXPECT_GT(edges, 100u) << "the dam break showed no surface: the lists were not tested";
}

TEST_F(DeviceWater, ADeviceFluidsSplatsShowItsSurface) {
    // Before the splats were built on the device, a device fluid's particles
    // came back without its neighbour lists, so no splat had an edge (rule
    // 5) or a surface stretch (rule 3). A resting 2D block on the device,
    // as the CPU fluid's test (FluidSplats.RestingBlockTopIsHorizontalBrightEdge):
    // its top row is edge (factor over 0.9) and bright (over 1.4), the
    // middle rows are not (under 0.1), and the splats are drawn.
    WorldDef wd;
    wd.backend = Backend::Vulkan;
    wd.threads = 1;
    const WorldId id = createWorld(wd);
    closedBox(id, glm::vec3(-0.2f, 0.0f, 0.0f), glm::vec3(0.6f, 1.0f, 0.0f), 2);
    FluidDef def;
    def.spacing = 0.02f;
    def.backend = FluidBackend::Gpu;
    def.blocks.push_back({glm::vec3(-0.2f, 0.0f, 0.0f), glm::vec3(0.6f, 0.2f, 0.0f), glm::vec3(0.0f)});
    createFluid(id, def);
    for (int s = 0; s < 5; ++s) stepWorld(id, kDt);
    {
        RenderDef view2 = view(2);
        view2.fluid = FluidRenderDef::upTo(5);
        ScopedRenderer r(id, view2);
        const Frame frame = renderFrame(r.id);
        dumpFrame(frame, "device_water_splats_block");
        // The splats are drawn: the block's middle, world (0.2, 0.1) m, is
        // pixel (47, 173) of the 240 x 200 view of 1.1 m centred on (0.6,
        // 0.5), and is not the background there.
        int off = 0;
        for (int c = 0; c < 3; ++c) off = std::max(off, std::abs(pixel(frame, 47, 173)[c] - srgbByte(0.05 + (c == 2 ? 0.05 : 0.0))));
        EXPECT_GT(off, 20) << "the block's splats are not drawn";
        const render::Renderer& renderer = render::rendererOf(r.id);
        const render::SplatFluid& sf = renderer.fluids.at(0);
        const auto* got = static_cast<const render::SplatInstance*>(renderer.splatBuffer.mapped) + sf.first;
        ASSERT_EQ(sf.onDevice, 400u);
        int tops = 0, middles = 0;
        for (std::uint32_t i = 0; i < sf.onDevice; ++i) {
            const glm::vec3 x(got[i].centre);
            if (x.x < 0.0f || x.x > 0.4f) continue;  // over h from the side walls
            if (x.y > 0.18f) {
                ++tops;
                EXPECT_GT(got[i].shade.y, 0.9f) << "top particle at " << x.x << ", " << x.y;
                EXPECT_GT(got[i].shade.x, 1.4f) << "top particle at " << x.x << ", " << x.y;
            } else if (x.y > 0.08f && x.y < 0.12f) {
                ++middles;
                EXPECT_LT(got[i].shade.y, 0.1f) << "middle particle at " << x.x << ", " << x.y;
            }
        }
        EXPECT_GE(tops, 15);
        EXPECT_GE(middles, 30);
    }
    destroyWorld(id);
}

}  // namespace
}  // namespace spindrift::test
