// Vulkan instance and device setup for the GPU backend.
#include "gpu/vulkan_device.h"

#include <spindrift/effects.h>

#include <fmt/format.h>

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#endif

#include <algorithm>
#include <cstring>
#include <initializer_list>

namespace spindrift::gpu {
namespace {

// Sanitizer builds only. Under LeakSanitizer every process (tests, the command
// line tool) that created a Vulkan instance failed at exit with 128 B "leaked"
// per instance from a module without a name: memory that the lavapipe driver
// or a layer keeps in its static state, which becomes
// unreachable only because the loader dlclose()s the library at
// vkDestroyInstance (Mesa 22.3.6, loader 1.3.239). Keeping the libraries
// mapped (RTLD_NODELETE) keeps that memory reachable, so LeakSanitizer stays
// on for everything else instead of being switched off or given a blanket
// suppression. The loader still opens and closes them as usual. Done before
// the process's first instance, not at start-up: lavapipe brings LLVM, and
// mapping it in each of the test suite's 600 processes, most of which never
// touch Vulkan, cost about 0.1 s apiece.
void keepVulkanLibrariesLoaded() {
#if defined(__SANITIZE_ADDRESS__)
    static const bool kept = [] {
        for (const char* library : {"libvulkan_lvp.so", "libVkLayer_MESA_device_select.so",
                                    "libVkLayer_khronos_validation.so"}) {
            dlopen(library, RTLD_LAZY | RTLD_NODELETE);  // absent: nothing to keep
        }
        return true;
    }();
    (void)kept;
#endif
}

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

// Counts warnings and errors and keeps their text (the messenger's pUserData
// is the DebugLog). Returning VK_FALSE is required for application callbacks
// (Vulkan 1.3 spec, PFN_vkDebugUtilsMessengerCallbackEXT).
VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* log = static_cast<DebugLog*>(user);
    std::lock_guard lock(log->mutex);
    bool error = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) != 0;
    (error ? log->errors : log->warnings) += 1;
    log->messages.push_back(fmt::format("{}: {}", error ? "error" : "warning",
                                        data != nullptr && data->pMessage != nullptr ? data->pMessage : "?"));
    return VK_FALSE;
}

VkDebugUtilsMessengerCreateInfoEXT messengerInfo(DebugLog* log) {
    auto info = vkStruct<VkDebugUtilsMessengerCreateInfoEXT>(VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT);
    info.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onDebugMessage;
    info.pUserData = log;
    return info;
}

bool hasLayer(const char* name) {
    std::uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

VkInstance createInstance(bool validation, DebugLog* log, const std::vector<std::string>& extra) {
    keepVulkanLibrariesLoaded();
    std::uint32_t version = VK_API_VERSION_1_0;
    check(vkEnumerateInstanceVersion(&version), "vkEnumerateInstanceVersion");
    if (version < VK_API_VERSION_1_2) {
        throw Error(fmt::format("Vulkan 1.2 is required; the loader offers {}.{}", VK_API_VERSION_MAJOR(version),
                                VK_API_VERSION_MINOR(version)));
    }
    if (validation && !hasLayer(kValidationLayer)) {
        throw Error(fmt::format("validation was requested but {} is not installed (Debian: vulkan-validationlayers)",
                                kValidationLayer));
    }
    auto app = vkStruct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "spindrift";
    app.pEngineName = "spindrift";
    app.apiVersion = VK_API_VERSION_1_2;
    std::vector<const char*> extensions;
    for (const std::string& e : extra) {
        extensions.push_back(e.c_str());
    }
    auto info = vkStruct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
    // Chained messenger info: also reports problems inside vkCreateInstance and
    // vkDestroyInstance (VK_EXT_debug_utils, "pNext chain of VkInstanceCreateInfo").
    VkDebugUtilsMessengerCreateInfoEXT debug = messengerInfo(log);
    if (validation) {
        info.enabledLayerCount = 1;
        info.ppEnabledLayerNames = &kValidationLayer;
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        info.pNext = &debug;
    }
    info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
    return instance;
}

VkDebugUtilsMessengerEXT createMessenger(VkInstance instance, DebugLog* log) {
    // Extension entry points are not exported by the loader: fetch them.
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create == nullptr) {
        throw Error("vkGetInstanceProcAddr(vkCreateDebugUtilsMessengerEXT) returned null");
    }
    VkDebugUtilsMessengerCreateInfoEXT info = messengerInfo(log);
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    check(create(instance, &info, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
    return messenger;
}

DeviceKind kindOf(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return DeviceKind::Discrete;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return DeviceKind::Integrated;
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return DeviceKind::Cpu;
        default: return DeviceKind::Other;
    }
}

// A queue family with compute, one that also has graphics where there is one
// (the renderer draws with the world's queue); UINT32_MAX when there is none.
std::uint32_t computeFamily(VkPhysicalDevice physical) {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    const VkQueueFlags both = VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT;
    for (std::uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & both) == both) {
            return i;
        }
    }
    for (std::uint32_t i = 0; i < count; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) != 0) {
            return i;
        }
    }
    return UINT32_MAX;
}

bool hasGraphics(VkPhysicalDevice physical, std::uint32_t family) {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    return family < count && (families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
}

struct Candidate {
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    DeviceKind kind = DeviceKind::Other;
    std::uint32_t family = UINT32_MAX;
};

// Discrete first, then integrated, then CPU, then anything else; among equals
// the first enumerated. Only Vulkan 1.2 devices with a compute queue count.
std::vector<Candidate> rankDevices(VkInstance instance) {
    std::uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
    std::vector<Candidate> out;
    for (VkPhysicalDevice p : devices) {
        VkPhysicalDeviceProperties props;
        vkGetPhysicalDeviceProperties(p, &props);
        std::uint32_t family = computeFamily(p);
        if (props.apiVersion >= VK_API_VERSION_1_2 && family != UINT32_MAX) {
            out.push_back({p, kindOf(props.deviceType), family});
        }
    }
    std::stable_sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.kind < b.kind; });
    return out;
}

// Enables the few optional features the backend uses, where the device has them
// (vkGetPhysicalDeviceFeatures): indexing the field sampler arrays of
// effects_update.comp with a dynamically uniform value.
VkDevice createLogicalDevice(VkPhysicalDevice physical, std::uint32_t family, VkPhysicalDeviceFeatures& enabled,
                             bool swapchain) {
    VkPhysicalDeviceFeatures available{};
    vkGetPhysicalDeviceFeatures(physical, &available);
    enabled = VkPhysicalDeviceFeatures{};
    enabled.shaderSampledImageArrayDynamicIndexing = available.shaderSampledImageArrayDynamicIndexing;
    float priority = 1.0f;
    auto queue = vkStruct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue.queueFamilyIndex = family;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    auto info = vkStruct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    info.pEnabledFeatures = &enabled;
    const char* swapchainExtension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
    if (swapchain) {
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &swapchainExtension;
    }
    VkDevice device = VK_NULL_HANDLE;
    check(vkCreateDevice(physical, &info, nullptr, &device), "vkCreateDevice");
    return device;
}

VkCommandPool createCommandPool(VkDevice device, std::uint32_t family) {
    auto info = vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    info.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    info.queueFamilyIndex = family;
    VkCommandPool pool = VK_NULL_HANDLE;
    check(vkCreateCommandPool(device, &info, nullptr, &pool), "vkCreateCommandPool");
    return pool;
}

// Any Candidate at all (kind filter applied by the caller); never throws.
bool probe(bool (*accept)(DeviceKind)) {
    try {
        VkInstance instance = createInstance(false, nullptr, {});
        bool found = false;
        try {
            for (const Candidate& c : rankDevices(instance)) {
                found = found || accept(c.kind);
            }
        } catch (const std::exception&) {
        }
        vkDestroyInstance(instance, nullptr);
        return found;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace

void DebugLog::clear() {
    std::lock_guard lock(mutex);
    warnings = 0;
    errors = 0;
    messages.clear();
}

std::uint32_t DebugLog::total() {
    std::lock_guard lock(mutex);
    return warnings + errors;
}

std::string DebugLog::text() {
    std::lock_guard lock(mutex);
    std::string out;
    for (const std::string& m : messages) {
        out += m;
        out += '\n';
    }
    return out;
}

const char* resultName(VkResult r) {
    switch (r) {
        case VK_SUCCESS: return "VK_SUCCESS";
        case VK_NOT_READY: return "VK_NOT_READY";
        case VK_TIMEOUT: return "VK_TIMEOUT";
        case VK_INCOMPLETE: return "VK_INCOMPLETE";
        case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
        case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
        case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
        case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
        case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
        case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
        case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
        case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
        case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
        case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
        case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
        case VK_ERROR_FRAGMENTED_POOL: return "VK_ERROR_FRAGMENTED_POOL";
        case VK_ERROR_OUT_OF_POOL_MEMORY: return "VK_ERROR_OUT_OF_POOL_MEMORY";
        default: return "VkResult (unnamed)";
    }
}

void check(VkResult r, const char* call) {
    if (r != VK_SUCCESS) {
        throw Error(fmt::format("{} failed: {} ({})", call, resultName(r), static_cast<int>(r)));
    }
}

const char* deviceKindName(DeviceKind k) {
    switch (k) {
        case DeviceKind::Discrete: return "discrete GPU";
        case DeviceKind::Integrated: return "integrated GPU";
        case DeviceKind::Cpu: return "CPU";
        default: return "other";
    }
}

std::unique_ptr<Device> createDevice(const DeviceOptions& options) {
    auto d = std::make_unique<Device>();
    d->log = options.log != nullptr ? options.log : d->ownLog.get();
    try {
        d->instance = createInstance(options.validation, d->log, options.instanceExtensions);
        if (options.validation) {
            d->messenger = createMessenger(d->instance, d->log);
        }
        std::vector<Candidate> candidates = rankDevices(d->instance);
        if (candidates.empty()) {
            throw Error("no Vulkan 1.2 device with a compute queue (install mesa-vulkan-drivers for lavapipe)");
        }
        d->physical = candidates.front().physical;
        d->kind = candidates.front().kind;
        d->queueFamily = candidates.front().family;
        vkGetPhysicalDeviceProperties(d->physical, &d->properties);
        vkGetPhysicalDeviceMemoryProperties(d->physical, &d->memory);
        d->graphics = hasGraphics(d->physical, d->queueFamily);
        d->device = createLogicalDevice(d->physical, d->queueFamily, d->features, !options.instanceExtensions.empty());
        vkGetDeviceQueue(d->device, d->queueFamily, 0, &d->queue);
        d->commandPool = createCommandPool(d->device, d->queueFamily);
    } catch (...) {
        destroyDevice(*d);
        throw;
    }
    return d;
}

// Children before parents, the reverse of creation (Vulkan spec, "Object
// Lifetime": a VkDevice's objects are destroyed before it, and the instance last).
void destroyDevice(Device& d) {
    if (d.device != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(d.device);
        if (d.commandPool != VK_NULL_HANDLE) {
            vkDestroyCommandPool(d.device, d.commandPool, nullptr);
        }
        vkDestroyDevice(d.device, nullptr);
    }
    if (d.messenger != VK_NULL_HANDLE) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(d.instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy != nullptr) {
            destroy(d.instance, d.messenger, nullptr);
        }
    }
    if (d.instance != VK_NULL_HANDLE) {
        vkDestroyInstance(d.instance, nullptr);
    }
    d.commandPool = VK_NULL_HANDLE;
    d.device = VK_NULL_HANDLE;
    d.messenger = VK_NULL_HANDLE;
    d.instance = VK_NULL_HANDLE;
}

bool vulkanAvailable() {
    static const bool available = probe([](DeviceKind) { return true; });
    return available;
}

bool hardwareGpuAvailable() {
    static const bool available =
        probe([](DeviceKind k) { return k == DeviceKind::Discrete || k == DeviceKind::Integrated; });
    return available;
}

VkCommandBuffer beginOneTime(Device& d) {
    auto alloc = vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = d.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(d.device, &alloc, &cmd), "vkAllocateCommandBuffers");
    auto begin = vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VkResult r = vkBeginCommandBuffer(cmd, &begin);
    if (r != VK_SUCCESS) {
        vkFreeCommandBuffers(d.device, d.commandPool, 1, &cmd);
        check(r, "vkBeginCommandBuffer");
    }
    return cmd;
}

// Submits and blocks on a fence; the command buffer is freed on every path.
void endAndWait(Device& d, VkCommandBuffer cmd) {
    VkFence fence = VK_NULL_HANDLE;
    auto cleanup = [&] {
        if (fence != VK_NULL_HANDLE) {
            vkDestroyFence(d.device, fence, nullptr);
        }
        vkFreeCommandBuffers(d.device, d.commandPool, 1, &cmd);
    };
    try {
        check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
        auto fenceInfo = vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        check(vkCreateFence(d.device, &fenceInfo, nullptr, &fence), "vkCreateFence");
        auto submit = vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        check(vkQueueSubmit(d.queue, 1, &submit, fence), "vkQueueSubmit");
        check(vkWaitForFences(d.device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    } catch (...) {
        if (fence != VK_NULL_HANDLE) {
            vkQueueWaitIdle(d.queue);  // the buffer may be pending: wait before freeing
        }
        cleanup();
        throw;
    }
    cleanup();
}

std::uint32_t findMemoryType(const Device& d, std::uint32_t typeBits, VkMemoryPropertyFlags required) {
    for (std::uint32_t i = 0; i < d.memory.memoryTypeCount; ++i) {
        if ((typeBits & (1u << i)) != 0 && (d.memory.memoryTypes[i].propertyFlags & required) == required) {
            return i;
        }
    }
    throw Error(fmt::format("no Vulkan memory type with properties 0x{:x} among types 0x{:x}", required, typeBits));
}

}  // namespace spindrift::gpu
