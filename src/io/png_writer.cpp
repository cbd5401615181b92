#include "io/png_writer.h"

#include <fmt/format.h>
#include <stb/stb_image_write.h>

#include <climits>
#include <string>

#include "io/atomic_file.h"

namespace spindrift::io {

namespace {

// stbi_write_png_to_func hands the encoded file over in pieces.
void appendToString(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

}  // namespace

void writePng(const std::filesystem::path& path, const Frame& frame) {
    const std::size_t expected = std::size_t{frame.width} * frame.height * 4;
    if (frame.width == 0 || frame.height == 0 || frame.rgba.size() != expected) {
        throw Error(fmt::format("cannot write '{}': a {} x {} frame needs {} bytes of RGBA, got {}", path.string(),
                                frame.width, frame.height, expected, frame.rgba.size()));
    }
    // stb takes int sizes and an int row stride.
    if (frame.width > INT_MAX / 4 || frame.height > INT_MAX) {
        throw Error(
            fmt::format("cannot write '{}': {} x {} is too large for a PNG", path.string(), frame.width, frame.height));
    }
    // Encoded in memory first, so the file itself goes through AtomicFile.
    std::string encoded;
    const int width = static_cast<int>(frame.width);
    if (stbi_write_png_to_func(&appendToString, &encoded, width, static_cast<int>(frame.height), 4, frame.rgba.data(),
                               width * 4) == 0) {
        throw Error(fmt::format("cannot encode '{}' as PNG", path.string()));
    }
    AtomicFile file(path);
    file.stream().write(encoded.data(), static_cast<std::streamsize>(encoded.size()));
    file.commit();
}

}  // namespace spindrift::io
