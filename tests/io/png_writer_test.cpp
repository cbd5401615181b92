// PNG frames: what is written reads back byte for byte, and failures leave
// no file behind.
#include "io/png_writer.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <string>

namespace {

namespace fs = std::filesystem;

fs::path scratchDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("spindrift-png-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

spindrift::Frame patternFrame(std::uint32_t width, std::uint32_t height) {
    spindrift::Frame frame{width, height, {}};
    frame.rgba.resize(std::size_t{width} * height * 4);
    // Every channel different and alpha not constant, so a swapped channel,
    // a flipped row order or a dropped alpha would show.
    for (std::size_t i = 0; i < frame.rgba.size(); ++i) frame.rgba[i] = static_cast<std::uint8_t>(i * 7 + i / 5);
    return frame;
}

TEST(IoPngWriter, RoundTripsExactly) {
    const fs::path dir = scratchDir("roundtrip");
    const spindrift::Frame frame = patternFrame(37, 23);  // odd sizes: no row padding assumed
    spindrift::io::writePng(dir / "f.png", frame);
    int w = 0, h = 0, channels = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load((dir / "f.png").c_str(), &w, &h, &channels, 4),
                                                     &stbi_image_free);
    ASSERT_NE(pixels, nullptr) << stbi_failure_reason();
    EXPECT_EQ(w, 37);
    EXPECT_EQ(h, 23);
    EXPECT_EQ(channels, 4);
    EXPECT_EQ(std::vector<std::uint8_t>(pixels.get(), pixels.get() + frame.rgba.size()), frame.rgba);
    EXPECT_FALSE(fs::exists(dir / "f.png.tmp"));
    fs::remove_all(dir);
}

TEST(IoPngWriter, RejectsAFrameWhosePixelsDoNotMatchItsSize) {
    const fs::path dir = scratchDir("mismatch");
    spindrift::Frame frame = patternFrame(8, 8);
    frame.rgba.pop_back();
    EXPECT_THROW(spindrift::io::writePng(dir / "f.png", frame), spindrift::Error);
    EXPECT_TRUE(fs::is_empty(dir));
    fs::remove_all(dir);
}

TEST(IoPngWriter, UnwritableDirectoryIsAnErrorNamingThePath) {
    const fs::path missing = fs::temp_directory_path() / "spindrift-png-no-such-dir" / "f.png";
    try {
        spindrift::io::writePng(missing, patternFrame(4, 4));
        FAIL() << "wrote into a missing directory";
    } catch (const spindrift::Error& e) {
        EXPECT_NE(std::string(e.what()).find("spindrift-png-no-such-dir"), std::string::npos) << e.what();
    }
}

}  // namespace
