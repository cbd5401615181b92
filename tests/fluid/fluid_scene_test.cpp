// [[fluid]] in scene files: parsed values, errors pointing at the line, and the
// command line's caches and summary for a fluid scene.
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>

namespace spindrift_test {  // tests/io/json_check.cpp
std::optional<std::string> jsonQuery(std::string_view text, std::string_view path);
}  // namespace spindrift_test

namespace spindrift {
namespace {

TEST(FluidScene, ParsesEveryKey) {
    const SceneDef s = parseScene(R"(
[[fluid]]
name = "water"
dimension = 3
spacing = 0.04
h = 0.1
iterations = 8
baumgarte = 0.2
warm_start = 0.3
split_impulse = false
max_neighbours = 64
solver = "sequential"
substeps = 2
gravity = [0.0, -5.0, 0.0]
friction = 0.1
capacity = 5000
[[fluid.block]]
min = [0.0, 0.0, 0.0]
max = [0.4, 0.4, 0.4]
velocity = [1.0, 0.0, 0.0]
[[fluid.jet]]
position = [0.0, 1.0, 0.0]
direction = [1.0, 0.0, 0.0]
speed = 2.0
rate = 100.0
radius = 0.05
duration = 1.0
[[fluid.polygon]]
vertices = [[0.0, 0.0], [1.0, 0.0], [0.5, 0.5]]
)",
                                  "inline.toml");
    ASSERT_EQ(s.fluids.size(), 1u);
    const FluidDef& f = s.fluids[0];
    EXPECT_EQ(f.dimension, 3u);
    EXPECT_FLOAT_EQ(f.smoothing, 0.1f);
    EXPECT_EQ(f.iterations, 8u);
    EXPECT_EQ(f.solver, FluidSolver::Sequential);
    EXPECT_EQ(f.substeps, 2u);
    EXPECT_FALSE(f.splitImpulse);
    EXPECT_EQ(f.capacity, 5000u);
    ASSERT_EQ(f.blocks.size(), 1u);
    EXPECT_EQ(f.blocks[0].velocity.x, 1.0f);
    ASSERT_EQ(f.jets.size(), 1u);
    EXPECT_FLOAT_EQ(f.jets[0].duration, 1.0f);
    ASSERT_EQ(f.polygons.size(), 1u);
    EXPECT_EQ(f.polygons[0].vertices.size(), 3u);
}

TEST(FluidScene, ErrorsPointAtTheLine) {
    try {
        parseScene("[[fluid]]\nname = \"w\"\niterations = 40\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [1, 1, 0]\n",
                   "bad.toml");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.line(), 3);
        EXPECT_NE(std::string(e.what()).find("bad.toml:3:"), std::string::npos) << e.what();
    }
    try {
        parseScene("[[fluid]]\nname = \"w\"\nsolver = \"fast\"\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [1, 1, 0]\n",
                   "bad.toml");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.line(), 3);
    }
    // A polygon that is not convex: reported at the fluid's table.
    EXPECT_THROW(parseScene("[[fluid]]\nname = \"w\"\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [1, 1, 0]\n"
                            "[[fluid.polygon]]\nvertices = [[0, 0], [1, 0], [0.2, 0.2], [0, 1]]\n",
                            "bad.toml"),
                 SceneError);
}

TEST(FluidScene, CliWritesDensityAndPressureColumnsAndStats) {
    const std::filesystem::path out = std::filesystem::temp_directory_path() / "spindrift_fluid_cli_test";
    std::filesystem::remove_all(out);
    const std::string command = std::string(SPINDRIFT_CLI_PATH) + " run " + SPINDRIFT_SOURCE_DIR +
                                "/scenes/fluid_tank.toml -q -n 5 -e 3 -o " + out.string() + " -f csv,ply > /dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0);
    std::ifstream csv(out / "water_000005.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header, "x,y,z,vx,vy,vz,density,pressure,id");
    EXPECT_TRUE(std::filesystem::exists(out / "water_000005.ply"));
    std::stringstream summary;
    summary << std::ifstream(out / "summary.json").rdbuf();
    for (const char* key : {"\"fluids\"", "\"mean_density_error\"", "\"max_density_error\"", "\"mean_neighbours\"",
                            "\"max_speed\"", "\"neighbour_overflows\""}) {
        EXPECT_NE(summary.str().find(key), std::string::npos) << key;
    }
    // The number-density ratio on the written frames (steps 3 and 5, not 4)
    // and in the totals: a tank 5 steps after release is still close to its lattice,
    // whose interior reads exactly 1 (more than half of its particles).
    const std::string json = summary.str();
    const auto median = spindrift_test::jsonQuery(json, "per_step/4/fluids/0/number_density_median");
    ASSERT_TRUE(median.has_value()) << json.substr(0, 2000);
    EXPECT_NEAR(std::strtod(median->c_str(), nullptr), 1.0, 0.03);
    EXPECT_EQ(spindrift_test::jsonQuery(json, "totals/fluids/0/final_number_density_median"), *median);
    EXPECT_TRUE(spindrift_test::jsonQuery(json, "per_step/4/fluids/0/number_density_p95").has_value());
    EXPECT_TRUE(spindrift_test::jsonQuery(json, "per_step/2/fluids/0/number_density_median").has_value());
    EXPECT_FALSE(spindrift_test::jsonQuery(json, "per_step/3/fluids/0/number_density_median").has_value());
    EXPECT_EQ(spindrift_test::jsonQuery(json, "totals/fluids/0/number_density_reference"), "45");
    std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace spindrift
