// The command line tool, run as a separate process the way users run it.
#include <spindrift/scene.h>

#include <stb/stb_image.h>

#include "apps/app_test_util.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace spindrift_test {  // tests/io/json_check.cpp
std::string jsonError(std::string_view text);
std::optional<std::string> jsonQuery(std::string_view text, std::string_view path);
}  // namespace spindrift_test

namespace {

namespace fs = std::filesystem;
using spindrift_test::jsonError;
using spindrift_test::jsonQuery;

const fs::path kCli = SPINDRIFT_CLI_PATH;
const fs::path kFountain = fs::path(SPINDRIFT_SOURCE_DIR) / "scenes" / "fountain.toml";

using spindrift::test::quoted;
using spindrift::test::readFile;
using spindrift::test::Result;

/// A fresh directory per test, removed afterwards.
class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("spindrift-cli-" + std::to_string(::getpid()) + "-" + test->test_suite_name() + "-" + test->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "cwd");
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    /// Runs `spindrift ARGS` in dir/cwd, capturing both streams; `env` holds
    /// shell variable assignments for the command alone ("PATH=...").
    Result cli(const std::string& args, const std::string& env = "") {
        return spindrift::test::runCaptured(
            "cd " + quoted(dir_ / "cwd") + " && " + env + " " + quoted(kCli) + " " + args, dir_);
    }

    const fs::path& dir() const { return dir_; }

private:
    fs::path dir_;
};

std::vector<std::string> fileNames(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// Data rows of a CSV cache (lines after the header).
std::size_t csvRows(const fs::path& file) {
    const std::string text = readFile(file);
    const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    return lines == 0 ? 0 : lines - 1;
}

#define SKIP_WITHOUT_FOUNTAIN()                                                         \
    if (!fs::exists(kFountain)) GTEST_SKIP() << kFountain << " is not written yet"

// --version, usage --------------------------------------------------------------------

TEST_F(CliTest, VersionPrintsNameAndSemver) {
    const Result r = cli("--version");
    EXPECT_EQ(r.code, 0);
    EXPECT_TRUE(std::regex_match(r.out, std::regex(R"(spindrift \d+\.\d+\.\d+\n)"))) << r.out;
}

TEST_F(CliTest, BadUsageExitsWith2AndSaysWhy) {
    // Parsing fails before the scene is opened, so a missing scene is fine:
    // a parser that let these through would exit 1 instead.
    const char* bad[] = {"",
                         "frobnicate",
                         "run",
                         "run x.toml --steps abc",
                         "run x.toml --steps 0",
                         "run x.toml --steps -3",
                         "run x.toml --dt -1",
                         "run x.toml --dt nan",
                         "run x.toml --seconds inf",
                         "run x.toml --steps 5 --seconds 1",
                         "run x.toml --backend metal",
                         "run x.toml --out d --format csv,obj",
                         "run x.toml --every 5",
                         "run x.toml --out d --every 0",
                         "run x.toml --no-such-option",
                         "validate",
                         "render x.toml",
                         "render x.toml --out d --frames 0",
                         "render x.toml --out d --frames 3 --seconds 1",
                         "render x.toml --out d --format gif",
                         "render x.toml --out d --fluid-steps 8",
                         "render x.toml --out d --width 0",
                         "render x.toml --out d --fps nan"};
    for (const char* args : bad) {
        const Result r = cli(args);
        EXPECT_EQ(r.code, 2) << "spindrift " << args;
        EXPECT_FALSE(r.err.empty()) << "spindrift " << args;
    }
    EXPECT_TRUE(fs::is_empty(dir() / "cwd")) << "nothing may be written on a usage error";
}

// validate -------------------------------------------------------------------------------

TEST_F(CliTest, ValidateMissingFileFailsWithPath) {
    const fs::path missing = dir() / "no-such-scene.toml";
    const Result r = cli("validate " + quoted(missing));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST_F(CliTest, ValidateUnknownKeyReportsFileLineColumn) {
    const fs::path scene = dir() / "typo.toml";
    std::ofstream(scene) << "# a scene with a misspelt key\n"
                            "\n"
                            "  bogus_key = 1\n";
    const Result r = cli("validate " + quoted(scene));
    EXPECT_EQ(r.code, 1);
    const std::regex location(std::regex_replace(scene.string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
                              R"(:3:\d+: )");
    EXPECT_TRUE(std::regex_search(r.err, location)) << r.err;
    EXPECT_NE(r.err.find("bogus_key"), std::string::npos) << r.err;
}

TEST_F(CliTest, ValidateFountainCountsItsParts) {
    SKIP_WITHOUT_FOUNTAIN();
    const spindrift::SceneDef scene = spindrift::loadScene(kFountain.string());
    const Result r = cli("validate " + quoted(kFountain));
    EXPECT_EQ(r.code, 0) << r.err;
    std::ostringstream expected;
    expected << kFountain.string() << ": ok (emitters: " << scene.emitters.size()
             << ", forces: " << scene.forces.size() << ", colliders: " << scene.colliders.size() << ")\n";
    EXPECT_EQ(r.out, expected.str());
}

/// Writes `text` to DIR/name and returns the path.
fs::path writeScene(const fs::path& dir, const std::string& name, const std::string& text) {
    const fs::path path = dir / name;
    std::ofstream(path) << text;
    return path;
}

TEST_F(CliTest, ValidateCountsFluidsJetsBodiesJointsAndFires) {
    // Counted by hand: 2 fluids with 2 + 1 jets, 3 bodies, 1 joint, 1 fire.
    const fs::path scene = writeScene(dir(), "parts.toml", R"(
[[emitter]]
name = "flames"

[[fluid]]
name = "water"
dimension = 2
[[fluid.jet]]
position = [0, 1, 0]
[[fluid.jet]]
position = [1, 1, 0]
aim = [[0.0, 0.5]]

[[fluid]]
name = "oil"
dimension = 2
[[fluid.block]]
min = [0, 0, 0]
max = [0.2, 0.2, 0]
[[fluid.jet]]
position = [2, 1, 0]

[[body]]
name = "floor"
type = "static"
shape = [{ box = [2.0, 0.1] }]
[[body]]
name = "gate"
position = [1.0, 0.5]
shape = [{ box = [0.05, 0.4] }]
[[body]]
name = "log"
position = [2.0, 0.5]
shape = [{ circle = 0.1 }]

[[joint]]
name = "hinge"
kind = "revolute"
body_a = "floor"
body_b = "gate"
anchor = [1.0, 0.9]

[[fire]]
name = "bonfire"
body = "log"
flames = "flames"
)");
    const Result r = cli("validate " + quoted(scene));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, scene.string() + ": ok (emitters: 1, forces: 0, colliders: 0, fluids: 2, jets: 3, bodies: 3, "
                                      "joints: 1, fires: 1)\n");
}

TEST_F(CliTest, ValidateJetWithAimAndDirectionNamesBothAtTheSecond) {
    const fs::path scene = writeScene(dir(), "jet.toml",
                                      "[[fluid]]\nname = \"water\"\ndimension = 2\n\n[[fluid.jet]]\n"
                                      "position = [0, 1, 0]\naim = [[0.0, 0.5]]\ndirection = [1, 0, 0]\n");
    const Result r = cli("validate " + quoted(scene));
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(r.err.starts_with(scene.string() + ":8:1: fluid[0].jet[0].direction: ")) << r.err;
    EXPECT_NE(r.err.find("`direction`"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("`aim`"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

// run -----------------------------------------------------------------------------------------

TEST_F(CliTest, RunFountainWritesCachesAndSummary) {
    SKIP_WITHOUT_FOUNTAIN();
    const spindrift::SceneDef scene = spindrift::loadScene(kFountain.string());
    const fs::path out = dir() / "cache";
    const Result r = cli("run " + quoted(kFountain) + " --steps 20 --every 10 --out " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;

    std::vector<std::string> expected{"summary.json"};
    for (const auto& e : scene.emitters) {
        ASSERT_TRUE(std::regex_match(e.name, std::regex("[A-Za-z0-9_-]+"))) << "test assumes plain names";
        expected.push_back(e.name + "_000010.csv");
        expected.push_back(e.name + "_000020.csv");
    }
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(fileNames(out), expected);

    const std::string json = readFile(out / "summary.json");
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(jsonQuery(json, "steps"), "20");
    EXPECT_EQ(jsonQuery(json, "per_step/#"), "20");
    EXPECT_EQ(jsonQuery(json, "per_step/19/step"), "20");
    EXPECT_EQ(jsonQuery(json, "totals/cache_files"), std::to_string(2 * scene.emitters.size()));

    // "alive" counts state-preserving particles; stateless ones are not stored.
    std::size_t rows = 0;
    for (const auto& e : scene.emitters) {
        if (!e.stateless) rows += csvRows(out / (e.name + "_000020.csv"));
    }
    EXPECT_EQ(jsonQuery(json, "per_step/19/alive"), std::to_string(rows));
    EXPECT_GT(rows, 0u) << "a fountain should have particles after 20 steps";
    EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(^20 steps, .* )" + std::to_string(rows) +
                                                    R"( alive, )" + std::to_string(expected.size()) +
                                                    R"( files written)")))
        << r.out;
}

TEST_F(CliTest, RunSecondsBecomeStepsAndLastStepIsAlwaysWritten) {
    SKIP_WITHOUT_FOUNTAIN();
    const fs::path out = dir() / "cache";
    // 0.1 s at 0.01 s is 10 steps; --every 4 writes after 4, 8 and the last, 10.
    const Result r = cli("run " + quoted(kFountain) + " --seconds 0.1 --dt 0.01 --every 4 --quiet --out " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string json = readFile(out / "summary.json");
    EXPECT_EQ(jsonQuery(json, "steps"), "10");
    EXPECT_EQ(jsonQuery(json, "dt"), "0.01");
    std::set<std::string> steps;
    for (const std::string& name : fileNames(out)) {
        if (name.ends_with(".csv")) steps.insert(name.substr(name.size() - 10, 6));
    }
    EXPECT_EQ(steps, (std::set<std::string>{"000004", "000008", "000010"}));
    EXPECT_EQ(r.err, "");
}

TEST_F(CliTest, RunWritesPlyWithTheSameParticlesAsCsv) {
    SKIP_WITHOUT_FOUNTAIN();
    const spindrift::SceneDef scene = spindrift::loadScene(kFountain.string());
    const fs::path out = dir() / "cache";
    const Result r = cli("run " + quoted(kFountain) + " --steps 12 --every 12 --format ply,csv -o " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;
    for (const auto& e : scene.emitters) {
        const std::string ply = readFile(out / (e.name + "_000012.ply"));
        ASSERT_EQ(ply.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
        const std::string vertices = "element vertex " + std::to_string(csvRows(out / (e.name + "_000012.csv"))) + "\n";
        EXPECT_NE(ply.find(vertices), std::string::npos) << e.name;
    }
}

TEST_F(CliTest, RunWithoutOutWritesNothing) {
    SKIP_WITHOUT_FOUNTAIN();
    const Result r = cli("run " + quoted(kFountain) + " --steps 5");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::is_empty(dir() / "cwd"));
    EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(^5 steps, .* 0 files written\n$)"))) << r.out;
}

TEST_F(CliTest, RunBadSceneExits1) {
    const fs::path scene = dir() / "typo.toml";
    std::ofstream(scene) << "bogus_key = 1\n";
    const Result r = cli("run " + quoted(scene) + " --steps 3 --out " + quoted(dir() / "cache"));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(scene.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir() / "cache")) << "a rejected scene must not create the output";
}

TEST_F(CliTest, RunOnVulkanFailsCleanlyOrWorks) {
    SKIP_WITHOUT_FOUNTAIN();
    const fs::path out = dir() / "cache";
    const Result r = cli("run " + quoted(kFountain) + " --steps 2 --backend vulkan --out " + quoted(out));
    ASSERT_TRUE(r.code == 0 || r.code == 1) << "exit " << r.code << " (-1: killed by a signal)\n" << r.err;
    if (r.code == 1) {
        EXPECT_TRUE(r.err.starts_with("error: ")) << r.err;
        EXPECT_FALSE(fs::exists(out)) << "a world that could not be built must not create the output";
    } else {
        EXPECT_TRUE(fs::exists(out / "summary.json"));
    }
}

// render ----------------------------------------------------------------------------------------

/// A quick scene: a few particles, 64 x 48, 0.25 s at 24 fps (6 frames).
const char* kSmallRenderScene = R"(
[run]
dt = 0.016666667

[render]
width = 64
height = 48
fps = 24
seconds = 0.25

[[emitter]]
name = "drops"
rate = 50
)";

/// Width and height of a PNG, or {0, 0} if it cannot be read.
std::pair<int, int> pngSize(const fs::path& file) {
    int w = 0, h = 0, channels = 0;
    if (stbi_info(file.c_str(), &w, &h, &channels) == 0) return {0, 0};
    return {w, h};
}

std::vector<std::string> pngNames(std::size_t count) {
    std::vector<std::string> names;
    for (std::size_t k = 0; k < count; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05zu.png", k);
        names.emplace_back(name);
    }
    return names;
}

class CliRenderTest : public CliTest {
protected:
    void SetUp() override {
        CliTest::SetUp();
        scene_ = dir() / "small.toml";
        std::ofstream(scene_) << kSmallRenderScene;
    }
    const fs::path& scene() const { return scene_; }

private:
    fs::path scene_;
};

TEST_F(CliRenderTest, WritesOnePngPerFrameAtTheRequestedSize) {
    const fs::path out = dir() / "frames";
    const Result r = cli("render " + quoted(scene()) + " --out " + quoted(out) +
                         " --format png --frames 5 --width 32 --height 24 --quiet");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(fileNames(out), pngNames(5));
    for (const std::string& name : pngNames(5)) EXPECT_EQ(pngSize(out / name), std::make_pair(32, 24)) << name;
    EXPECT_TRUE(r.out.starts_with("5 frames of 32x24 at 24 fps")) << r.out;
    EXPECT_NE(r.out.find((out / "frame_00000.png").string() + " .. frame_00004.png"), std::string::npos) << r.out;
    EXPECT_EQ(r.err, "");
}

TEST_F(CliRenderTest, SceneSecondsAndFpsGiveTheFrameCountAndTheSceneSize) {
    const fs::path out = dir() / "frames";
    // 0.25 s at 24 fps = 6 frames; frame 5 is at 5/24 s, after 12 steps of 1/60 s.
    const Result r = cli("render " + quoted(scene()) + " -o " + quoted(out) + " -f png");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(fileNames(out), pngNames(6));
    EXPECT_EQ(pngSize(out / "frame_00005.png"), std::make_pair(64, 48));
    EXPECT_NE(r.out.find("in 12 steps"), std::string::npos) << r.out;
}

TEST_F(CliRenderTest, WithoutFfmpegWritesPngFramesAndSaysSo) {
    const fs::path out = dir() / "video";
    // An empty directory as the whole PATH: no ffmpeg to be found.
    fs::create_directories(dir() / "empty-bin");
    const Result r = cli("render " + quoted(scene()) + " --out " + quoted(out) + " --format mp4 --frames 3",
                         "PATH=" + quoted(dir() / "empty-bin"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("ffmpeg not found: writing PNG frames only; install it with tools/install-deps.sh"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(fileNames(out), pngNames(3));
}

TEST_F(CliRenderTest, Mp4HasEveryFrameAtTheRequestedSize) {
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg is not installed";
    if (std::system("command -v ffprobe >/dev/null 2>&1") != 0) GTEST_SKIP() << "ffprobe is not installed";
    const fs::path out = dir() / "video";
    const Result r = cli("render " + quoted(scene()) + " --out " + quoted(out) + " --frames 6 --quiet");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(fileNames(out), std::vector<std::string>{"small.mp4"}) << "the default is the video alone";
    const fs::path probeOut = dir() / "probe.txt";
    const std::string probe = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                              "stream=width,height,nb_read_frames -of csv=p=0 " +
                              quoted(out / "small.mp4") + " >" + quoted(probeOut);
    ASSERT_EQ(std::system(probe.c_str()), 0);
    EXPECT_EQ(readFile(probeOut), "64,48,6\n");
    EXPECT_NE(r.out.find((out / "small.mp4").string()), std::string::npos) << r.out;
}

TEST_F(CliRenderTest, Mp4AndPngTogether) {
    if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg is not installed";
    const fs::path out = dir() / "both";
    const Result r = cli("render " + quoted(scene()) + " --out " + quoted(out) + " --format png,mp4 --frames 2 -q");
    ASSERT_EQ(r.code, 0) << r.err;
    std::vector<std::string> expected = pngNames(2);
    expected.push_back("small.mp4");
    EXPECT_EQ(fileNames(out), expected);
}

TEST_F(CliRenderTest, BadRenderKeyExits1WithItsPositionAndWritesNothing) {
    const fs::path bad = dir() / "bad.toml";
    std::ofstream(bad) << "[render]\nwidth = 64\nfps = -5\n";
    const fs::path out = dir() / "frames";
    const Result r = cli("render " + quoted(bad) + " --out " + quoted(out));
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(bad.string() + ":3:7: render.fps: "), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliRenderTest, UnwritableOutputDirectoryExits1) {
    const fs::path file = dir() / "a-file";
    std::ofstream(file) << "not a directory\n";
    const Result r = cli("render " + quoted(scene()) + " --out " + quoted(file / "frames") + " --format png");
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(r.err.starts_with("error: cannot create output directory")) << r.err;
}

}  // namespace
