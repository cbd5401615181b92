// Every kind of bad scene is rejected with the file, line, column and key path
// of the offending node and a message that says what was expected. Expected
// positions are counted by hand from the inline TOML (line 1 is the first
// line of the string; columns are 1-based).
#include <spindrift/scene.h>

#include "scene/scene_error_expect.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace {

using spindrift::SceneError;

using spindrift::test::expectError;

// A minimal valid emitter, to which tests append one bad line.
const std::string kEmitter = "[[emitter]]\nname = \"e\"\n";

TEST(SceneErrors, WhatReadsFileLineColumnKeyPathMessage) {
    try {
        spindrift::parseScene(kEmitter + "capacity = 0\n", "scenes/x.toml");
        FAIL() << "capacity 0 accepted";
    } catch (const SceneError& err) {
        EXPECT_STREQ(err.what(),
                     "scenes/x.toml:3:12: emitter[0].capacity: expected an integer in "
                     "[1, 16777216], got 0");
    }
}

TEST(SceneErrors, TomlSyntaxError) {
    // The second '=' on line 2 (column 8) cannot start a value.
    expectError("[world]\nseed = = 3\n", {2, 8, "", "TOML syntax error"});
}

TEST(SceneErrors, MissingCommaIsASyntaxError) {
    // "eye = [1, 2 3]": the 3 at column 13 is where a comma or ']' was due.
    expectError("[camera]\neye = [1, 2 3]\n", {2, 13, "", "TOML syntax error"});
}

TEST(SceneErrors, DuplicateTomlKeyIsASyntaxError) {
    // toml++ points at the value of the redefinition ("steps = 4": column 9).
    expectError("[run]\nsteps = 3\nsteps = 4\n", {3, 9, "", "TOML syntax error"});
}

TEST(SceneErrors, UnknownTopLevelTable) {
    expectError("[emiter]\nname = \"x\"\n", {1, 2, "emiter", "did you mean \"emitter\""});
}

TEST(SceneErrors, UnknownEmitterKeyWithSuggestion) {
    expectError(kEmitter + "capacty = 10\n",
                {3, 1, "emitter[0].capacty", "did you mean \"capacity\""});
}

// Scene files spell it `color` (as the bundled scenes do); `colour`, in keys
// and in the background's kind, is a typo with a hint, wherever it appears.
TEST(SceneErrors, ColourIsAMisspellingOfColor) {
    expectError(kEmitter + "colour = [1, 1, 1, 1]\n", {3, 1, "emitter[0].colour", "did you mean \"color\""});
    expectError(kEmitter + "colour_over_life = []\n",
                {3, 1, "emitter[0].colour_over_life", "did you mean \"color_over_life\""});
    expectError("[render.fluid]\ncolour = [1, 1, 1]\n", {2, 1, "render.fluid.colour", "did you mean \"color\""});
    expectError("[render.background]\nkind = \"color\"\ncolour = [1, 1, 1]\n",
                {3, 1, "render.background.colour", "did you mean \"color\""});
    expectError("[render.background]\nkind = \"colour\"\n",
                {2, 8, "render.background.kind", "did you mean \"color\""});
}

TEST(SceneErrors, UnknownKeyInNestedShapeTable) {
    expectError(kEmitter + "[emitter.shape]\nkind = \"sphere\"\nraduis = 1\n",
                {5, 1, "emitter[0].shape.raduis", "did you mean \"radius\""});
}

TEST(SceneErrors, UnknownKeyInInlineCurveKey) {
    expectError(kEmitter + "size_over_life = [{t = 0, valeu = 1}]\n",
                {3, 27, "emitter[0].size_over_life[0].valeu", "unknown key"});
}

TEST(SceneErrors, KeyOfAnotherForceKindIsUnknown) {
    // `position` means nothing to gravity: rejected, with the keys gravity knows.
    expectError("[[force]]\nname = \"g\"\nkind = \"gravity\"\nposition = [0, 0, 0]\n",
                {4, 1, "force[0].position", "acceleration"});
}

TEST(SceneErrors, CurlNoiseKeysOutOfRange) {
    const std::string noise = "[[force]]\nname = \"n\"\nkind = \"curl_noise\"\n";
    expectError(noise + "octaves = 5\n", {4, 11, "force[0].octaves", "expected an integer in [1, 4], got 5"});
    expectError(noise + "frequency = 0\n", {4, 13, "force[0].frequency", "expected a number > 0"});
    expectError(noise + "speed = -1\n", {4, 9, "force[0].speed", "expected a number >= 0"});
    expectError(noise + "strength = -2\n", {4, 12, "force[0].strength", "expected a number >= 0"});
    expectError(noise + "seed = -1\n", {4, 8, "force[0].seed", "expected an integer in [0, 4294967295]"});
    // A flow field's key means nothing to curl noise.
    expectError(noise + "field = \"f\"\n", {4, 1, "force[0].field", "frequency"});
}

TEST(SceneErrors, UnknownKeyFarFromAnyKnownListsTheKnownKeys) {
    expectError("[run]\nzzzzzz = 1\n", {2, 1, "run.zzzzzz", "expected one of: dt, steps"});
}

TEST(SceneErrors, WrongTypeStringForInteger) {
    expectError(
        kEmitter + "capacity = \"many\"\n",
        {3, 12, "emitter[0].capacity", "expected an integer in [1, 16777216], got \"many\""});
}

TEST(SceneErrors, WrongTypeFloatForInteger) {
    expectError(kEmitter + "capacity = 1e4\n", {3, 12, "emitter[0].capacity", "got 10000.0"});
}

TEST(SceneErrors, WrongTypeBoolForRange) {
    expectError(kEmitter + "speed = true\n", {3, 9, "emitter[0].speed", "got true"});
}

TEST(SceneErrors, WrongTypeTableExpected) {
    expectError("world = 3\n", {1, 9, "world", "expected a table"});
}

TEST(SceneErrors, SingleTableWhereArrayOfTablesExpected) {
    expectError("[emitter]\nname = \"e\"\n", {1, 1, "emitter", "[[emitter]]"});
}

TEST(SceneErrors, WrongVectorLength) {
    expectError("[camera]\neye = [1, 2]\n", {2, 7, "camera.eye", "expected an array of 3 numbers"});
}

TEST(SceneErrors, UnknownEnumName) {
    expectError("[world]\nbackend = \"gpu\"\n",
                {2, 11, "world.backend", "one of \"cpu\", \"vulkan\", \"auto\", got \"gpu\""});
}

TEST(SceneErrors, NegativeShapeRadius) {
    expectError(kEmitter + "[emitter.shape]\nkind = \"sphere\"\nradius = -1\n",
                {5, 10, "emitter[0].shape.radius", "expected a number >= 0, got -1"});
}

TEST(SceneErrors, CapacityAboveSixteenMillion) {
    expectError(kEmitter + "capacity = 16777217\n", {3, 12, "emitter[0].capacity", "16777216"});
}

TEST(SceneErrors, LifetimeMustBePositive) {
    expectError(kEmitter + "lifetime = [0, 1]\n",
                {3, 13, "emitter[0].lifetime[0]", "expected a number > 0, got 0"});
}

TEST(SceneErrors, MassMustBePositive) {
    expectError(kEmitter + "mass = 0.0\n", {3, 8, "emitter[0].mass", "> 0"});
}

TEST(SceneErrors, RateMustNotBeNegative) {
    expectError(kEmitter + "rate = -5\n", {3, 8, "emitter[0].rate", ">= 0, got -5"});
}

TEST(SceneErrors, RangeMinAboveMax) {
    expectError(kEmitter + "speed = [5, 2]\n", {3, 9, "emitter[0].speed", "min <= max"});
}

TEST(SceneErrors, ResilienceAboveOne) {
    expectError("[[collider]]\nname = \"c\"\nkind = \"plane\"\nresilience = 1.5\n",
                {4, 14, "collider[0].resilience", "in [0, 1], got 1.5"});
}

TEST(SceneErrors, FrictionBelowZero) {
    expectError("[[collider]]\nname = \"c\"\nkind = \"plane\"\nfriction = -0.1\n",
                {4, 12, "collider[0].friction", "in [0, 1]"});
}

TEST(SceneErrors, ZeroNormal) {
    expectError("[[collider]]\nname = \"c\"\nkind = \"plane\"\nnormal = [0, 0, 0]\n",
                {4, 10, "collider[0].normal", "non-zero"});
}

TEST(SceneErrors, TimeStepMustBePositive) {
    expectError("[run]\ndt = 0\n", {2, 6, "run.dt", "got 0"});
}

TEST(SceneErrors, LifeLossOutsideUnitInterval) {
    expectError(kEmitter + "[emitter.collision]\nlife_loss = 2\n",
                {4, 13, "emitter[0].collision.life_loss", "in [0, 1]"});
}

TEST(SceneErrors, SpreadAboveHalfTurn) {
    expectError(kEmitter + "shape = {kind = \"point\", spread = 200}\n",
                {3, 35, "emitter[0].shape.spread", "in [0, 3.1415927]"});
}

TEST(SceneErrors, NanNumber) {
    expectError(kEmitter + "rate = nan\n", {3, 8, "emitter[0].rate", "got nan"});
}

TEST(SceneErrors, NanInsideVector) {
    expectError("[camera]\neye = [0, nan, 1]\n", {2, 11, "camera.eye[1]", "got nan"});
}

TEST(SceneErrors, InfNumber) {
    expectError(kEmitter + "speed = [1, inf]\n", {3, 13, "emitter[0].speed[1]", "got inf"});
}

TEST(SceneErrors, NegativeInfNumber) {
    expectError("[[force]]\nname = \"g\"\nkind = \"gravity\"\nacceleration = [0, -inf, 0]\n",
                {4, 20, "force[0].acceleration[1]", "got -inf"});
}

TEST(SceneErrors, NumberBeyondSinglePrecision) {
    expectError("[camera]\northo_height = 1e300\n",
                {2, 16, "camera.ortho_height", "single precision"});
}

TEST(SceneErrors, UnknownForceReference) {
    expectError("[[force]]\nname = \"gravity\"\nkind = \"gravity\"\n" + kEmitter +
                    "forces = [\"gravity\", \"gravty\"]\n",
                {6, 22, "emitter[0].forces[1]", "unknown force \"gravty\""});
}

TEST(SceneErrors, UnknownColliderReference) {
    expectError(kEmitter + "collision = {colliders = [\"floor\"]}\n",
                {3, 27, "emitter[0].collision.colliders[0]", "unknown collider \"floor\""});
}

TEST(SceneErrors, UnknownFlowFieldReference) {
    expectError("[[force]]\nname = \"f\"\nkind = \"flow_field\"\nfield = \"smoke\"\n",
                {4, 9, "force[0].field", "unknown flow field \"smoke\""});
}

TEST(SceneErrors, EmptyReferenceListIsRefused) {
    expectError(kEmitter + "forces = []\n", {3, 10, "emitter[0].forces", "leave the key out"});
}

TEST(SceneErrors, DuplicateForceName) {
    expectError(
        "[[force]]\nname = \"g\"\nkind = \"gravity\"\n"
        "[[force]]\nname = \"g\"\nkind = \"damping\"\n",
        {5, 8, "force[1].name", "duplicate force name \"g\" (first used at line 2)"});
}

TEST(SceneErrors, DuplicateEmitterName) {
    expectError(kEmitter + kEmitter, {4, 8, "emitter[1].name", "duplicate emitter name"});
}

TEST(SceneErrors, MissingRequiredKeyPointsAtItsTable) {
    // A sphere collider without a radius: reported at the [[collider]] header.
    expectError("[world]\nseed = 2\n[[collider]]\nname = \"ball\"\nkind = \"sphere\"\n",
                {3, 1, "collider[0].radius", "required key is missing"});
}

TEST(SceneErrors, MissingName) {
    expectError("[[force]]\nkind = \"gravity\"\n", {1, 1, "force[0].name", "missing"});
}

TEST(SceneErrors, CurveKeysOutOfOrder) {
    expectError(kEmitter + "size_over_life = [{t = 0.5, value = 1}, {t = 0.2, value = 2}]\n",
                {3, 46, "emitter[0].size_over_life[1].t", "strictly increasing"});
}

TEST(SceneErrors, CurveKeyTimeOutsideUnitInterval) {
    expectError(kEmitter + "size_over_life = [{t = 1.5, value = 1}]\n",
                {3, 24, "emitter[0].size_over_life[0].t", "in [0, 1]"});
}

TEST(SceneErrors, CurveWithTooManyKeys) {
    std::string keys;
    for (int i = 0; i < 9; ++i) {
        keys += (i ? ", " : "") + std::string("{t = 0.") + std::to_string(i) + ", value = 1}";
    }
    expectError(kEmitter + "size_over_life = [" + keys + "]\n",
                {3, 18, "emitter[0].size_over_life", "at most 8 curve keys, got 9"});
}

TEST(SceneErrors, MoreThan32Colliders) {
    std::string text;
    for (int i = 0; i < 33; ++i) {
        text += "[[collider]]\nname = \"c" + std::to_string(i) + "\"\nkind = \"plane\"\n";
    }
    // The 33rd table starts on line 3 * 32 + 1.
    expectError(text, {97, 1, "collider[32]", "at most 32"});
}

TEST(SceneErrors, BurstLargerThanCapacity) {
    expectError(kEmitter + "capacity = 100\nbursts = [{time = 0, count = 101}]\n",
                {4, 30, "emitter[0].bursts[0].count", "in [1, 100], got 101"});
}

TEST(SceneErrors, RateInRecycleMode) {
    expectError(kEmitter + "lifecycle = \"recycle\"\nrate = 10\n",
                {4, 1, "emitter[0].rate", "lifecycle = \"spawn\""});
}

TEST(SceneErrors, ForcesOnStatelessEmitter) {
    expectError("[[force]]\nname = \"g\"\nkind = \"gravity\"\n" + kEmitter +
                    "stateless = true\nforces = [\"g\"]\n",
                {7, 1, "emitter[0].forces", "stateless"});
}

TEST(SceneErrors, CameraLookingAtItself) {
    expectError("[camera]\neye = [1, 2, 3]\ntarget = [1, 2, 3]\n",
                {3, 10, "camera.target", "differs from the eye"});
}

TEST(SceneErrors, FlowFieldWithoutSource) {
    expectError("[[flow_field]]\nname = \"f\"\n", {1, 1, "flow_field[0]", "needs a source"});
}

TEST(SceneErrors, FlowFieldBoundsInverted) {
    expectError(
        "[[flow_field]]\nname = \"f\"\ngenerate = \"uniform\"\nvelocity = [1, 0, 0]\n"
        "bounds_min = [0, 0, 0]\nbounds_max = [1, -1, 1]\n",
        {6, 18, "flow_field[0].bounds_max[1]", "expected a number > bounds_min[1] = 0, got -1"});
}

TEST(SceneErrors, TerrainWithTwoHeightSources) {
    expectError(
        "[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\n"
        "generate = \"hills\"\nheights = [0, 0, 0, 0]\n",
        {6, 1, "collider[0].heights", "only one height source"});
}

TEST(SceneErrors, TerrainInlineHeightsWrongCount) {
    expectError(
        "[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\n"
        "resolution = [2, 3]\nheights = [0, 0, 0, 0]\n",
        {6, 11, "collider[0].heights", "expected 6 heights"});
}

TEST(SceneErrors, CubeMapCentreOutsideShapes) {
    expectError(
        "[[collider]]\nname = \"c\"\nkind = \"cube_map\"\ncenter = [5, 0, 0]\n"
        "shapes = [{kind = \"sphere\", center = [0, 0, 0], radius = 1}]\n",
        {4, 1, "collider[0].center", "inside the shapes"});
}

TEST(SceneErrors, CubeMapShapeWithUnknownKey) {
    expectError(
        "[[collider]]\nname = \"c\"\nkind = \"cube_map\"\n"
        "shapes = [{kind = \"sphere\", centre = [0, 0, 0], radius = 1}]\n",
        {4, 29, "collider[0].shapes[0].centre", "did you mean \"center\""});
}

TEST(SceneErrors, MissingSceneFile) {
    const std::string path = "/nonexistent-dir/no-such-scene.toml";
    try {
        spindrift::loadScene(path);
        FAIL() << "loaded a file that does not exist";
    } catch (const SceneError& err) {
        EXPECT_EQ(err.file(), path);
        EXPECT_NE(err.message().find("cannot read scene file"), std::string::npos) << err.what();
        EXPECT_NE(err.message().find("No such file"), std::string::npos) << err.what();
    }
}

TEST(SceneErrors, SceneFileThatIsADirectory) {
    EXPECT_THROW(spindrift::loadScene(std::filesystem::temp_directory_path().string()), SceneError);
}

TEST(SceneErrors, MissingDataFilePointsAtTheFileKey) {
    expectError("[[flow_field]]\nname = \"f\"\nfile = \"no/such.flow\"\n",
                {3, 8, "flow_field[0].file", "cannot read \"no/such.flow\""});
}

// --- Errors inside data files: reported at the data file's line and column ---

// A fresh directory per test and process: ctest runs tests in parallel.
std::filesystem::path uniqueTempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return std::filesystem::temp_directory_path() /
           (std::string("spindrift-") + info->test_suite_name() + "-" + info->name() + "-" +
            std::to_string(::getpid()));
}

class SceneDataFileErrors : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = uniqueTempDir();
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir_ / name) << text;
    }

    // Parses `scene` with relative paths resolved in the temporary directory
    // and checks the error points into `dataFile`.
    void expectDataError(const std::string& scene, const std::string& dataFile, int line,
                         int column, const std::string& keyPath, const std::string& part) {
        try {
            spindrift::parseScene(scene, "scene.toml", dir_.string());
            ADD_FAILURE() << "accepted bad data in " << dataFile;
        } catch (const SceneError& err) {
            EXPECT_EQ(err.file(), (dir_ / dataFile).lexically_normal().string()) << err.what();
            EXPECT_EQ(err.line(), line) << err.what();
            EXPECT_EQ(err.column(), column) << err.what();
            EXPECT_EQ(err.keyPath(), keyPath) << err.what();
            EXPECT_NE(err.message().find(part), std::string::npos) << err.what();
        }
    }

    std::filesystem::path dir_;
};

const std::string kFlowScene = "[[flow_field]]\nname = \"f\"\nfile = \"f.flow\"\n";

TEST_F(SceneDataFileErrors, FlowFileBadHeader) {
    write("f.flow", "spindrift-flw 1 2 2 1 0 0 0 1 1 1\n");
    expectDataError(kFlowScene, "f.flow", 1, 1, "flow_field[0].file", "expected the header");
}

TEST_F(SceneDataFileErrors, FlowFileLineWithTwoNumbers) {
    write("f.flow", "# comment\nspindrift-flow 1 2 1 1 0 0 0 1 1 1\n1 0 0\n1 0\n");
    expectDataError(kFlowScene, "f.flow", 4, 1, "flow_field[0].file", "got 2 values");
}

TEST_F(SceneDataFileErrors, FlowFileBadNumberColumn) {
    write("f.flow", "spindrift-flow 1 2 1 1 0 0 0 1 1 1\n1 0 0\n1  x 0\n");
    expectDataError(kFlowScene, "f.flow", 3, 4, "flow_field[0].file",
                    "expected a number, got \"x\"");
}

TEST_F(SceneDataFileErrors, FlowFileNan) {
    write("f.flow", "spindrift-flow 1 1 1 1 0 0 0 1 1 1\nnan 0 0\n");
    expectDataError(kFlowScene, "f.flow", 2, 1, "flow_field[0].file", "finite");
}

TEST_F(SceneDataFileErrors, FlowFileTooShort) {
    write("f.flow", "spindrift-flow 1 2 2 1 0 0 0 1 1 1\n1 0 0\n1 0 0\n");
    // At the file's last line, line 3 (a line past the end no editor shows).
    expectDataError(kFlowScene, "f.flow", 3, 1, "flow_field[0].file", "after 2 of 4");
}

TEST_F(SceneDataFileErrors, FlowFileInvertedBounds) {
    write("f.flow", "spindrift-flow 1 1 1 1 0 0 0 1 -1 1\n0 0 0\n");
    // Token 10 of the header, "-1", starts at column 32.
    expectDataError(kFlowScene, "f.flow", 1, 32, "flow_field[0].file", "max > min along y");
}

// A truncated .cube file (issue 14 found one reported at a line past its end):
// at its last line, with or without a final newline; an empty one at line 1.
TEST_F(SceneDataFileErrors, CubeFileTruncatedAtItsLastLine) {
    const std::string scene = "[[collider]]\nname = \"c\"\nkind = \"cube_map\"\nfile = \"c.cube\"\n";
    write("c.cube", "spindrift-cubemap 1 2\n1 1\n1 1\n");
    expectDataError(scene, "c.cube", 3, 1, "collider[0].file", "ends after 2 of 12 rows");
    write("c.cube", "spindrift-cubemap 1 2\n1 1\n\n# comment\n1 1");
    expectDataError(scene, "c.cube", 5, 1, "collider[0].file", "ends after 2 of 12 rows");
    write("c.cube", "");
    expectDataError(scene, "c.cube", 1, 1, "collider[0].file", "expected the header");
}

TEST_F(SceneDataFileErrors, CubeFileNegativeDepth) {
    write("c.cube", "spindrift-cubemap 1 2\n1 1\n1 -1\n");
    expectDataError("[[collider]]\nname = \"c\"\nkind = \"cube_map\"\nfile = \"c.cube\"\n",
                    "c.cube", 3, 3, "collider[0].file", "depth > 0");
}

}  // namespace
