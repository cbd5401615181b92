// Scenes rendered by `spindrift render`, as users run it, compared to
// committed reference images: a frame passes when at most 1 % of its pixels
// differ from the reference by more than 8/255 in any channel. The margin
// absorbs what may legitimately differ between machines (lavapipe's vector
// width and fused multiply-adds shift edges by a pixel and colours by a code
// or two); a change of what is drawn moves far more.
//
// The references are reviewed pictures, not outputs copied blindly: after a
// deliberate change to the renderer or a scene, look at the new frames and
// refresh them with
//   SPINDRIFT_UPDATE_REFERENCES=1 build/release/spindrift_tests --gtest_filter='ReferenceImages*'
// then check the PNGs in tests/render/references/ before committing them.
// Each scene also runs on the Vulkan backend against the same reference (its
// particles differ from the CPU's by rounding only).
#include <gtest/gtest.h>

#include <stb/stb_image.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

namespace {

namespace fs = std::filesystem;

struct ReferenceCase {
    const char* scene;   // scene file, relative to the source tree; the reference is named after its stem
    double start;        // s: the moment shown
    const char* backend;
    const char* options = "";  // more `spindrift render` options
    const char* suffix = "";   // of the reference's name, for a case with options
};

struct Image {
    int width = 0, height = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> pixels{nullptr, stbi_image_free};
};

Image readPng(const fs::path& path) {
    Image image;
    int channels = 0;
    image.pixels.reset(stbi_load(path.string().c_str(), &image.width, &image.height, &channels, 4));
    return image;
}

// Pixels with a channel more than `threshold` codes away.
std::size_t differingPixels(const Image& a, const Image& b, int threshold) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < std::size_t(a.width) * a.height; ++i) {
        for (int c = 0; c < 4; ++c) {
            if (std::abs(int(a.pixels.get()[4 * i + c]) - int(b.pixels.get()[4 * i + c])) > threshold) {
                ++count;
                break;
            }
        }
    }
    return count;
}

std::string stem(const ReferenceCase& c) { return fs::path(c.scene).stem().string() + c.suffix; }

class ReferenceImages : public ::testing::TestWithParam<ReferenceCase> {};

TEST_P(ReferenceImages, FrameMatchesTheReviewedReference) {
    const ReferenceCase& c = GetParam();
    const fs::path source = SPINDRIFT_SOURCE_DIR;
    const fs::path out = fs::temp_directory_path() /
                         ("spindrift-reference-" + std::to_string(::getpid()) + "-" + stem(c) + "-" + c.backend);
    fs::remove_all(out);
    const std::string command = "SPINDRIFT_VULKAN_VALIDATION=1 '" + std::string(SPINDRIFT_CLI_PATH) + "' render '" +
                                (source / c.scene).string() + "' --out '" +
                                out.string() + "' --start " + std::to_string(c.start) +
                                " --frames 1 --format png --width 160 --height 90 --quiet --backend " + c.backend +
                                " " + c.options +
                                " > '" + out.string() + ".log' 2>&1";
    const int status = std::system(command.c_str());
    ASSERT_TRUE(status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0)
        << command << "\nfailed (non-zero also when validation reported messages); see " << out << ".log";
    const fs::path frame = out / "frame_00000.png";
    const fs::path reference = source / "tests" / "render" / "references" / (stem(c) + ".png");
    if (std::getenv("SPINDRIFT_UPDATE_REFERENCES") != nullptr && std::string(c.backend) == "cpu") {
        fs::copy_file(frame, reference, fs::copy_options::overwrite_existing);
        GTEST_SKIP() << "reference updated: " << reference << " (look at it before committing)";
    }
    Image got = readPng(frame), want = readPng(reference);
    ASSERT_TRUE(want.pixels) << "no reference " << reference << "; make it with SPINDRIFT_UPDATE_REFERENCES=1";
    ASSERT_TRUE(got.pixels) << "cannot read " << frame;
    ASSERT_EQ(got.width, want.width);
    ASSERT_EQ(got.height, want.height);
    const std::size_t differing = differingPixels(got, want, 8);
    EXPECT_LE(differing, std::size_t(got.width) * got.height / 100)
        << differing << " pixels differ by more than 8/255; the frame is kept in " << out;
    if (differing <= std::size_t(got.width) * got.height / 100) {
        fs::remove_all(out);
        fs::remove(out.string() + ".log");
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ReferenceImages,
                         ::testing::Values(ReferenceCase{"scenes/fluid_splash.toml", 1.0, "cpu"},
                                           // Sprinkle's seven splat steps, the other style.
                                           ReferenceCase{"scenes/fluid_splash.toml", 1.0, "cpu", "--fluid-steps 7",
                                                         "_splats"},
                                           ReferenceCase{"scenes/fluid_dam_break_2d.toml", 1.0, "cpu"},
                                           // The 2D liquid surface close up: 3.5 pixels a spacing.
                                           ReferenceCase{"tests/render/scenes/fluid_dam_break_closeup.toml", 1.0,
                                                         "cpu"},
                                           // The showcase at night, lit by its fires: the cannon on the
                                           // crate (3 s), the gate open and the barrel fire (8 s).
                                           ReferenceCase{"scenes/showcase.toml", 3.0, "cpu", "", "_3s"},
                                           ReferenceCase{"scenes/showcase.toml", 8.0, "cpu", "", "_8s"},
                                           // The 3D screen-space liquid.
                                           ReferenceCase{"scenes/fluid_dam_break_3d.toml", 1.0, "cpu"},
                                           ReferenceCase{"tests/render/scenes/effects_closeup.toml", 1.5, "cpu"},
                                           // A flipbook, soft particles and OIT smoke.
                                           ReferenceCase{"scenes/campfire.toml", 2.0, "cpu"},
                                           ReferenceCase{"scenes/campfire.toml", 2.0, "vulkan"},
                                           ReferenceCase{"tests/render/scenes/effects_closeup.toml", 1.5, "vulkan"}),
                         [](const auto& info) { return stem(info.param) + "_" + info.param.backend; });

}  // namespace
