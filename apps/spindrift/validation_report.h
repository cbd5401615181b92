// The last line of `render` and `view`: what was done and, when Vulkan
// validation is on (SPINDRIFT_VULKAN_VALIDATION=1), how many validation
// messages the run produced; any message makes the exit status 1, so tests
// and CI can hold the renderer to zero.
#pragma once

#include "gpu/device_settings.h"

#include <fmt/format.h>

#include <cstdio>
#include <string>

namespace spindrift::app {

inline int finishWithValidationReport(const std::string& summary) {
    if (!gpu::worldDeviceOptions().validation) {
        fmt::print("{}\n", summary);
        return 0;
    }
    const std::uint32_t messages = gpu::worldDebugLog().total();
    fmt::print("{}, {} validation messages\n", summary, messages);
    if (messages > 0) std::fprintf(stderr, "%s\n", gpu::worldDebugLog().text().c_str());
    return messages == 0 ? 0 : 1;
}

}  // namespace spindrift::app
