// Hostile scene text (issue 14): what the pre-scan (src/scene/toml_prescan.h)
// refuses before toml++ sees it, at the line and column where the limit is
// passed, and what it lets through. Positions are counted by hand.
#include <spindrift/scene.h>

#include "scene/field_sources.h"
#include "scene/limits.h"
#include "scene/scene_error_expect.h"

#include <gtest/gtest.h>

#include <chrono>

#include <string>
#include <string_view>

namespace {

using spindrift::test::expectError;
namespace scene = spindrift::scene;

// "a.a.a...a" with `parts` parts: the k-th dot is at column 2k.
std::string dottedKey(int parts) {
    std::string key = "a";
    for (int i = 1; i < parts; ++i) {
        key += ".a";
    }
    return key;
}

// prefix + middle + suffix with append: gcc 12's -Wrestrict misfires on
// `"literal" + std::string` chains (a false positive, GCC bug 105329).
std::string cat(std::string_view prefix, std::string_view middle, std::string_view suffix) {
    std::string s(prefix);
    s.append(middle);
    s.append(suffix);
    return s;
}

// The fuzzer's crash: a 62 KB one-line dotted key of 31,000 parts overflowed
// the stack inside toml++ (SIGSEGV). Refused at the 32nd dot (column 64).
TEST(SceneLimits, DottedKeyOfThirtyOneThousandPartsIsRefusedAtTheLimit) {
    static_assert(scene::kMaxKeyParts == 32);
    expectError(cat("", dottedKey(31000), " = 1\n"), {1, 64, "", "more than 32 parts"});
}

TEST(SceneLimits, TableHeaderOfThirtyOneThousandPartsIsRefusedAtTheLimit) {
    // '[' at column 1 moves every dot one column right: the 32nd is at 65.
    expectError(cat("[", dottedKey(31000), "]\n"), {1, 65, "", "more than 32 parts"});
    expectError(cat("[[", dottedKey(31000), "]]\n"), {1, 66, "", "more than 32 parts"});
}

TEST(SceneLimits, KeyOfThirtyTwoPartsReachesTheSceneReader) {
    // At the limit the pre-scan lets it through; the scene then refuses the
    // unknown top-level key "a" (column 1), not the length.
    expectError(cat("", dottedKey(32), " = 1\n"), {1, 1, "a", "unknown"});
}

TEST(SceneLimits, NestingDeeperThanTheLimitIsRefused) {
    static_assert(scene::kMaxTomlNesting == 32);
    // "x = " then brackets from column 5: the 33rd is at column 37.
    expectError(cat("x = ", std::string(33, '['), cat("1", std::string(33, ']'), "\n")),
                {1, 37, "", "nested more than 32 deep"});
    expectError(cat("x = ", std::string(10000, '{'), ""), {1, 37, "", "nested more than 32 deep"});
    // 32 levels parse (toml++ allows 256); the scene refuses the key.
    expectError(cat("x = ", std::string(32, '['), cat("1", std::string(32, ']'), "\n")), {1, 1, "x", "unknown"});
}

TEST(SceneLimits, DotsAndBracketsInStringsAndCommentsDoNotCount) {
    std::string many;
    for (int i = 0; i < 100; ++i) {
        many += "[{.";
    }
    const std::string text = cat("# ", many, "\n[[emitter]]\nname = \"") + cat(many, "\"\n", "") +
                             cat("# '\"\n[[emitter]]\nname = '''", many, "\n") + cat(many, "'''\n", "");
    const spindrift::SceneDef def = spindrift::parseScene(text, "ok.toml");
    ASSERT_EQ(def.emitters.size(), 2u);
    EXPECT_EQ(def.emitters[0].name, many);
    EXPECT_EQ(def.emitters[1].name, many + "\n" + many);
    // A quoted key's dots are one part: 40 parts of "a.a" is 40 parts, not 80
    // (the error is the scene's unknown key, not the pre-scan's limit).
    std::string quoted = "\"a.a\"";
    for (int i = 1; i < 32; ++i) {
        quoted += ".\"a.a\"";
    }
    expectError(cat(quoted, " = 1\n", ""), {1, 1, "a.a", "unknown"});
}

TEST(SceneLimits, LineLongerThanTheLimitIsRefused) {
    // A comment of kMaxSceneLineBytes bytes on line 2 is the longest line;
    // one byte more is refused at that byte.
    const std::string atLimit = cat("[world]\n#", std::string(scene::kMaxSceneLineBytes - 1, 'x'), "\n");
    EXPECT_NO_THROW(spindrift::parseScene(atLimit, "ok.toml"));
    const std::string over = cat("[world]\n#", std::string(scene::kMaxSceneLineBytes, 'x'), "\n");
    expectError(over, {2, static_cast<int>(scene::kMaxSceneLineBytes) + 1, "", "a line longer than"});
}

TEST(SceneLimits, TextLongerThanTheLimitIsRefusedWhereItPassesIt) {
    // 16 comment lines of 1 MiB each (newline included) fill the limit; the
    // next byte, line 17 column 1, is refused.
    const std::size_t lineBytes = scene::kMaxSceneBytes / 16;
    static_assert(scene::kMaxSceneBytes / 16 <= scene::kMaxSceneLineBytes);
    std::string text;
    for (int i = 0; i < 16; ++i) {
        text += cat("#", std::string(lineBytes - 2, 'x'), "\n");
    }
    ASSERT_EQ(text.size(), scene::kMaxSceneBytes);
    text += "[world]\n";
    expectError(text, {17, 1, "", "longer than 16777216 bytes"});
}

// --- Generated fields: their cost is checked before they are built ---------

// The fuzzer's hangs: curl noise 512 x 512 x 16 with 8 octaves (8 to 22 s in
// validate) and hills 4096^2 with 8 octaves, both within the per-key limits.
// Refused at `octaves` before any sample is made: the time bound (1 s, for
// ASan and a loaded machine) fails if the field were generated first.
TEST(SceneLimits, CostlyGeneratedFieldsAreRefusedBeforeTheyAreBuilt) {
    static_assert(scene::kMaxNoiseEvaluations == 4194304);
    const auto start = std::chrono::steady_clock::now();
    expectError("[[flow_field]]\nname = \"f\"\ngenerate = \"curl_noise\"\nbounds_min = [0, 0, 0]\n"
                "bounds_max = [1, 1, 1]\nresolution = [512, 512, 16]\noctaves = 8\n",
                {7, 11, "flow_field[0].octaves",
                 "curl noise of 512 x 512 x 16 samples x 8 octaves x 3 potentials is 100663296 noise "
                 "evaluations, more than the limit of 4194304"});
    expectError("[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\ngenerate = \"hills\"\n"
                "resolution = [4096, 4096]\noctaves = 8\n",
                {7, 11, "collider[0].octaves",
                 "hills of 4096 x 4096 samples x 8 octaves is 134217728 noise evaluations"});
    // Without `octaves` (1 for curl noise, 3 for hills) the error is at `resolution`.
    expectError("[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\ngenerate = \"hills\"\n"
                "resolution = [2048, 2048]\n",
                {6, 14, "collider[0].resolution", "2048 x 2048 samples x 3 octaves is 12582912"});
    // One row over the limit: 2048 x 2049 x 1 = 4194304 + 2048.
    expectError("[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\ngenerate = \"hills\"\n"
                "resolution = [2048, 2049]\noctaves = 1\n",
                {7, 11, "collider[0].octaves", "is 4196352 noise evaluations"});
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

// The cost the limit bounds, counted as the generators count it (building a
// field at the limit takes about half a second, too long for this suite; the
// refusal above is one row past it).
TEST(SceneLimits, NoiseEvaluationsAreSamplesTimesOctavesTimesPotentials) {
    spindrift::FlowFieldDef field;
    field.nx = 128;
    field.ny = 128;
    field.nz = 85;
    EXPECT_EQ(scene::curlNoiseEvaluations(field, 1), 4177920u);  // 3D: three potentials
    field.nz = 1;
    EXPECT_EQ(scene::curlNoiseEvaluations(field, 8), 131072u);  // planar: one stream function
    spindrift::ColliderDef terrain;
    terrain.terrainNx = 2048;
    terrain.terrainNz = 2048;
    EXPECT_EQ(scene::hillsEvaluations(terrain, 1), scene::kMaxNoiseEvaluations);
}

}  // namespace
