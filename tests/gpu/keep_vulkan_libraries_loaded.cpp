// Under LeakSanitizer every test that creates a Vulkan instance failed at exit
// with 128 B "leaked" per instance from a module without a name: memory that
// the lavapipe driver or a layer keeps in its static state, which becomes
// unreachable only because the loader dlclose()s the library at
// vkDestroyInstance (Mesa 22.3.6, loader 1.3.239). Keeping the libraries
// mapped (RTLD_NODELETE) keeps that memory reachable, so LeakSanitizer stays
// on for everything else instead of being switched off or given a blanket
// suppression. The loader still opens and closes them as usual. Only for the
// sanitizer build.
#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>

#include <initializer_list>

namespace {

struct KeepVulkanLibrariesLoaded {
    KeepVulkanLibrariesLoaded() {
        for (const char* library : {"libvulkan_lvp.so", "libVkLayer_MESA_device_select.so",
                                    "libVkLayer_khronos_validation.so"}) {
            dlopen(library, RTLD_LAZY | RTLD_NODELETE);  // absent: nothing to keep
        }
    }
};

const KeepVulkanLibrariesLoaded keepVulkanLibrariesLoaded;

}  // namespace
#endif
