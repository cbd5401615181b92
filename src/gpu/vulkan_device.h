// The Vulkan device of the GPU backend: instance, optional validation with a
// counting debug messenger, one compute queue, a command pool and a
// one-time-submit helper. Plain structs and free functions (zeux/niagara style).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace spindrift::gpu {

/// What the debug messenger saw: tests assert that both counts are zero.
struct DebugLog {
    std::mutex mutex;
    std::uint32_t warnings = 0;
    std::uint32_t errors = 0;
    std::vector<std::string> messages;

    void clear();
    std::uint32_t total();
    /// All messages, one per line (for a test's failure text).
    std::string text();
};

enum class DeviceKind : std::uint32_t { Discrete, Integrated, Cpu, Other };

struct DeviceOptions {
    /// Enables VK_LAYER_KHRONOS_validation and a VK_EXT_debug_utils messenger.
    bool validation = false;
    /// Where the messenger writes; null: the device's own log.
    DebugLog* log = nullptr;
    /// Instance extensions a window needs (glfwGetRequiredInstanceExtensions);
    /// when any are given, the device also enables VK_KHR_swapchain.
    std::vector<std::string> instanceExtensions;
};

struct Device {
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    VkPhysicalDeviceMemoryProperties memory{};
    /// The optional features enabled on `device` (createDevice enables
    /// shaderSampledImageArrayDynamicIndexing where the device has it).
    VkPhysicalDeviceFeatures features{};
    DeviceKind kind = DeviceKind::Other;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
    /// The queue also draws (the renderer needs it; lavapipe's does).
    bool graphics = false;
    VkCommandPool commandPool = VK_NULL_HANDLE;
    /// Filled by the messenger unless DeviceOptions::log redirected it.
    std::unique_ptr<DebugLog> ownLog = std::make_unique<DebugLog>();
    DebugLog* log = nullptr;
    /// Bytes moved through staging buffers (vulkan_buffer.cpp).
    std::uint64_t bytesUploaded = 0;
    std::uint64_t bytesDownloaded = 0;
};

/// A zeroed Vulkan info struct with its sType set (T x{sType} would leave the
/// other members unnamed, which -Wmissing-field-initializers rejects).
template <class T>
T vkStruct(VkStructureType type) {
    T t{};
    t.sType = type;
    return t;
}

/// Throws spindrift::Error "<call> failed: <VkResult name>" unless r is VK_SUCCESS.
void check(VkResult r, const char* call);
const char* resultName(VkResult r);

/// Creates everything; throws Error naming the failing call. Destroy with
/// destroyDevice (also on the error path: it accepts a half-built Device).
std::unique_ptr<Device> createDevice(const DeviceOptions& options);
void destroyDevice(Device& d);

/// True when a Vulkan driver with a compute queue is present; never throws.
bool vulkanAvailable();
/// True when a discrete or integrated GPU (not a CPU implementation such as
/// lavapipe) is present; never throws. Cached after the first call.
bool hardwareGpuAvailable();

/// Records with `record`, submits once and waits on a fence.
template <class F>
void submitOnce(Device& d, F&& record);
VkCommandBuffer beginOneTime(Device& d);
void endAndWait(Device& d, VkCommandBuffer cmd);

/// Finds a memory type with `required` property flags among `typeBits`.
std::uint32_t findMemoryType(const Device& d, std::uint32_t typeBits, VkMemoryPropertyFlags required);

const char* deviceKindName(DeviceKind k);

template <class F>
void submitOnce(Device& d, F&& record) {
    VkCommandBuffer cmd = beginOneTime(d);
    record(cmd);
    endAndWait(d, cmd);
}

}  // namespace spindrift::gpu
