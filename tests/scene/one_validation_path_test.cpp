// Each value is validated once, by the API's rule, whichever way it enters: a
// bad value given to the API from C++ and the same value in a scene file
// break the same rule with the same words; the scene's error is located at
// the key that set it (issue 11).
#include <spindrift/fires.h>
#include <spindrift/fluid.h>
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <string>

namespace spindrift {
namespace {

// A valid 2D fluid in a file, the line `bad` added on line 3, `more` at the end.
// (Built by appending: GCC 12 at -O3 warns falsely on a chain of string +.)
std::string fluidScene(const std::string& bad, const std::string& more = "") {
    std::string text = "[[fluid]]\nname = \"w\"\n";
    text.append(bad).append("\n[[fluid.block]]\nmin = [0, 0, 0]\nmax = [1, 1, 0]\n").append(more);
    return text;
}

FluidDef fluidDef() {
    FluidDef def;
    def.name = std::string("w");  // (operator=(const char*) trips a false GCC 12 -Wrestrict at -O3)
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 0.0f), glm::vec3(0.0f)});
    return def;
}

FieldError apiError(const FluidDef& def) {
    try {
        validateFluidDef(def);
    } catch (const FieldError& e) {
        return e;
    }
    ADD_FAILURE() << "the API accepted it";
    return FieldError("", "", "");
}

SceneError sceneError(const std::string& text) {
    try {
        parseScene(text, "bad.toml");
    } catch (const SceneError& e) {
        return e;
    }
    ADD_FAILURE() << "the scene was accepted:\n" << text;
    return SceneError("", 0, 0, "", "");
}

TEST(OneValidationPath, FluidIterationsReadTheSameFromTheApiAndAFile) {
    FluidDef def = fluidDef();
    def.iterations = kFluidMaxIterations + 1;
    const FieldError api = apiError(def);
    EXPECT_EQ(api.field(), "iterations");
    EXPECT_EQ(api.message(), "expected an integer in [1, 16], got 17");
    EXPECT_STREQ(api.what(), "fluid 'w': iterations: expected an integer in [1, 16], got 17");

    const SceneError scene = sceneError(fluidScene("iterations = 17"));
    EXPECT_EQ(scene.message(), api.message());  // the same rule, the same words
    EXPECT_EQ(scene.line(), 3);
    EXPECT_EQ(scene.column(), 14);  // the value
    EXPECT_EQ(scene.keyPath(), "fluid[0].iterations");
}

TEST(OneValidationPath, NestedFieldsPointAtTheirKey) {
    FluidDef def = fluidDef();
    FluidJetDef jet;
    jet.speed = -2.0f;
    def.jets.push_back(jet);
    const FieldError api = apiError(def);
    EXPECT_EQ(api.field(), "jet[0].speed");
    EXPECT_EQ(api.message(), "expected a number > 0, got -2");

    const SceneError scene =
        sceneError(fluidScene("", "[[fluid.jet]]\nposition = [0, 0, 0]\nspeed = -2\n"));
    EXPECT_EQ(scene.message(), api.message());
    EXPECT_EQ(scene.line(), 9);
    EXPECT_EQ(scene.column(), 9);
    EXPECT_EQ(scene.keyPath(), "fluid[0].jet[0].speed");
}

TEST(OneValidationPath, ARuleBetweenTwoKeysPointsAtTheOneThatBrokeIt) {
    // h must exceed the spacing: with the spacing left at its default, h is wrong.
    FluidDef def = fluidDef();
    def.smoothing = 0.01f;
    const FieldError api = apiError(def);
    EXPECT_EQ(api.field(), "h");
    const SceneError scene = sceneError(fluidScene("h = 0.01"));
    EXPECT_EQ(scene.message(), api.message());
    EXPECT_EQ(scene.line(), 3);
    EXPECT_EQ(scene.keyPath(), "fluid[0].h");
}

TEST(OneValidationPath, ATypeErrorStaysTheReadersAndNamesTheRule) {
    const SceneError scene = sceneError(fluidScene("iterations = \"many\""));
    EXPECT_EQ(scene.message(), "expected an integer in [1, 16], got \"many\"");
    EXPECT_EQ(scene.line(), 3);
}

TEST(OneValidationPath, FireStrengthReadsTheSameFromTheApiAndAFile) {
    FireDef def;
    def.name = std::string("f");
    def.dousePerStrike = -1.0f;
    try {
        validateFireDef(def);
        ADD_FAILURE() << "the API accepted it";
    } catch (const FieldError& api) {
        EXPECT_EQ(api.field(), "douse_per_strike");
        const SceneError scene = sceneError(
            "[[body]]\nname = \"b\"\nshape = [{ box = [1, 1] }]\n"
            "[[fire]]\nname = \"f\"\nbody = \"b\"\ndouse_per_strike = -1\n");
        EXPECT_EQ(scene.message(), api.message());
        EXPECT_EQ(scene.message(), "expected a number >= 0, got -1");
        EXPECT_EQ(scene.line(), 7);
        EXPECT_EQ(scene.keyPath(), "fire[0].douse_per_strike");
    }
}

}  // namespace
}  // namespace spindrift
