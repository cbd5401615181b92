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

TEST_F(DeviceWater, A2DLiquidFromTheDevicesBuffersIsTheHostsAndReadsNoParticlesBack) {
    // The 2D surface (kernels, their mirror images behind the box's walls,
    // splashes) of a dam break of 1,000 particles, 8 frames 6 steps apart
    // from t = 0.1 s, through the front's strike on the far wall (splashes).
    DeviceFluidWorld w(2);
    for (int s = 0; s < 6; ++s) stepWorld(w.id, kDt);
    std::size_t splashes = 0;
    const std::uint64_t down = compareFrames(w, 2, 8, 6, splashes);
    std::printf("largest read-back of a device-drawn frame: %llu bytes; most splashes alive %zu\n",
                static_cast<unsigned long long>(down), splashes);
    EXPECT_GT(splashes, 0u) << "the dam break threw no splash: the throwers were not tested";
    // The particles alone are 1,000 x 20 bytes (position, velocity, serial);
    // a frame reads back the throwers' count (16 bytes) and 48 bytes a
    // thrower, and at most kMaxSplashes throwers can be alive.
    EXPECT_LT(down, 16u + 48u * 100u);
}

TEST_F(DeviceWater, A3DScreenLiquidFromTheDevicesBuffersIsTheHosts) {
    DeviceFluidWorld w(3);
    for (int s = 0; s < 6; ++s) stepWorld(w.id, kDt);
    std::size_t splashes = 0;
    const std::uint64_t down = compareFrames(w, 3, 4, 8, splashes);
    std::printf("largest read-back of a device-drawn 3D frame: %llu bytes; most splashes alive %zu\n",
                static_cast<unsigned long long>(down), splashes);
    EXPECT_LT(down, 16u + 48u * 100u);
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

}  // namespace
}  // namespace spindrift::test
