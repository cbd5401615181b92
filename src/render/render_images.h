// Images the renderer samples: PNG files (sprites, backgrounds) and a 1x1
// white placeholder for bindings with nothing to show.
#pragma once

#include "gpu/vulkan_buffer.h"

#include <string>

namespace spindrift::render {

/// An sRGB RGBA8 image of the PNG at `path`, uploaded; throws Error naming
/// `what` and the path when it cannot be read.
gpu::Image loadImage(gpu::Device& d, const std::string& path, const std::string& what);
gpu::Image whiteImage(gpu::Device& d);

}  // namespace spindrift::render
