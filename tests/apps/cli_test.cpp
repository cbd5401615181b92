// The command line tool, run as a separate process the way users run it.
#include <spindrift/scene.h>

#include <stb/stb_image.h>

#include "apps/app_test_util.h"
#include "io/csv_check.h"
#include "io/ply_check.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
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
                         "run x.toml --out ''",  // wrote nothing and exited 0 (issue 14)
                         "render x.toml --out ''",
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

[[light]]
name = "glow"
emitter = "flames"
[[light]]
name = "lamp"
)");
    const Result r = cli("validate " + quoted(scene));
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.out, scene.string() + ": ok (emitters: 1, forces: 0, colliders: 0, fluids: 2, jets: 3, bodies: 3, "
                                      "joints: 1, fires: 1, lights: 2)\n");
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

// run: rigid bodies --------------------------------------------------------------------------

/// A ball dropped from rest far from anything, and a static body whose name
/// a CSV must quote, far below it.
const char* kFallingBallScene = R"(
[world]
body_gravity = [0.0, -9.81]

[run]
dt = 0.01
steps = 30

[[body]]
name = "ball"
position = [0.5, 10.0]
shape = [{ circle = 0.1 }]

[[body]]
name = "ground, far below"
type = "static"
position = [0.0, -100.0]
shape = [{ box = [1.0, 0.1] }]
)";

using Rows = std::vector<std::vector<std::string>>;
const std::vector<std::string> kBodyColumns{"step", "time", "id",  "name", "x",
                                            "y",    "angle", "vx", "vy",   "angular_velocity"};

float toFloat(const std::string& text) { return std::strtof(text.c_str(), nullptr); }

TEST_F(CliTest, RunWritesTheBodiesAtEveryCacheStepInFreeFall) {
    const fs::path scene = writeScene(dir(), "fall.toml", kFallingBallScene);
    const fs::path out = dir() / "cache";
    const Result r = cli("run " + quoted(scene) + " --every 10 --format csv,ply --quiet --out " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(fileNames(out), (std::vector<std::string>{"bodies_000010.csv", "bodies_000010.ply", "bodies_000020.csv",
                                                        "bodies_000020.ply", "bodies_000030.csv", "bodies_000030.ply",
                                                        "summary.json"}));
    const std::string json = readFile(out / "summary.json");
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(jsonQuery(json, "totals/cache_files"), "6");

    const double g = 9.81, dt = static_cast<double>(0.01f);
    for (int n : {10, 20, 30}) {
        char stem[32];
        std::snprintf(stem, sizeof stem, "bodies_%06d", n);
        const Rows rows = spindrift_test::readCsv(readFile(out / (std::string(stem) + ".csv")));
        ASSERT_EQ(rows.size(), 3u) << stem;
        EXPECT_EQ(rows[0], kBodyColumns);
        const std::vector<std::string>& ball = rows[1];
        const std::vector<std::string>& ground = rows[2];
        EXPECT_EQ(ball[0], std::to_string(n));
        // The state after n steps, at the time summary.json gives that step.
        EXPECT_EQ(ball[1], jsonQuery(json, "per_step/" + std::to_string(n - 1) + "/time"));
        EXPECT_EQ(ball[2], "1");
        EXPECT_EQ(ball[3], "ball");
        // From rest under g with Box2D's semi-implicit Euler (velocity first,
        // then position with the new velocity): v_n = -g n dt and
        // y_n = y0 - g dt^2 n (n + 1) / 2, not the continuous y0 - g t^2 / 2
        // (0.015 m higher at n = 30).
        const double vy = -g * dt * n, y = 10.0 - g * dt * dt * n * (n + 1) / 2.0;
        EXPECT_EQ(toFloat(ball[4]), 0.5f);
        EXPECT_NEAR(toFloat(ball[5]), y, 1e-4) << stem;
        EXPECT_EQ(toFloat(ball[6]), 0.0f);
        EXPECT_EQ(toFloat(ball[7]), 0.0f);
        EXPECT_NEAR(toFloat(ball[8]), vy, 1e-4) << stem;
        EXPECT_EQ(toFloat(ball[9]), 0.0f);
        EXPECT_EQ(ground[2], "2");
        EXPECT_EQ(ground[3], "ground, far below");
        EXPECT_EQ(toFloat(ground[5]), -100.0f) << "a static body stays put";

        // The PLY of the same step: a file a PLY reader takes, with the same values.
        const auto ply = spindrift_test::readPlyFile(readFile(out / (std::string(stem) + ".ply")));
        const auto& vertex = ply.element("vertex");
        ASSERT_EQ(vertex.count, 2u);
        const char* columns[] = {"x", "y", "angle", "vx", "vy", "angular_velocity"};
        for (std::size_t k = 0; k < 6; ++k) {
            for (std::size_t b = 0; b < 2; ++b) {
                EXPECT_EQ(static_cast<float>(vertex.values.at(columns[k])[b]), toFloat(rows[b + 1][4 + k]))
                    << stem << " body " << b + 1 << " " << columns[k];
            }
        }
        EXPECT_EQ(vertex.values.at("id"), (std::vector<double>{1, 2}));
        EXPECT_EQ(vertex.values.at("z"), (std::vector<double>{0, 0}));
    }
}

TEST_F(CliTest, RunLastBodiesRowIsTheSummarysFinalStateAndTheLibrarys) {
    const fs::path scene = writeScene(dir(), "fall.toml", kFallingBallScene);
    const fs::path out = dir() / "cache";
    const Result r = cli("run " + quoted(scene) + " --every 7 --quiet --out " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string json = readFile(out / "summary.json");
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(jsonQuery(json, "bodies/#"), "2");
    EXPECT_EQ(jsonQuery(json, "bodies/1"), "ground, far below");
    ASSERT_EQ(jsonQuery(json, "totals/final_bodies/#"), "2");

    // The same scene stepped through the library, as a program would.
    spindrift::SceneDef def = spindrift::loadScene(scene.string());
    const spindrift::WorldId world = spindrift::buildWorld(def);
    for (std::uint32_t i = 0; i < def.run.steps; ++i) spindrift::stepWorld(world, def.run.dt);
    const std::vector<spindrift::BodySnapshot> library = spindrift::readBodies(world);
    spindrift::destroyWorld(world);
    ASSERT_EQ(library.size(), 2u);

    // 30 steps every 7: the last step is written although 30 is no multiple of 7.
    const Rows rows = spindrift_test::readCsv(readFile(out / "bodies_000030.csv"));
    ASSERT_EQ(rows.size(), 3u);
    for (std::size_t b = 0; b < 2; ++b) {
        const std::vector<std::string>& row = rows[b + 1];
        const std::string at = "totals/final_bodies/" + std::to_string(b) + "/";
        EXPECT_EQ(row[0], "30");
        for (std::size_t k = 2; k < kBodyColumns.size(); ++k) {
            EXPECT_EQ(jsonQuery(json, at + kBodyColumns[k]), row[k]) << "body " << b + 1 << " " << kBodyColumns[k];
        }
        const spindrift::BodySnapshot& lib = library[b];
        EXPECT_EQ(row[2], std::to_string(lib.id.index));
        EXPECT_EQ(row[3], lib.name);
        const float values[] = {lib.position.x,       lib.position.y,       lib.angle,
                                lib.linearVelocity.x, lib.linearVelocity.y, lib.angularVelocity};
        for (std::size_t k = 0; k < 6; ++k) {
            EXPECT_EQ(std::bit_cast<std::uint32_t>(toFloat(row[4 + k])), std::bit_cast<std::uint32_t>(values[k]))
                << "body " << b + 1 << " " << kBodyColumns[4 + k] << ": csv " << row[4 + k] << ", library "
                << values[k];
        }
    }
    EXPECT_LT(toFloat(rows[1][5]), 9.6f) << "the ball has fallen";
}

TEST_F(CliTest, RunBodyCachesGiveWayToAnEmitterCalledBodies) {
    const fs::path scene = writeScene(dir(), "clash.toml", std::string(kFallingBallScene) + R"(
[[emitter]]
name = "bodies"
rate = 10
)");
    const fs::path out = dir() / "cache";
    const Result r = cli("run " + quoted(scene) + " --steps 2 --every 2 --quiet --out " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(fileNames(out),
              (std::vector<std::string>{"bodies_000002.csv", "rigid_bodies_000002.csv", "summary.json"}));
    EXPECT_EQ(readFile(out / "rigid_bodies_000002.csv").substr(0, 5), "step,");
    EXPECT_EQ(readFile(out / "bodies_000002.csv").substr(0, 2), "x,") << "the emitter keeps its name";
}

TEST_F(CliTest, RunWithoutBodiesWritesNoBodyFilesOrMembers) {
    const fs::path scene = writeScene(dir(), "drops.toml", "[[emitter]]\nname = \"drops\"\nrate = 10\n");
    const fs::path out = dir() / "cache";
    const Result r = cli("run " + quoted(scene) + " --steps 2 --format csv,ply --quiet --out " + quoted(out));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(fileNames(out), (std::vector<std::string>{"drops_000001.csv", "drops_000001.ply", "drops_000002.csv",
                                                        "drops_000002.ply", "summary.json"}));
    const std::string json = readFile(out / "summary.json");
    EXPECT_FALSE(jsonQuery(json, "bodies").has_value());
    EXPECT_FALSE(jsonQuery(json, "totals/final_bodies").has_value());
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
