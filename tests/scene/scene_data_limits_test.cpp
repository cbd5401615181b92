// Hostile data paths (issue 14): a `file`, `image` or `texture` (and the
// scene itself) must be a regular file within a size limit. /dev/zero used to
// be read until memory ran out and end in std::bad_alloc with no location;
// now it is refused before a byte is read, at the key that named it.
#include <spindrift/scene.h>

#include "scene/limits.h"
#include "scene/scene_error_expect.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace {

using spindrift::SceneError;
using spindrift::test::expectError;
namespace scene = spindrift::scene;

// A fresh directory per test and process: ctest runs tests in parallel.
class SceneDataLimits : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() /
               (std::string("spindrift-") + info->test_suite_name() + "-" + info->name() + "-" +
                std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::filesystem::path dir_;
};

// Each key that names a data file, on /dev/zero and /dev/urandom (endless
// character devices). The time bound is generous (reading stopped at once
// takes microseconds; the old loop ran until memory ran out).
TEST(SceneDataLimitsDevices, EndlessDevicesAreRefusedAtTheKey) {
    const auto start = std::chrono::steady_clock::now();
    for (const std::string device : {"/dev/zero", "/dev/urandom"}) {
        expectError("[[flow_field]]\nname = \"f\"\nfile = \"" + device + "\"\n",
                    {3, 8, "flow_field[0].file", "not a regular file"});
        expectError("[[collider]]\nname = \"c\"\nkind = \"cube_map\"\ncenter = [0, 0, 0]\nfile = \"" + device +
                        "\"\n",
                    {5, 8, "collider[0].file", "not a regular file"});
        expectError("[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\nimage = \"" + device +
                        "\"\n",
                    {5, 9, "collider[0].image", "not a regular file"});
        expectError("[[emitter]]\nname = \"e\"\nsprite = { texture = \"" + device + "\" }\n",
                    {3, 22, "emitter[0].sprite.texture", "not a regular file"});
        expectError("[render.background]\nkind = \"image\"\nimage = \"" + device + "\"\n",
                    {3, 9, "render.background.image", "not a regular file"});
        try {
            spindrift::loadScene(device);
            ADD_FAILURE() << "loaded " << device << " as a scene";
        } catch (const SceneError& err) {
            EXPECT_EQ(err.file(), device);
            EXPECT_NE(err.message().find("not a regular file"), std::string::npos) << err.what();
        }
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
}

// A FIFO with no writer: opening it must not wait (the test would hang).
TEST_F(SceneDataLimits, FifoIsRefusedWithoutWaiting) {
    const std::filesystem::path fifo = dir_ / "f.flow";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    expectError("[[flow_field]]\nname = \"f\"\nfile = \"f.flow\"\n",
                {3, 8, "flow_field[0].file", "not a regular file"}, dir_.string());
}

// Sparse files one byte over each limit (no disk space used): refused from
// their size, before reading; at the limit the content is read (and here is
// refused for what it holds, zero bytes, which is not a size error).
TEST_F(SceneDataLimits, DataFileOverTheSizeLimitIsRefused) {
    const std::filesystem::path flow = dir_ / "f.flow";
    std::ofstream(flow).put('#');
    std::filesystem::resize_file(flow, scene::kMaxDataFileBytes + 1);
    expectError("[[flow_field]]\nname = \"f\"\nfile = \"f.flow\"\n",
                {3, 8, "flow_field[0].file", "is 268435457 bytes, more than the limit of 268435456"},
                dir_.string());
}

TEST_F(SceneDataLimits, SceneFileOverTheSizeLimitIsRefused) {
    const std::filesystem::path path = dir_ / "big.toml";
    std::ofstream(path).put('#');
    std::filesystem::resize_file(path, scene::kMaxSceneBytes + 1);
    try {
        spindrift::loadScene(path.string());
        FAIL() << "loaded a scene over the size limit";
    } catch (const SceneError& err) {
        EXPECT_EQ(err.file(), path.string());
        EXPECT_NE(err.message().find("is 16777217 bytes, more than the limit of 16777216"), std::string::npos)
            << err.what();
    }
}

// A NUL escape in a path used to be cut at the NUL by the system:
// "data/rock.cube\u0000.txt" opened data/rock.cube, and the error about
// "data/swirl.flow\u0000.txt" printed no further than the NUL. Now every
// string with a NUL is refused at its value, and the message shows the NUL
// as an escape (what() has no NUL in it).
TEST(SceneDataLimitsNul, NulInAPathIsRefusedAtTheValue) {
    const std::string flow = "[[flow_field]]\nname = \"f\"\nfile = \"data/swirl.flow\\u0000.txt\"\n";
    expectError(flow, {3, 8, "flow_field[0].file", "without NUL"}, SPINDRIFT_SOURCE_DIR "/scenes");
    const std::string cube =
        "[[collider]]\nname = \"c\"\nkind = \"cube_map\"\ncenter = [0, 0, 0]\nfile = \"data/rock.cube\\u0000.txt\"\n";
    expectError(cube, {5, 8, "collider[0].file", "without NUL"}, SPINDRIFT_SOURCE_DIR "/scenes");
    try {
        spindrift::parseScene(flow, "bad.toml", SPINDRIFT_SOURCE_DIR "/scenes");
        FAIL() << "accepted a NUL in a path";
    } catch (const SceneError& err) {
        const std::string what = err.what();
        EXPECT_EQ(what.find('\0'), std::string::npos);
        EXPECT_NE(what.find("got \"data/swirl.flow\\u0000.txt\""), std::string::npos) << what;
    }
    // Without the NUL the same scene reads: the refusal is the NUL's.
    EXPECT_NO_THROW(spindrift::parseScene("[[flow_field]]\nname = \"f\"\nfile = \"data/swirl.flow\"\n", "ok.toml",
                                          SPINDRIFT_SOURCE_DIR "/scenes"));
}

TEST(SceneDataLimitsNul, NulInANameIsRefusedAtTheValue) {
    expectError("[[emitter]]\nname = \"a\\u0000b\"\n", {2, 8, "emitter[0].name", "without NUL"});
}

// A PNG's size is checked from its header, before decoding: a header that
// says 20000 x 20000 (what stb_image would decode to 400 MB, or 1.6 GB as
// RGBA) and holds no pixels at all is refused for its size, which only the
// header can have told. At most 16384 a side for textures and backgrounds
// (render_rules::kMaxImageSide), 4096 for height maps (kTerrainMaxAxis).
std::string pngHeader(std::uint32_t width, std::uint32_t height) {
    std::string png("\x89PNG\r\n\x1a\n", 8);
    const auto be32 = [&](std::uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8) png.push_back(static_cast<char>((v >> shift) & 0xFF));
    };
    be32(13);
    png += "IHDR";
    be32(width);
    be32(height);
    png += std::string("\x08\x00\x00\x00\x00", 5);  // 8-bit grey, deflate, no filter, no interlace
    be32(0);                                             // CRC: stb_image does not check it
    return png;
}

TEST_F(SceneDataLimits, PngSizeIsCheckedFromItsHeaderBeforeDecoding) {
    std::ofstream(dir_ / "big.png", std::ios::binary) << pngHeader(20000, 20000);
    std::ofstream(dir_ / "tall.png", std::ios::binary) << pngHeader(2, 5000);
    expectError("[[emitter]]\nname = \"e\"\nsprite = { texture = \"big.png\" }\n",
                {3, 22, "emitter[0].sprite.texture", "20000 x 20000 pixels; at most 16384 a side"}, dir_.string());
    expectError("[render.background]\nkind = \"image\"\nimage = \"big.png\"\n",
                {3, 9, "render.background.image", "at most 16384 a side"}, dir_.string());
    expectError("[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\nimage = \"tall.png\"\n",
                {5, 9, "collider[0].image", "2 x 5000 pixels; at most 4096 a side"}, dir_.string());
}

// Names that are empty or only blanks name nothing anyone can see; refused
// at the value, for every kind of object.
TEST(SceneNames, BlankNamesAreRefusedAtTheValue) {
    expectError("[[emitter]]\nname = \"  \\t \"\n", {2, 8, "emitter[0].name", "visible character"});
    expectError("[[emitter]]\nname = \"\"\n", {2, 8, "emitter[0].name", "non-empty string"});
    expectError("[[force]]\nname = \"\\n\"\nkind = \"gravity\"\n", {2, 8, "force[0].name", "visible character"});
    expectError("[[collider]]\nname = \" \"\nkind = \"plane\"\n", {2, 8, "collider[0].name", "visible character"});
    expectError("[[body]]\nname = \" \"\n", {2, 8, "body[0].name", "visible character"});
    // A name with blanks around a visible character is a name.
    EXPECT_NO_THROW(spindrift::parseScene("[[force]]\nname = \" g \"\nkind = \"gravity\"\n", "ok.toml", "."));
}

// Found by the 3,000-mutant campaign: a fluid capacity smaller than its
// blocks passed validation and failed in createFluid without a location.
// 0.6 m x 1.2 m at 2 cm is 30 x 60 = 1800 particles.
TEST(SceneFluidCapacity, ACapacityUnderTheBlocksIsRefusedAtTheKey) {
    const std::string fluid = "[[fluid]]\nname = \"water\"\ncapacity = {}\nspacing = 0.02\n"
                              "[[fluid.block]]\nmin = [0.0, 0.0, 0.0]\nmax = [0.6, 1.2, 0.0]\n";
    const auto withCapacity = [&](int n) {
        std::string text = fluid;
        return text.replace(text.find("{}"), 2, std::to_string(n));
    };
    expectError(withCapacity(1), {3, 12, "fluid[0].capacity", "room for the blocks' 1800 particles"});
    expectError(withCapacity(1799), {3, 12, "fluid[0].capacity", "got 1799"});
    EXPECT_NO_THROW(spindrift::parseScene(withCapacity(1800), "ok.toml", "."));
}

}  // namespace
