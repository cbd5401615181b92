// The Vulkan device: creation with validation, device choice, the counting
// debug messenger, staging transfers.
#include "gpu/vulkan_buffer.h"
#include "gpu_test_util.h"

#include <array>
#include <cstring>
#include <numeric>
#include <vector>

namespace spindrift {
namespace {

using test::GpuTest;

TEST_F(GpuTest, DeviceCreatesWithValidationAndPicksTheBestKind) {
    gpu::DeviceOptions options;
    options.validation = true;
    std::unique_ptr<gpu::Device> d = gpu::createDevice(options);
    ASSERT_NE(d->device, VK_NULL_HANDLE);
    ASSERT_NE(d->messenger, VK_NULL_HANDLE);
    EXPECT_GE(d->properties.apiVersion, VK_API_VERSION_1_2);
    if (gpu::hardwareGpuAvailable()) {
        EXPECT_TRUE(d->kind == gpu::DeviceKind::Discrete || d->kind == gpu::DeviceKind::Integrated);
    } else {
        // No GPU here: Mesa's lavapipe, which names itself llvmpipe.
        EXPECT_EQ(d->kind, gpu::DeviceKind::Cpu);
        EXPECT_NE(std::string(d->properties.deviceName).find("llvmpipe"), std::string::npos)
            << d->properties.deviceName;
    }
    gpu::destroyDevice(*d);
    EXPECT_EQ(d->log->total(), 0u) << d->log->text();
}

// The messenger must really count: an invalid call (a buffer of size 0,
// VUID-VkBufferCreateInfo-size-00912) has to show up as an error.
TEST_F(GpuTest, MessengerCountsAValidationError) {
    gpu::DeviceOptions options;
    options.validation = true;
    std::unique_ptr<gpu::Device> d = gpu::createDevice(options);
    auto info = gpu::vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkResult r = vkCreateBuffer(d->device, &info, nullptr, &buffer);
    if (r == VK_SUCCESS && buffer != VK_NULL_HANDLE) {
        vkDestroyBuffer(d->device, buffer, nullptr);
    }
    EXPECT_GE(d->log->errors, 1u);
    EXPECT_NE(d->log->text().find("00912"), std::string::npos) << d->log->text();
    gpu::destroyDevice(*d);
}

TEST_F(GpuTest, StagingRoundTripIsExactAndCounted) {
    gpu::DeviceOptions options;
    options.validation = true;
    std::unique_ptr<gpu::Device> d = gpu::createDevice(options);
    std::vector<std::uint32_t> a(1000), b(77);
    std::iota(a.begin(), a.end(), 5u);
    std::iota(b.begin(), b.end(), 900u);
    gpu::Buffer ba = gpu::createStorageBuffer(*d, a.size() * 4);
    gpu::Buffer bb = gpu::createStorageBuffer(*d, b.size() * 4);
    std::array<gpu::Transfer, 2> up{{{&ba, a.data(), a.size() * 4}, {&bb, b.data(), b.size() * 4}}};
    gpu::upload(*d, up);
    std::vector<std::uint32_t> a2(a.size()), b2(b.size());
    std::array<gpu::Transfer, 2> down{{{&ba, a2.data(), a2.size() * 4}, {&bb, b2.data(), b2.size() * 4}}};
    gpu::download(*d, down);
    EXPECT_EQ(a, a2);
    EXPECT_EQ(b, b2);
    EXPECT_EQ(d->bytesUploaded, (a.size() + b.size()) * 4);
    EXPECT_EQ(d->bytesDownloaded, (a.size() + b.size()) * 4);
    gpu::destroyBuffer(*d, ba);
    gpu::destroyBuffer(*d, bb);
    gpu::destroyDevice(*d);
    EXPECT_EQ(d->log->total(), 0u) << d->log->text();
}

TEST_F(GpuTest, ErrorsNameTheCallAndResult) {
    try {
        gpu::check(VK_ERROR_OUT_OF_DEVICE_MEMORY, "vkAllocateMemory");
        FAIL() << "check did not throw";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("vkAllocateMemory failed: VK_ERROR_OUT_OF_DEVICE_MEMORY"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace spindrift
