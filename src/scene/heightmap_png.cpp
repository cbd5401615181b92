#include "scene/heightmap_png.h"

// stb_image's implementation lives in Debian's libstb; the build defines
// SPINDRIFT_HAVE_STB where the library is linked with it. Without it a PNG
// height map is a clear error instead of a link failure.
#ifdef SPINDRIFT_HAVE_STB
#include <stb/stb_image.h>
#endif

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <memory>

namespace spindrift::scene {

namespace {

bool hasPngSignature(const std::string& bytes) {
    static const char kSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
    return bytes.size() >= 8 && std::memcmp(bytes.data(), kSignature, 8) == 0;
}

#ifdef SPINDRIFT_HAVE_STB

// Decodes to one channel of T (8- or 16-bit) and scales to [0, 1].
template <class T, class Load>
bool decodeChannel(const std::string& bytes, Load load, float fullScale, GreyImage& image,
                   std::string& error) {
    int w = 0;
    int h = 0;
    int channels = 0;
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    std::unique_ptr<T, void (*)(void*)> pixels(
        load(data, static_cast<int>(bytes.size()), &w, &h, &channels, 1), &stbi_image_free);
    if (!pixels) {
        error = stbi_failure_reason();
        return false;
    }
    image.width = static_cast<std::uint32_t>(w);
    image.height = static_cast<std::uint32_t>(h);
    image.values.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (std::size_t i = 0; i < image.values.size(); ++i) {
        image.values[i] = static_cast<float>(pixels.get()[i]) / fullScale;
    }
    return true;
}

// The header's size against the limit, before a pixel is decoded.
bool withinSide(int w, int h, std::uint32_t maxSide, std::string& error) {
    if (w > static_cast<std::int64_t>(maxSide) || h > static_cast<std::int64_t>(maxSide)) {
        error = fmt::format("the image is {} x {} pixels; at most {} a side", w, h, maxSide);
        return false;
    }
    return true;
}

#endif

}  // namespace

bool decodeGreyPng(const std::string& bytes, std::uint32_t maxSide, GreyImage& image, std::string& error) {
    if (!hasPngSignature(bytes)) {
        error = "not a PNG file (the PNG signature is missing)";
        return false;
    }
#ifdef SPINDRIFT_HAVE_STB
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    const int size = static_cast<int>(bytes.size());
    int w = 0;
    int h = 0;
    int channels = 0;
    if (stbi_info_from_memory(data, size, &w, &h, &channels) == 0) {
        error = fmt::format("cannot decode the PNG: {}", stbi_failure_reason());
        return false;
    }
    if (!withinSide(w, h, maxSide, error)) {
        return false;
    }
    // 1 = grey, 2 = grey + alpha; colour would need a guess at what "height" means.
    if (channels > 2) {
        error = fmt::format("expected a greyscale PNG, got {} colour channels", channels);
        return false;
    }
    if (stbi_is_16_bit_from_memory(data, size) != 0) {
        return decodeChannel<stbi_us>(bytes, &stbi_load_16_from_memory, 65535.0f, image, error);
    }
    return decodeChannel<stbi_uc>(bytes, &stbi_load_from_memory, 255.0f, image, error);
#else
    (void)image;
    (void)maxSide;
    error = "this build of spindrift reads no PNG files (it was built without stb_image)";
    return false;
#endif
}

bool checkPng(const std::string& bytes, std::uint32_t maxSide, std::string& error) {
    if (!hasPngSignature(bytes)) {
        error = "not a PNG file (the PNG signature is missing)";
        return false;
    }
#ifdef SPINDRIFT_HAVE_STB
    int w = 0;
    int h = 0;
    int channels = 0;
    if (stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &w,
                              &h, &channels) == 0) {
        error = fmt::format("cannot decode the PNG: {}", stbi_failure_reason());
        return false;
    }
    return withinSide(w, h, maxSide, error);
#else
    (void)maxSide;
    error = "this build of spindrift reads no PNG files (it was built without stb_image)";
    return false;
#endif
}

}  // namespace spindrift::scene
