// Sampled fields on the Vulkan backend, host side: images created, uploaded
// once through staging buffers with layout transitions, bound in set 2 with
// placeholders in the unused elements, counts limited with a clear error; all
// without a validation message. The sampling itself is checked against the CPU
// backend in gpu_world_test.cpp and gpu_scenes_test.cpp.
#include "gpu_test_util.h"

#include <cmath>
#include <string>

namespace spindrift {
namespace {

using test::GpuTest;

struct OwnedGpuWorld {
    OwnedGpuWorld() : w(gpu::createGpuWorld()) {}
    ~OwnedGpuWorld() { gpu::destroyGpuWorld(*w); }
    OwnedGpuWorld(const OwnedGpuWorld&) = delete;
    OwnedGpuWorld& operator=(const OwnedGpuWorld&) = delete;
    std::unique_ptr<gpu::GpuWorld> w;
};

FlowGrid flowGrid(std::uint32_t nx, std::uint32_t ny, std::uint32_t nz) {
    FlowGrid g{nx, ny, nz, {}};
    for (std::uint32_t z = 0; z < nz; ++z) {
        for (std::uint32_t y = 0; y < ny; ++y) {
            for (std::uint32_t x = 0; x < nx; ++x) {
                g.velocity.emplace_back(std::sin(0.7f * y), std::cos(0.5f * z), std::sin(0.3f * x));
            }
        }
    }
    return g;
}

TEST_F(GpuTest, FieldImagesUploadOnceAndBindWithoutValidationMessages) {
    OwnedGpuWorld o;
    gpu::GpuWorld& w = *o.w;
    // lavapipe filters 32-bit float images linearly: no 16-bit fallback here.
    if (w.device->kind == gpu::DeviceKind::Cpu) {
        EXPECT_EQ(w.fields.flowFormat, VK_FORMAT_R32G32B32A32_SFLOAT);
        EXPECT_EQ(w.fields.heightFormat, VK_FORMAT_R32_SFLOAT);
        EXPECT_EQ(w.fields.cubeFormat, VK_FORMAT_R32G32B32A32_SFLOAT);
    }
    ASSERT_NE(w.fields.flowFormat, VK_FORMAT_UNDEFINED);
    const bool full = w.fields.flowFormat == VK_FORMAT_R32G32B32A32_SFLOAT &&
                      w.fields.heightFormat == VK_FORMAT_R32_SFLOAT &&
                      w.fields.cubeFormat == VK_FORMAT_R32G32B32A32_SFLOAT;

    std::uint64_t before = w.device->bytesUploaded;
    gpu::addFlowField(w, flowGrid(5, 4, 3), "swirl");
    HeightMap hills{6, 7, std::vector<float>(42, 0.25f)};
    gpu::addHeightMap(w, hills, "hills");
    std::vector<float> depths(6 * 4 * 4, 1.0f);
    gpu::addCubeMap(w, makeDepthCubeMap(4, depths), "ball");
    if (full) {
        // RGBA32F flow texels, R32F heights, RGBA32F cube texels: each byte once.
        EXPECT_EQ(w.device->bytesUploaded - before, 5u * 4 * 3 * 16 + 42u * 4 + 6u * 4 * 4 * 16);
    }
    EXPECT_EQ(w.fields.flows.size(), 1u);
    EXPECT_EQ(w.fields.heights.size(), 1u);
    EXPECT_EQ(w.fields.cubes.size(), 1u);
    EXPECT_EQ(w.device->bytesDownloaded, 0u);
}

TEST_F(GpuTest, FieldCountsBeyondTheSamplerArraysThrowClearErrors) {
    OwnedGpuWorld o;
    gpu::GpuWorld& w = *o.w;
    for (std::uint32_t i = 0; i < gpu::kMaxGpuFlowFields; ++i) {
        std::string name(1, static_cast<char>('a' + i));
        gpu::addFlowField(w, flowGrid(2, 2, 2), name);
    }
    try {
        gpu::addFlowField(w, flowGrid(2, 2, 2), "one too many");
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("at most 8 flow fields"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("one too many"), std::string::npos) << e.what();
    }
    EXPECT_EQ(w.fields.flows.size(), gpu::kMaxGpuFlowFields);
    const std::uint32_t limit = w.device->properties.limits.maxImageDimensionCube;
    DepthCubeMap huge{limit + 1, {}};  // rejected before its texels are read
    EXPECT_THROW(gpu::addCubeMap(w, huge, "huge"), Error);
    EXPECT_TRUE(w.fields.cubes.empty());
}

}  // namespace
}  // namespace spindrift
