// Images the renderer samples (see render_images.h).
#include "render/render_images.h"

#include "render/render_rules.h"

#include <spindrift/effects.h>

#include <fmt/format.h>
#include <stb/stb_image.h>

#include <memory>

namespace spindrift::render {
namespace {

gpu::Image uploadRgba(gpu::Device& d, std::uint32_t width, std::uint32_t height, const void* texels) {
    gpu::ImageShape shape{VK_IMAGE_VIEW_TYPE_2D, VK_FORMAT_R8G8B8A8_SRGB, width, height, 1};
    gpu::Image image = gpu::createSampledImage(d, shape);
    gpu::uploadImage(d, image, shape, texels, VkDeviceSize{width} * height * 4);
    return image;
}

}  // namespace

gpu::Image loadImage(gpu::Device& d, const std::string& path, const std::string& what) {
    int w = 0, h = 0, channels = 0;
    // The size from the header first: decoding is what would take the memory.
    if (stbi_info(path.c_str(), &w, &h, &channels) == 0) {
        throw Error(fmt::format("{}: cannot read image '{}': {}", what, path, stbi_failure_reason()));
    }
    if (w > static_cast<int>(render_rules::kMaxImageSide) || h > static_cast<int>(render_rules::kMaxImageSide)) {
        throw Error(fmt::format("{}: image '{}' is {} x {}; at most {} x {}", what, path, w, h,
                                render_rules::kMaxImageSide, render_rules::kMaxImageSide));
    }
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 4), stbi_image_free);
    if (!pixels) {
        throw Error(fmt::format("{}: cannot read image '{}': {}", what, path, stbi_failure_reason()));
    }
    return uploadRgba(d, static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), pixels.get());
}

gpu::Image whiteImage(gpu::Device& d) {
    const std::uint8_t white[4] = {255, 255, 255, 255};
    return uploadRgba(d, 1, 1, white);
}


}  // namespace spindrift::render
