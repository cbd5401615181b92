// Colours of colliders, bodies and body shapes (issue 15, materials): the
// `color` key reaches the Def, a bad value is refused at its line and column
// with the key path, the API's validators name the field, and readBodies
// hands the renderer the shape's colour, else the body's. Positions are
// counted by hand from the inline TOML (line 1 is the string's first line).
#include <spindrift/bodies.h>
#include <spindrift/scene.h>
#include <spindrift/world.h>

#include "particles/params.h"  // validateColliderDef, what createCollider checks
#include "scene/scene_error_expect.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace spindrift {
namespace {

using test::expectError;

const std::string kPlane = "[[collider]]\nname = \"c\"\nkind = \"plane\"\n";
const std::string kBody = "[[body]]\nname = \"b\"\n";

TEST(MaterialColour, ValuesArriveInTheDefs) {
    const SceneDef scene = parseScene(kPlane + "color = [0.02, 0.03, 0.05]\n" +
                                          "[[collider]]\nname = \"s\"\nkind = \"sphere\"\nradius = 1\n" + kBody +
                                          "type = \"static\"\ncolor = [0.5, 0.25, 2]\n"
                                          "shape = [{ box = [1, 1] }, { circle = 0.5, color = [0, 1, 0] }]\n",
                                      "ok.toml");
    ASSERT_EQ(scene.colliders.size(), 2u);
    ASSERT_TRUE(scene.colliders[0].colour.has_value());
    EXPECT_EQ(*scene.colliders[0].colour, glm::vec3(0.02f, 0.03f, 0.05f));
    EXPECT_FALSE(scene.colliders[1].colour.has_value());  // absent: the renderer's default
    ASSERT_EQ(scene.bodies.size(), 1u);
    ASSERT_TRUE(scene.bodies[0].colour.has_value());
    EXPECT_EQ(*scene.bodies[0].colour, glm::vec3(0.5f, 0.25f, 2.0f));  // above 1 is HDR, allowed
    ASSERT_EQ(scene.bodies[0].shapes.size(), 2u);
    EXPECT_FALSE(scene.bodies[0].shapes[0].colour.has_value());
    ASSERT_TRUE(scene.bodies[0].shapes[1].colour.has_value());
    EXPECT_EQ(*scene.bodies[0].shapes[1].colour, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(MaterialColour, EveryColliderKindTakesAColour) {
    // Terrain and cube maps have their own key sets; `color` is common to all.
    const SceneDef scene = parseScene(
        "[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\nresolution = [2, 2]\n"
        "heights = [0, 0, 0, 0]\ncolor = [0.1, 0.2, 0.3]\n"
        "[[collider]]\nname = \"m\"\nkind = \"cube_map\"\nresolution = 2\n"
        "shapes = [{ kind = \"sphere\", center = [0, 0, 0], radius = 1 }]\ncolor = [0.3, 0.2, 0.1]\n"
        "[[collider]]\nname = \"b\"\nkind = \"box\"\nhalf_extents = [1, 1, 1]\ncolor = [0, 0, 0]\n",
        "ok.toml");
    ASSERT_EQ(scene.colliders.size(), 3u);
    EXPECT_EQ(scene.colliders[0].colour.value_or(glm::vec3(-1.0f)), glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(scene.colliders[1].colour.value_or(glm::vec3(-1.0f)), glm::vec3(0.3f, 0.2f, 0.1f));
    EXPECT_EQ(scene.colliders[2].colour.value_or(glm::vec3(-1.0f)), glm::vec3(0.0f));  // black is a colour
}

TEST(MaterialColour, NegativeChannelIsRefusedAtItsElement) {
    // "color = [0.2, -0.1" : the '-' is column 15.
    expectError(kPlane + "color = [0.2, -0.1, 0.3]\n", {4, 15, "collider[0].color[1]", "expected a number >= 0, got -0.1"});
    // "color = [1, 0.5, -2]": the '-' is column 18.
    expectError(kBody + "color = [1, 0.5, -2]\nshape = [{ box = [1, 1] }]\n",
                {3, 18, "body[0].color[2]", "expected a number >= 0, got -2"});
    // "shape = [{ box = [1, 1], color = [0, -1, 0] }]": the '-' is column 38.
    expectError(kBody + "shape = [{ box = [1, 1], color = [0, -1, 0] }]\n",
                {3, 38, "body[0].shape[0].color[1]", "expected a number >= 0, got -1"});
    // A second shape in its own table: line 7, "color = [-3" : column 10.
    expectError(kBody + "[[body.shape]]\nbox = [1, 1]\n[[body.shape]]\ncircle = 1\ncolor = [-3, 0, 0]\n",
                {7, 10, "body[0].shape[1].color[0]", "got -3"});
}

TEST(MaterialColour, NonFiniteAndMisshapenValuesAreTypeErrors) {
    // "color = [0, nan" : the 'n' is column 13.
    expectError(kPlane + "color = [0, nan, 0]\n", {4, 13, "collider[0].color[1]", "got nan"});
    expectError(kBody + "color = [inf, 0, 0]\nshape = [{ box = [1, 1] }]\n", {3, 10, "body[0].color[0]", "got inf"});
    expectError(kPlane + "color = [1, 1]\n", {4, 9, "collider[0].color", "an array of 3 numbers, got an array of 2"});
    expectError(kPlane + "color = \"grey\"\n", {4, 9, "collider[0].color", "an array of 3 numbers"});
}

TEST(MaterialColour, ColourIsAMisspellingOfColor) {
    expectError(kPlane + "colour = [1, 1, 1]\n", {4, 1, "collider[0].colour", "did you mean \"color\""});
    expectError(kBody + "colour = [1, 1, 1]\nshape = [{ box = [1, 1] }]\n",
                {3, 1, "body[0].colour", "did you mean \"color\""});
    expectError(kBody + "[[body.shape]]\nbox = [1, 1]\ncolour = [1, 1, 1]\n",
                {5, 1, "body[0].shape[0].colour", "did you mean \"color\""});
}

template <class Validate>
FieldError apiFieldError(Validate&& validate) {
    try {
        validate();
    } catch (const FieldError& e) {
        return e;
    }
    ADD_FAILURE() << "the API accepted it";
    return FieldError("", "", "");
}

TEST(MaterialColour, ApiRefusesNanNegativeAndInfinityNamingTheKey) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();

    ColliderDef plane;
    plane.name = std::string("c");
    plane.colour = glm::vec3(0.5f, nan, 0.5f);
    FieldError e = apiFieldError([&] { validateColliderDef(plane); });
    EXPECT_EQ(e.field(), "color[1]");
    EXPECT_STREQ(e.what(), "collider 'c': color[1]: expected a number >= 0, got nan");
    plane.colour = glm::vec3(-0.5f, 0.0f, 0.0f);
    e = apiFieldError([&] { validateColliderDef(plane); });
    EXPECT_EQ(e.field(), "color[0]");
    EXPECT_EQ(e.message(), "expected a number >= 0, got -0.5");
    plane.colour = glm::vec3(0.0f, 0.0f, inf);
    EXPECT_EQ(apiFieldError([&] { validateColliderDef(plane); }).field(), "color[2]");
    plane.colour = glm::vec3(0.0f, 3.0f, 0.0f);  // HDR
    EXPECT_NO_THROW(validateColliderDef(plane));

    BodyDef body;
    body.name = std::string("b");
    body.shapes.push_back(boxShape({1.0f, 1.0f}));
    body.colour = glm::vec3(nan);
    e = apiFieldError([&] { validateBodyDef(body); });
    EXPECT_EQ(e.field(), "color[0]");
    EXPECT_STREQ(e.what(), "body 'b': color[0]: expected a number >= 0, got nan");
    body.colour = glm::vec3(0.2f);
    body.shapes.push_back(circleShape(0.5f));
    body.shapes[1].colour = glm::vec3(0.0f, 0.0f, -1.0f);
    e = apiFieldError([&] { validateBodyDef(body); });
    EXPECT_EQ(e.field(), "shape[1].color[2]");
    EXPECT_EQ(e.message(), "expected a number >= 0, got -1");
    body.shapes[1].colour = glm::vec3(0.0f, 0.0f, 1.0f);
    EXPECT_NO_THROW(validateBodyDef(body));

    // createBody and createCollider check through the same validators.
    WorldId world = createWorld(WorldDef{});
    body.shapes[1].colour = glm::vec3(-1.0f);
    EXPECT_THROW(createBody(world, body), FieldError);
    plane.colour = glm::vec3(-1.0f);
    EXPECT_THROW(createCollider(world, plane), FieldError);
    destroyWorld(world);
}

// The snapshot the renderer reads: each shape's own colour, else its body's,
// else none (the renderer's default).
TEST(MaterialColour, SnapshotGivesTheShapesColourElseTheBodys) {
    WorldId world = createWorld(WorldDef{});
    BodyDef painted;
    painted.type = BodyType::Static;
    painted.colour = glm::vec3(0.1f, 0.2f, 0.3f);
    painted.shapes = {boxShape({0.5f, 0.5f}), circleShape(0.25f, {2.0f, 0.0f})};
    painted.shapes[1].colour = glm::vec3(0.9f, 0.8f, 0.7f);
    createBody(world, painted);
    BodyDef plain;
    plain.shapes = {boxShape({0.5f, 0.5f}, {0.0f, 3.0f})};
    plain.shapes[0].colour = glm::vec3(0.4f, 0.0f, 0.0f);
    plain.shapes.push_back(boxShape({0.5f, 0.5f}, {0.0f, 5.0f}));
    createBody(world, plain);

    const std::vector<BodySnapshot> bodies = readBodies(world);
    ASSERT_EQ(bodies.size(), 2u);
    ASSERT_EQ(bodies[0].shapes.size(), 2u);
    EXPECT_EQ(bodies[0].colour, std::optional<glm::vec3>(glm::vec3(0.1f, 0.2f, 0.3f)));
    EXPECT_EQ(bodies[0].shapes[0].colour, std::optional<glm::vec3>(glm::vec3(0.1f, 0.2f, 0.3f)));
    EXPECT_EQ(bodies[0].shapes[1].colour, std::optional<glm::vec3>(glm::vec3(0.9f, 0.8f, 0.7f)));
    ASSERT_EQ(bodies[1].shapes.size(), 2u);
    EXPECT_FALSE(bodies[1].colour.has_value());
    EXPECT_EQ(bodies[1].shapes[0].colour, std::optional<glm::vec3>(glm::vec3(0.4f, 0.0f, 0.0f)));
    EXPECT_FALSE(bodies[1].shapes[1].colour.has_value());
    destroyWorld(world);
}

}  // namespace
}  // namespace spindrift
