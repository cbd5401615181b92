// PNG files that scenes name (decoded with stb_image): greyscale height maps
// are decoded here; sprite textures and background images are only checked,
// the renderer decodes them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace spindrift::scene {

struct GreyImage {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    /// width * height values in [0, 1] (8-bit / 255, 16-bit / 65535), row 0
    /// (the top of the image) first, x fastest.
    std::vector<float> values;
};

/// Decodes an 8- or 16-bit greyscale PNG (an alpha channel is ignored). On
/// failure returns false and says why in `error`; colour images are refused
/// rather than silently converted, and images wider or taller than maxSide
/// pixels before anything is decoded (from the header's size).
bool decodeGreyPng(const std::string& bytes, std::uint32_t maxSide, GreyImage& image, std::string& error);

/// Checks that `bytes` are a PNG that stb_image can decode (any channel
/// count) of at most maxSide pixels a side, from its header; on failure
/// returns false and says why in `error`.
bool checkPng(const std::string& bytes, std::uint32_t maxSide, std::string& error);

}  // namespace spindrift::scene
