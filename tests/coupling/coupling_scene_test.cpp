// [[body]] and [[joint]] in scene files: what they parse to, the world
// buildWorld makes of them, and errors with file, line, column and key path
// (positions counted from the inline TOML: line 1 is its first line).
#include <spindrift/scene.h>

#include "scene/scene_error_expect.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace spindrift {
namespace {

const std::string kBodies = R"(
[[body]]
name = "floor"
type = "static"
shape = [{ box = [2.0, 0.1] }, { edge = [[0, 0], [1, 0]] }]

[[body]]
name = "crate"
position = [0.5, 1.0]
angle = 0.25
density = 500.0
fixed_rotation = true

[[body.shape]]
box = [0.1, 0.2]
offset = [0.0, 0.1]
angle = 0.5

[[body.shape]]
circle = 0.1

[[joint]]
name = "hinge"
kind = "revolute"
body_a = "floor"
body_b = "crate"
anchor = [0.5, 1.0]
limits = [-0.5, 0.5]
motor_speed = 1.0
max_motor_torque = 10.0
)";

TEST(CouplingScene, BodiesAndJointsParseAndBuild) {
    const SceneDef s = parseScene(kBodies, "bodies.toml");
    ASSERT_EQ(s.bodies.size(), 2u);
    EXPECT_EQ(s.bodies[0].type, BodyType::Static);
    ASSERT_EQ(s.bodies[0].shapes.size(), 2u);
    EXPECT_EQ(s.bodies[0].shapes[1].kind, BodyShapeKind::Edge);
    const BodyDef& crate = s.bodies[1];
    EXPECT_EQ(crate.type, BodyType::Dynamic);
    EXPECT_EQ(crate.position, glm::vec2(0.5f, 1.0f));
    EXPECT_FLOAT_EQ(crate.density, 500.0f);
    EXPECT_TRUE(crate.fixedRotation);
    ASSERT_EQ(crate.shapes.size(), 2u);
    EXPECT_EQ(crate.shapes[0].halfExtents, glm::vec2(0.1f, 0.2f));
    EXPECT_FLOAT_EQ(crate.shapes[0].angle, 0.5f);
    EXPECT_FLOAT_EQ(crate.shapes[1].radius, 0.1f);
    ASSERT_EQ(s.joints.size(), 1u);
    EXPECT_EQ(s.joints[0].bodyA.index, 1u);
    EXPECT_EQ(s.joints[0].bodyB.index, 2u);
    EXPECT_TRUE(s.joints[0].enableLimit && s.joints[0].enableMotor);
    EXPECT_FLOAT_EQ(s.joints[0].maxMotor, 10.0f);
    const WorldId world = buildWorld(s);
    EXPECT_EQ(bodyCount(world), 2u);
    stepWorld(world, 1.0f / 60.0f);
    EXPECT_EQ(readBodies(world)[1].name, "crate");
    destroyWorld(world);
}

TEST(CouplingScene, TheFluidBoxesSceneHasFloatingAndSinkingCrates) {
    const SceneDef s = loadScene(std::string(SPINDRIFT_SOURCE_DIR) + "/scenes/fluid_boxes.toml");
    bool light = false, heavy = false;
    for (const BodyDef& b : s.bodies) {
        if (b.type != BodyType::Dynamic) continue;
        light = light || b.density < s.fluids.at(0).density;
        heavy = heavy || b.density > s.fluids.at(0).density;
    }
    EXPECT_TRUE(light && heavy);
}

using test::expectError;

TEST(CouplingSceneErrors, BodyWithoutShape) {
    expectError("[[body]]\nname = \"b\"\n", {1, 1, "body[0].shape", "expected at least one shape, got none"});
}

TEST(CouplingSceneErrors, UnknownBodyType) {
    expectError("[[body]]\nname = \"b\"\ntype = \"floating\"\nshape = [{ circle = 1.0 }]\n",
                {3, 8, "body[0].type", "\"static\", \"kinematic\", \"dynamic\""});
}

TEST(CouplingSceneErrors, ShapeWithTwoKinds) {
    expectError("[[body]]\nname = \"b\"\nshape = [{ box = [1, 1], circle = 1.0 }]\n",
                {3, 26, "body[0].shape[0].circle", "already has \"box\""});
}

TEST(CouplingSceneErrors, NegativeBoxExtent) {
    expectError("[[body]]\nname = \"b\"\nshape = [{ box = [1, -1] }]\n",
                {3, 22, "body[0].shape[0].box[1]", "expected a number in [0.005, 10000], got -1"});
}

TEST(CouplingSceneErrors, ConcavePolygon) {
    expectError("[[body]]\nname = \"b\"\n\n[[body.shape]]\npolygon = [[0, 0], [1, 0], [0.2, 0.2], [0, 1]]\n",
                {5, 11, "body[0].shape[0].polygon", "expected a strictly convex polygon"});
}

TEST(CouplingSceneErrors, DynamicEdge) {
    expectError("[[body]]\nname = \"b\"\nshape = [{ edge = [[0, 0], [1, 0]] }]\n",
                {3, 19, "body[0].shape[0].edge", "no area, so no mass"});
}

TEST(CouplingSceneErrors, JointToAnUnknownBody) {
    expectError("[[body]]\nname = \"crate\"\nshape = [{ circle = 1.0 }]\n\n[[joint]]\nname = \"j\"\nkind = "
                "\"weld\"\nbody_a = \"crate\"\nbody_b = \"crat\"\nanchor = [0, 0]\n",
                {9, 10, "joint[0].body_b", "did you mean \"crate\""});
}

TEST(CouplingSceneErrors, JointMotorWithoutItsLimit) {
    expectError("[[body]]\nname = \"a\"\nshape = [{ circle = 1.0 }]\n\n[[body]]\nname = \"b\"\nshape = [{ "
                "circle = 1.0 }]\n\n[[joint]]\nname = \"j\"\nkind = \"revolute\"\nbody_a = \"a\"\nbody_b = "
                "\"b\"\nanchor = [0, 0]\nmotor_speed = 1.0\n",
                {9, 1, "joint[0]", "needs both motor_speed and max_motor_torque"});
}

TEST(CouplingSceneErrors, PrismaticTakesAForceNotATorque) {
    expectError("[[body]]\nname = \"a\"\nshape = [{ circle = 1.0 }]\n\n[[body]]\nname = \"b\"\nshape = [{ "
                "circle = 1.0 }]\n\n[[joint]]\nname = \"j\"\nkind = \"prismatic\"\nbody_a = \"a\"\nbody_b = "
                "\"b\"\nanchor = [0, 0]\nmax_motor_torque = 1.0\n",
                {15, 1, "joint[0].max_motor_torque", "max_motor_force"});
}

TEST(CouplingSceneErrors, JetRidesAnUnknownBody) {
    expectError("[[body]]\nname = \"truck\"\nshape = [{ circle = 1.0 }]\n\n[[fluid]]\nname = \"f\"\n\n"
                "[[fluid.jet]]\nposition = [0, 0, 0]\nbody = \"truk\"\n",
                {10, 8, "fluid[0].jet[0].body", "did you mean \"truck\""});
}

TEST(CouplingSceneErrors, JetAimRunsBackwards) {
    expectError("[[fluid]]\nname = \"f\"\n\n[[fluid.jet]]\nposition = [0, 0, 0]\naim = [[1.0, 0.0], [0.5, 1.0]]\n",
                {6, 20, "fluid[0].jet[0].aim[1]", "not before the previous key's"});
}

// `aim` and `direction` both set a jet's direction: whichever comes second in
// the file is the error, and the message names both.
TEST(CouplingSceneErrors, JetWithAimAndDirectionNamesBoth) {
    expectError("[[fluid]]\nname = \"f\"\n\n[[fluid.jet]]\nposition = [0, 0, 0]\ndirection = [1, 0, 0]\n"
                "aim = [[0.0, 0.5]]\n",
                {7, 1, "fluid[0].jet[0].aim", "either `direction` or `aim`"});
    expectError("[[fluid]]\nname = \"f\"\n\n[[fluid.jet]]\nposition = [0, 0, 0]\naim = [[0.0, 0.5]]\n"
                "direction = [1, 0, 0]\n",
                {7, 1, "fluid[0].jet[0].direction", "either `direction` or `aim`"});
    // One line: the column decides which is second.
    expectError("[[fluid]]\nname = \"f\"\njet = [{ position = [0, 0, 0], aim = [[0.0, 0.5]], direction = [1, 0, 0] }]\n",
                {3, 52, "fluid[0].jet[0].direction", "either `direction` or `aim`"});
}

TEST(CouplingSceneErrors, BodyGravityNeedsTwoNumbers) {
    expectError("[world]\nbody_gravity = [0, -9.81, 0]\n", {2, 16, "world.body_gravity", "an array of 2 numbers"});
}

// Issue 14's fuzz findings: values that reached Box2D or the fluid's grid
// as infinities are refused where they enter, with their location.
TEST(CouplingSceneErrors, AHugeCircleIsRefusedBeforeBox2DSeesIt) {
    // Radius 1e18 overflowed the inertia and fired b2Body::ResetMassData's
    // assertion m_I > 0.
    expectError("[[body]]\nname = \"b\"\nshape = [{ circle = 1e18 }]\n", {3, 21, "body[0].shape[0].circle", "expected a number in [0.005, 10000], got 1e+18"});
}

TEST(CouplingSceneErrors, BodyGravityOfAThousandGAtMost) {
    expectError("[world]\nbody_gravity = [3e38, 3e38]\n", {2, 17, "world.body_gravity[0]", "10000"});
}

TEST(CouplingSceneErrors, AStepUnderANanosecondIsRefused) {
    expectError("[run]\ndt = 1e-45\n", {2, 6, "run.dt", "1e-09"});
}

}  // namespace
}  // namespace spindrift
