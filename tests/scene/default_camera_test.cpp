// A scene without [camera]: a 2D fluid scene is framed square-on
// (src/scene/default_camera.cpp); any other keeps CameraDef's defaults.
#include <gtest/gtest.h>
#include <spindrift/scene.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

// The bundled tank (scenes/fluid_tank.toml) without its camera: a floor box
// under y = 0, side walls at x = 0 and 2, a lid at y = 1.5, water 0.5 deep.
const std::string kTank = R"(
[[collider]]
name = "floor"
kind = "box"
center = [1.0, -0.1, 0.0]
half_extents = [1.2, 0.1, 1.0]

[[collider]]
name = "left"
kind = "plane"
normal = [1.0, 0.0, 0.0]

[[collider]]
name = "right"
kind = "plane"
point = [2.0, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]

[[collider]]
name = "lid"
kind = "plane"
point = [0.0, 1.5, 0.0]
normal = [0.0, -1.0, 0.0]

[[fluid]]
name = "water"
spacing = 0.025

[[fluid.block]]
min = [0.0, 0.0, 0.0]
max = [2.0, 0.5, 0.0]
)";

/// Whether point (x, y) in the z = 0 plane is inside an orthographic
/// camera's frame of the given aspect ratio (width / height).
bool inView(const spindrift::CameraDef& c, float aspect, float x, float y) {
    const float halfHeight = 0.5f * c.orthoHeight;
    const float halfWidth = halfHeight * aspect;
    return std::abs(x - c.target.x) <= halfWidth && std::abs(y - c.target.y) <= halfHeight;
}

TEST(DefaultCamera, A2DFluidSceneIsFramedSquareOn) {
    const spindrift::SceneDef scene = spindrift::parseScene(kTank, "tank.toml");
    const spindrift::CameraDef& c = scene.render.camera;
    const float aspect = static_cast<float>(scene.render.width) / static_cast<float>(scene.render.height);
    ASSERT_TRUE(c.orthographic);
    // Looking along -z, so x and y on screen are the scene's x and y.
    EXPECT_FLOAT_EQ(c.eye.x, c.target.x);
    EXPECT_FLOAT_EQ(c.eye.y, c.target.y);
    EXPECT_GT(c.eye.z, c.target.z);
    // The whole tank inside the frame: its inner corners and the water.
    for (float x : {0.0f, 2.0f}) {
        for (float y : {0.0f, 0.5f, 1.5f}) EXPECT_TRUE(inView(c, aspect, x, y)) << x << ", " << y;
    }
    // And large in it: the tank (2 x 1.5 m inside) fills at least 70 % of
    // the frame's width or height. The 3D default camera, 10 m away with a
    // 45 degree view (8.3 m visible height), showed it at 18 % of the height.
    const float frameHeight = c.orthoHeight;
    const float frameWidth = c.orthoHeight * aspect;
    EXPECT_GE(std::max(2.0f / frameWidth, 1.5f / frameHeight), 0.7f);
}

TEST(DefaultCamera, AFarAwayFloorIsNotFramed) {
    // A floor a kilometre below a small tank is not the tank's wall.
    const spindrift::SceneDef scene = spindrift::parseScene(kTank + R"(
[[collider]]
name = "far"
kind = "plane"
point = [0.0, -1000.0, 0.0]
normal = [0.0, 1.0, 0.0]
)",
                                                            "tank.toml");
    EXPECT_TRUE(scene.render.camera.orthographic);
    EXPECT_LT(scene.render.camera.orthoHeight, 3.0f);
}

TEST(DefaultCamera, OtherScenesKeepTheDefaultsAndACameraTableWins) {
    const spindrift::CameraDef defaults;
    // 3D fluid: CameraDef's defaults.
    const spindrift::SceneDef cube = spindrift::parseScene(R"(
[[fluid]]
name = "water"
dimension = 3
spacing = 0.05
[[fluid.block]]
min = [0.0, 0.0, 0.0]
max = [0.5, 0.5, 0.5]
)",
                                                           "cube.toml");
    EXPECT_FALSE(cube.render.camera.orthographic);
    EXPECT_EQ(cube.render.camera.eye, defaults.eye);
    // No fluid at all: the defaults.
    EXPECT_EQ(spindrift::parseScene("", "empty.toml").render.camera.eye, defaults.eye);
    // A [camera] table is taken as written, even in a 2D fluid scene.
    const spindrift::SceneDef own = spindrift::parseScene(kTank + R"(
[camera]
eye = [0.0, 3.0, 9.0]
)",
                                                          "own.toml");
    EXPECT_FALSE(own.render.camera.orthographic);
    EXPECT_EQ(own.render.camera.eye, glm::vec3(0.0f, 3.0f, 9.0f));
}

}  // namespace
