// `spindrift view`: a window showing a scene as it simulates, drawn by the
// same renderer as `spindrift render`, with a Dear ImGui panel (viewer.cpp).
#pragma once

#include <cstdint>
#include <string>

namespace spindrift::app {

struct ViewOptions {
    std::string scene;
    std::uint32_t frames = 0;  ///< 0: until the window closes; else show this many and exit
    std::uint32_t width = 0;   ///< 0: the scene's render width
    std::uint32_t height = 0;  ///< 0: the scene's render height
    std::string backend;       ///< empty: the scene's; else cpu, vulkan or auto
    std::string script;        ///< tests: input and reports by frame (view_script.h); empty: none
};

/// Opens the window and runs until it closes, Esc, or `frames` frames.
/// Returns the exit status: 0, or 1 when validation (SPINDRIFT_VULKAN_VALIDATION)
/// reported any message. Throws Error (SceneError) for a bad scene or no
/// display / Vulkan presentation.
int viewCommand(const ViewOptions& options);

}  // namespace spindrift::app
