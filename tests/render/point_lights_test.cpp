// The scene's light (issue 15, item 2; src/render/point_lights.cpp and
// shaders/lighting.glsl): the sky's and the sun's colours and point lights
// reach the pixels of a coloured body as the shading rule says, computed
// here by hand; a light that follows an emitter moves with its spawn centre
// and scales with its rate; bad values are refused at their key, in the API
// and in scene files. Validation is on (GpuTest): any message fails a test.
#include "render/render_test_util.h"
#include "scene/scene_error_expect.h"

#include <spindrift/bodies.h>
#include <spindrift/effects.h>

#include <cmath>
#include <string>

namespace spindrift::test {
namespace {

// 8-bit quantisation of the read-back is +-0.5 code, float rounding in the
// shader a little more (as tests/render/render_test.cpp).
constexpr int kCodeTolerance = 2;

// 64 x 64 pixels over 2 m: 32 px per m, the world origin at pixel (32, 32),
// y up. The tone map is a plain clamp and bloom off, so a pixel is the
// linear colour through sRGB.
RenderDef flatView() {
    RenderDef def = orthoView(64, 64, 2.0f);
    def.sunDirection = {0.48f, 0.6f, 0.64f};  // a unit vector: n . sun = 0.64 on a face toward the camera
    return def;
}

const glm::vec3 kBoxColour{0.8f, 0.5f, 0.4f};

// staticBox() in kBoxColour.
WorldId worldWithBox() {
    WorldId world = worldWithoutBodyGravity();
    BodyDef box = staticBox();
    box.colour = kBoxColour;
    createBody(world, box);
    return world;
}

// The world point of pixel (32, 19)'s centre on the box's front face.
const glm::vec3 kFacePoint{(32.5f - 32.0f) / 32.0f, (32.0f - 19.5f) / 32.0f, 0.5f};

void expectBoxLitBy(const Frame& f, glm::vec3 light) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(pixel(f, 32, 19)[c], srgbByte(kBoxColour[c] * light[c]), kCodeTolerance) << "channel " << c;
    }
}

// A point light's share on a face of normal n = +z, as lighting.glsl says:
// (1 - (d/r)^2)^2 falloff times the wrapped Lambert term 0.5 + 0.5 n.l.
glm::vec3 pointShare(glm::vec3 lightAt, float radius, glm::vec3 colour) {
    const glm::vec3 toLight = lightAt - kFacePoint;
    const float q = glm::dot(toLight, toLight) / (radius * radius);
    const float facing = toLight.z / glm::length(toLight);
    return colour * ((1.0f - q) * (1.0f - q) * (0.5f + 0.5f * facing));
}

class PointLightsRender : public GpuTest {};

// colour x (ambient x 0.35 + sun colour x 0.65 x n.sun) per channel: each
// colour scales its own term, so a wrong pairing (ambient on the sun's term)
// or a grey light would miss by far more than 2 codes.
TEST_F(PointLightsRender, SkyAndSunColoursScaleTheirTerms) {
    WorldId world = worldWithBox();
    {
        RenderDef def = flatView();
        def.ambient = {0.6f, 0.3f, 1.0f};
        def.sunColour = {0.2f, 1.0f, 0.5f};
        ScopedRenderer r(world, def);
        Frame f = renderFrame(r.id);
        dumpFrame(f, "sky_and_sun_colours");
        expectBoxLitBy(f, def.ambient * 0.35f + def.sunColour * (0.65f * 0.64f));
    }
    destroyWorld(world);
}

// In the dark (no sky, no sun) only a point light in front of the box lights
// it, by the closed form above; a light whose reach ends before the box
// leaves it black.
TEST_F(PointLightsRender, PointLightFallsOffToItsReach) {
    WorldId world = worldWithBox();
    {
        RenderDef def = flatView();
        def.ambient = glm::vec3(0.0f);
        def.sunColour = glm::vec3(0.0f);
        LightDef light;
        light.name = "lamp";
        light.position = {0.0f, 0.4f, 1.5f};  // 1 m in front of the face
        light.colour = {0.9f, 0.6f, 0.3f};
        light.radius = 2.0f;  // (1 - 1/4)^2 = 0.5625 of it
        def.lights = {light};
        ScopedRenderer r(world, def);
        Frame f = renderFrame(r.id);
        dumpFrame(f, "point_light");
        expectBoxLitBy(f, pointShare(light.position, light.radius, light.colour));
        EXPECT_GT(pixel(f, 32, 19)[0], 100) << "the light is bright there, not a black pixel passing by tolerance";
    }
    {
        RenderDef def = flatView();
        def.ambient = glm::vec3(0.0f);
        def.sunColour = glm::vec3(0.0f);
        LightDef light;
        light.position = {0.0f, 0.4f, 1.5f};
        light.radius = 0.99f;  // ends 1 cm before the face
        def.lights = {light};
        ScopedRenderer r(world, def);
        Frame f = renderFrame(r.id);
        expectBoxLitBy(f, glm::vec3(0.0f));
    }
    destroyWorld(world);
}

// A light following an emitter sits at its spawn centre plus its offset and
// scales with the emitter's rate over the rate it had when the renderer was
// made: as the world changes them (a fire's flames), the light follows.
TEST_F(PointLightsRender, LightFollowsItsEmittersCentreAndRate) {
    WorldId world = worldWithBox();
    EmitterDef e;
    e.name = "flames";
    e.capacity = 16;
    e.rate = 100.0f;
    e.shape.center = {0.0f, 0.4f, 0.0f};
    const EmitterId emitter = createEmitter(world, e);
    {
        RenderDef def = flatView();
        def.ambient = glm::vec3(0.0f);
        def.sunColour = glm::vec3(0.0f);
        LightDef light;
        light.position = {0.0f, 0.0f, 1.0f};  // 1 m in front of the emitter's centre
        light.colour = {1.0f, 0.7f, 0.5f};
        light.radius = 2.0f;
        light.emitter = emitter;
        def.lights = {light};
        ScopedRenderer r(world, def);  // no step: no particle is drawn
        expectBoxLitBy(renderFrame(r.id), pointShare({0.0f, 0.4f, 1.0f}, 2.0f, light.colour));
        setEmitterRate(world, emitter, 25.0f);
        expectBoxLitBy(renderFrame(r.id), pointShare({0.0f, 0.4f, 1.0f}, 2.0f, light.colour) * 0.25f);
        setEmitterPosition(world, emitter, {1.0f, 0.4f, 0.0f});
        Frame moved = renderFrame(r.id);
        dumpFrame(moved, "light_follows_emitter");
        expectBoxLitBy(moved, pointShare({1.0f, 0.4f, 1.0f}, 2.0f, light.colour) * 0.25f);
    }
    destroyWorld(world);
}

TEST_F(PointLightsRender, UnknownEmitterIsAnError) {
    WorldId world = worldWithBox();
    RenderDef def = flatView();
    LightDef light;
    light.emitter = EmitterId{3};
    def.lights = {light};
    EXPECT_THROW(createRenderer(world, def), Error);
    destroyWorld(world);
}

// The public API names the key of a bad value as a scene file spells it.
TEST(PointLights, BadValuesNameTheirKey) {
    auto field = [](const RenderDef& def) -> std::string {
        try {
            validateRenderDef(def);
        } catch (const FieldError& e) {
            return e.object() + ": " + e.field();
        }
        return "accepted";
    };
    RenderDef def;
    EXPECT_EQ(def.ambient, glm::vec3(1.0f)) << "relative to the default daylight";
    EXPECT_EQ(def.sunColour, glm::vec3(1.0f));
    def.ambient.y = -0.1f;
    EXPECT_EQ(field(def), "render: ambient[1]");
    def = RenderDef{};
    def.sunColour.z = std::nanf("");
    EXPECT_EQ(field(def), "render: sun_color[2]");
    def = RenderDef{};
    LightDef light;
    light.name = "glow";
    def.lights = {light};
    EXPECT_EQ(field(def), "accepted");
    def.lights[0].radius = 0.0f;
    EXPECT_EQ(field(def), "light 'glow': radius");
    def.lights[0] = light;
    def.lights[0].flicker = 1.5f;
    EXPECT_EQ(field(def), "light 'glow': flicker");
    def.lights[0] = light;
    def.lights[0].colour.x = -1.0f;
    EXPECT_EQ(field(def), "light 'glow': color[0]");
    def.lights[0] = light;
    def.lights[0].position.y = INFINITY;
    EXPECT_EQ(field(def), "light 'glow': position[1]");
    def.lights.assign(kRenderMaxLights + 1, light);
    EXPECT_EQ(field(def), "render: lights");
}

const std::string kEmitter = "[[emitter]]\nname = \"flames\"\nrate = 10\n";

TEST(PointLights, SceneKeysArriveInTheDef) {
    const SceneDef scene = parseScene("[render]\nsun_color = [0.2, 0.25, 0.4]\nambient = [0.1, 0.1, 0.2]\n" + kEmitter +
                                          "[[light]]\nname = \"glow\"\nemitter = \"flames\"\nposition = [0, 0.2, 0.8]\n"
                                          "color = [2, 0.8, 0.3]\nradius = 2.5\nflicker = 0.3\n"
                                          "[[light]]\nname = \"lamp\"\n",
                                      "ok.toml");
    EXPECT_EQ(scene.render.sunColour, glm::vec3(0.2f, 0.25f, 0.4f));
    EXPECT_EQ(scene.render.ambient, glm::vec3(0.1f, 0.1f, 0.2f));
    ASSERT_EQ(scene.render.lights.size(), 2u);
    const LightDef& glow = scene.render.lights[0];
    EXPECT_EQ(glow.name, "glow");
    EXPECT_EQ(glow.emitter.index, 1u);
    EXPECT_EQ(glow.position, glm::vec3(0.0f, 0.2f, 0.8f));
    EXPECT_EQ(glow.colour, glm::vec3(2.0f, 0.8f, 0.3f));
    EXPECT_EQ(glow.radius, 2.5f);
    EXPECT_EQ(glow.flicker, 0.3f);
    const LightDef defaults;
    EXPECT_EQ(scene.render.lights[1].emitter.index, 0u) << "no emitter: a fixed light";
    EXPECT_EQ(scene.render.lights[1].colour, defaults.colour);
}

TEST(PointLights, BadSceneValuesAreRefusedWhereTheyAre) {
    // "radius = 0": the value is column 10 of line 3.
    expectError("[[light]]\nname = \"a\"\nradius = 0\n", {3, 10, "light[0].radius", "expected a number > 0, got 0"});
    expectError("[[light]]\nname = \"a\"\nflicker = 2\n", {3, 11, "light[0].flicker", "got 2"});
    // "color = [1, -1" : the '-' is column 13.
    expectError("[[light]]\nname = \"a\"\ncolor = [1, -1, 0]\n", {3, 13, "light[0].color[1]", "got -1"});
    expectError(kEmitter + "[[light]]\nname = \"a\"\nemitter = \"smoke\"\n", {6, 11, "light[0].emitter", "smoke"});
    expectError("[[light]]\nname = \"a\"\nbrightness = 2\n", {3, 1, "light[0].brightness", "unknown key"});
    expectError("[render]\nambient = [0, -0.5, 0]\n", {2, 15, "render.ambient[1]", "got -0.5"});
    std::string nine;
    for (int i = 0; i < 9; ++i) nine += "[[light]]\nname = \"l" + std::to_string(i) + "\"\n";
    expectError(nine, {17, 1, "light[8]", "at most 8 [[light]] tables"});
}

}  // namespace
}  // namespace spindrift::test
