// The settings every Vulkan device of the process is created with (GPU
// worlds and renderers): validation, the debug log, presentation extensions.
// Apart from gpu_world.h so that programs (the viewer, the validation report)
// can set and read them without seeing the GPU world's internals.
#pragma once

#include "gpu/vulkan_device.h"

#include <string>
#include <vector>

namespace spindrift::gpu {

/// Validation for GPU worlds created from now on. Default: on when the
/// environment variable SPINDRIFT_VULKAN_VALIDATION is set and not "0".
void setWorldValidation(bool on);
/// Where the debug messengers of all validated GPU worlds write.
DebugLog& worldDebugLog();
/// Instance extensions every device created from now on enables, with
/// VK_KHR_swapchain (the viewer sets them before it builds a world, so the
/// world's device can present). Empty by default: headless.
void setPresentationExtensions(std::vector<std::string> instanceExtensions);
/// Options of the devices of GPU worlds and renderers: validation, log and
/// presentation as set above.
DeviceOptions worldDeviceOptions();

}  // namespace spindrift::gpu
