// [[fluid]] in scene files: parsed values, errors pointing at the line, and the
// command line's caches and summary for a fluid scene.
#include <spindrift/scene.h>
#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

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
relaxation = 1.1
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
vertices = [[2.0, 0.0], [3.0, 0.0], [2.5, 0.5]]  # beside the block, not under it
)",
                                  "inline.toml");
    ASSERT_EQ(s.fluids.size(), 1u);
    const FluidDef& f = s.fluids[0];
    EXPECT_EQ(f.dimension, 3u);
    EXPECT_FLOAT_EQ(f.smoothing, 0.1f);
    EXPECT_EQ(f.iterations, 8u);
    EXPECT_FLOAT_EQ(f.relaxation, 1.1f);
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

/// The line and message of the SceneError that a fluid with `key` (one
/// line, the file's third) and a block gives.
std::pair<int, std::string> errorAtKey(const std::string& key) {
    try {
        parseScene("[[fluid]]\nname = \"w\"\n" + key + "\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [1, 1, 0]\n",
                   "bad.toml");
    } catch (const SceneError& e) {
        return {e.line(), e.what()};
    }
    return {0, "no SceneError"};
}

TEST(FluidScene, ErrorsPointAtTheLine) {
    const auto iterations = errorAtKey("iterations = 40");
    EXPECT_EQ(iterations.first, 3) << iterations.second;
    EXPECT_NE(iterations.second.find("bad.toml:3:"), std::string::npos) << iterations.second;
    EXPECT_EQ(errorAtKey("solver = \"fast\"").first, 3);
    // Below kFluidMinBaumgarte a crushed splash can blow up (docs/fluid.md):
    // refused at its line, with the range.
    const auto baumgarte = errorAtKey("baumgarte = 0");
    EXPECT_EQ(baumgarte.first, 3) << baumgarte.second;
    EXPECT_NE(baumgarte.second.find("[0.01, 1]"), std::string::npos) << baumgarte.second;
    // Over-relaxation past 1.5 overshoots (docs/fluid.md): refused with the range.
    const auto relaxation = errorAtKey("relaxation = 1.9");
    EXPECT_EQ(relaxation.first, 3) << relaxation.second;
    EXPECT_NE(relaxation.second.find("[1, 1.5]"), std::string::npos) << relaxation.second;
    // A polygon that is not convex: reported at the fluid's table.
    EXPECT_THROW(parseScene("[[fluid]]\nname = \"w\"\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [1, 1, 0]\n"
                            "[[fluid.polygon]]\nvertices = [[0, 0], [1, 0], [0.2, 0.2], [0, 1]]\n",
                            "bad.toml"),
                 SceneError);
}

// A block laid into a wall would be crushed out of it at the first step
// (issue 14: a fuzzer's 19,800 particles pressed into a 1.2 m channel took
// 1.5 s a step), so it is refused at the block. 2D, spacing 0.1 m, block
// [0, 1.5] x [0, 0.5]: particles at x = 0.05 ... 1.45 (15 columns) and 5 rows;
// the wall x = 1 (solid beyond) holds the columns at 1.05 ... 1.45, 5 x 5 = 25
// of 75. Up to the wall (max x = 1) the last column sits 0.05 m clear.
TEST(FluidScene, BlockInsideASolidIsRefusedAtTheBlock) {
    const std::string wall = "[[collider]]\nname = \"right\"\nkind = \"plane\"\npoint = [1, 0, 0]\n"
                             "normal = [-1, 0, 0]\n";
    auto fluid = [](const char* maxX) {
        return std::string("[[fluid]]\nname = \"w\"\nspacing = 0.1\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [") +
               maxX + ", 0.5, 0]\n";
    };
    EXPECT_NO_THROW(parseScene(wall + fluid("1.0"), "ok.toml"));
    try {
        parseScene(wall + fluid("1.5"), "bad.toml");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.line(), 10);  // the block's `min`
        EXPECT_NE(std::string(e.what()).find("25 of the block's 75 particles"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("collider 'right'"), std::string::npos) << e.what();
    }
    // The fluid's own polygons are solids too: a triangle over the block's corner.
    try {
        parseScene(fluid("1.0") + "[[fluid.polygon]]\nvertices = [[-1, -1], [1.5, -1], [-1, 1.5]]\n", "bad.toml");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("polygon[0]"), std::string::npos) << e.what();
    }
    // The public API refuses the same block, in createFluid and addFluidBlock.
    const WorldId world = createWorld(WorldDef{});
    ColliderDef plane;
    plane.name = "right";
    plane.kind = ColliderKind::Plane;
    plane.position = {1.0f, 0.0f, 0.0f};
    plane.normal = {-1.0f, 0.0f, 0.0f};
    createCollider(world, plane);
    FluidDef def;
    def.spacing = 0.1f;
    def.blocks.push_back(FluidBlockDef{{0.0f, 0.0f, 0.0f}, {1.5f, 0.5f, 0.0f}, {0.0f, 0.0f, 0.0f}});
    EXPECT_THROW(createFluid(world, def), FieldError);
    def.blocks[0].max.x = 1.0f;
    const FluidId id = createFluid(world, def);
    EXPECT_THROW(addFluidBlock(world, id, FluidBlockDef{{0.5f, 1.0f, 0.0f}, {1.5f, 1.5f, 0.0f}, {}}), FieldError);
    destroyWorld(world);
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
