// Material textures (material_textures.h).
#include "render/material_textures.h"

#include "render/render_rules.h"
#include "world/world.h"

#include <spindrift/bodies.h>

#include <fmt/format.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace spindrift::render {
namespace {

// One image in linear light, RGBA, rows top first.
struct LinearImage {
    std::uint32_t width = 0, height = 0;
    std::vector<glm::vec4> texels;
    glm::vec4 at(std::uint32_t x, std::uint32_t y) const { return texels[std::size_t{y} * width + x]; }
};

// IEC 61966-2-1, both ways.
float srgbToLinear(float e) { return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f); }
std::uint8_t linearToSrgbByte(float l) {
    l = std::clamp(l, 0.0f, 1.0f);
    const float e = l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(e * 255.0f));
}

LinearImage loadLinear(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    // The size from the header first: decoding is what would take the memory.
    if (stbi_info(path.c_str(), &w, &h, &channels) == 0 || w > static_cast<int>(render_rules::kMaxImageSide) ||
        h > static_cast<int>(render_rules::kMaxImageSide)) {
        throw Error(fmt::format("surface texture: cannot read image '{}' (or it is over {} texels a side)", path,
                                render_rules::kMaxImageSide));
    }
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 4), stbi_image_free);
    if (!pixels) {
        throw Error(fmt::format("surface texture: cannot read image '{}': {}", path, stbi_failure_reason()));
    }
    LinearImage image{static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h), {}};
    image.texels.resize(std::size_t{image.width} * image.height);
    for (std::size_t i = 0; i < image.texels.size(); ++i) {
        const stbi_uc* p = pixels.get() + 4 * i;
        image.texels[i] = {srgbToLinear(p[0] / 255.0f), srgbToLinear(p[1] / 255.0f), srgbToLinear(p[2] / 255.0f),
                           p[3] / 255.0f};
    }
    return image;
}

// Bilinear resampling to width x height, texel centres onto texel centres,
// wrapping at the edges (the texture repeats).
LinearImage resample(const LinearImage& in, std::uint32_t width, std::uint32_t height) {
    if (in.width == width && in.height == height) return in;
    LinearImage out{width, height, std::vector<glm::vec4>(std::size_t{width} * height)};
    for (std::uint32_t y = 0; y < height; ++y) {
        const float fy = (y + 0.5f) * in.height / height - 0.5f;
        const float y0 = std::floor(fy), ty = fy - y0;
        const std::uint32_t ya = (static_cast<std::int64_t>(y0) + in.height) % in.height, yb = (ya + 1) % in.height;
        for (std::uint32_t x = 0; x < width; ++x) {
            const float fx = (x + 0.5f) * in.width / width - 0.5f;
            const float x0 = std::floor(fx), tx = fx - x0;
            const std::uint32_t xa = (static_cast<std::int64_t>(x0) + in.width) % in.width, xb = (xa + 1) % in.width;
            const glm::vec4 top = glm::mix(in.at(xa, ya), in.at(xb, ya), tx);
            const glm::vec4 bottom = glm::mix(in.at(xa, yb), in.at(xb, yb), tx);
            out.texels[std::size_t{y} * width + x] = glm::mix(top, bottom, ty);
        }
    }
    return out;
}

// The next mip level: each texel the mean of the 2 x 2 (or, at an odd or
// unit side, fewer) texels under it, in linear light.
LinearImage halve(const LinearImage& in) {
    LinearImage out{std::max(in.width / 2, 1u), std::max(in.height / 2, 1u), {}};
    out.texels.resize(std::size_t{out.width} * out.height);
    for (std::uint32_t y = 0; y < out.height; ++y) {
        for (std::uint32_t x = 0; x < out.width; ++x) {
            const std::uint32_t x1 = std::min(2 * x + 1, in.width - 1), y1 = std::min(2 * y + 1, in.height - 1);
            out.texels[std::size_t{y} * out.width + x] =
                0.25f * (in.at(2 * x, 2 * y) + in.at(x1, 2 * y) + in.at(2 * x, y1) + in.at(x1, y1));
        }
    }
    return out;
}

void addPath(MaterialLayers& paths, const std::string& path) {
    if (!path.empty() && std::find(paths.begin(), paths.end(), path) == paths.end()) paths.push_back(path);
}

}  // namespace

bool addBodyTexturePaths(MaterialLayers& paths, const std::vector<BodySnapshot>& bodies) {
    const std::size_t before = paths.size();
    for (const BodySnapshot& b : bodies) addPath(paths, b.texture.path);
    return paths.size() > before;
}

MaterialLayers surfaceTexturePaths(WorldId id) {
    const World& world = worldFromId(id);
    MaterialLayers paths;
    for (const ColliderDef& c : world.colliderDefs) addPath(paths, c.texture.path);
    addBodyTexturePaths(paths, readBodies(id));
    return paths;
}

void createMaterialTextures(gpu::Device& d, MaterialTextures& m, const MaterialLayers& paths) {
    std::vector<LinearImage> images;
    std::uint32_t width = 1, height = 1;
    for (const std::string& path : paths) {
        images.push_back(loadLinear(path));
        width = std::max(width, images.back().width);
        height = std::max(height, images.back().height);
    }
    if (images.empty()) {
        images.push_back(LinearImage{1, 1, {glm::vec4(1.0f)}});
    }
    // Levels down to 1 x 1; the buffer holds level 0 of every layer, then
    // level 1 of every layer, and so on (gpu::uploadImage).
    const std::uint32_t levels = static_cast<std::uint32_t>(std::floor(std::log2(std::max(width, height)))) + 1;
    std::vector<std::vector<LinearImage>> pyramid(images.size());
    for (std::size_t layer = 0; layer < images.size(); ++layer) {
        pyramid[layer].push_back(resample(images[layer], width, height));
        for (std::uint32_t level = 1; level < levels; ++level) pyramid[layer].push_back(halve(pyramid[layer].back()));
    }
    std::vector<std::uint8_t> bytes;
    for (std::uint32_t level = 0; level < levels; ++level) {
        for (const std::vector<LinearImage>& layer : pyramid) {
            for (const glm::vec4& t : layer[level].texels) {
                bytes.insert(bytes.end(), {linearToSrgbByte(t.r), linearToSrgbByte(t.g), linearToSrgbByte(t.b),
                                           static_cast<std::uint8_t>(std::lround(std::clamp(t.a, 0.0f, 1.0f) * 255.0f))});
            }
        }
    }
    gpu::ImageShape shape{VK_IMAGE_VIEW_TYPE_2D_ARRAY, VK_FORMAT_R8G8B8A8_SRGB, width, height, 1};
    shape.arrayLayers = static_cast<std::uint32_t>(images.size());
    shape.levels = levels;
    gpu::Image image = gpu::createSampledImage(d, shape);
    try {
        gpu::uploadImage(d, image, shape, bytes.data(), bytes.size());
    } catch (...) {
        gpu::destroyImage(d, image);
        throw;
    }
    if (m.sampler == VK_NULL_HANDLE) m.sampler = gpu::createSampler(d, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, true);
    gpu::destroyImage(d, m.image);
    m.image = image;
    m.paths = paths;
}

void destroyMaterialTextures(gpu::Device& d, MaterialTextures& m) {
    gpu::destroyImage(d, m.image);
    if (m.sampler != VK_NULL_HANDLE) vkDestroySampler(d.device, m.sampler, nullptr);
    m = MaterialTextures{};
}

}  // namespace spindrift::render
