// [render], [render.background], [render.fluid] and [emitter.sprite]: values
// land in RenderDef and SpriteDef, PNG paths resolve against the scene's
// folder, and every bad value is reported at its line and column.
#include "scene/scene_error_expect.h"

#include <gtest/gtest.h>
#include <spindrift/scene.h>

#include <filesystem>
#include <string>

namespace {

using spindrift::BackgroundKind;
using spindrift::SceneError;
using spindrift::SpriteBlend;
using spindrift::SpriteDef;

const std::filesystem::path kScenes = std::filesystem::path(SPINDRIFT_SOURCE_DIR) / "scenes";

spindrift::SceneDef parse(const std::string& text) {
    return spindrift::parseScene(text, "render.toml", kScenes.string());
}

void expectError(const std::string& text, const spindrift::test::ExpectedError& e) {
    spindrift::test::expectError(text, e, kScenes.string());
}

TEST(SceneRender, DefaultsWithoutARenderTable) {
    const spindrift::SceneDef scene = parse("");
    const spindrift::RenderDef def;
    EXPECT_EQ(scene.render.width, def.width);
    EXPECT_EQ(scene.render.height, def.height);
    EXPECT_EQ(scene.render.fps, def.fps);
    EXPECT_EQ(scene.render.background.kind, def.background.kind);
    EXPECT_TRUE(scene.render.fluid.bubbles);
    EXPECT_EQ(scene.render.fluid.style, spindrift::FluidStyle::Surface) << "the liquid surface is the default look";
}

TEST(SceneRender, EveryKeyLands) {
    const spindrift::SceneDef scene = parse(R"(
[camera]
eye = [0, 0, 5]
[render]
width = 640
height = 360
fps = 24
seconds = 2.5
draw_colliders = false
sun = [0, 2, 0]
exposure = 1.5
tone_map = "none"
bloom = 0.25
[render.background]
kind = "image"
image = "data/sky.png"
[render.fluid]
style = "splats"
color = [0.2, 0.5, 0.9]
opacity = 0.5
radius_scale = 2
surface_scale = 0.25
size_from_density = false
stretch = false
refraction = false
edges = false
splashes = false
bubbles = false
)");
    const spindrift::RenderDef& r = scene.render;
    EXPECT_EQ(r.width, 640u);
    EXPECT_EQ(r.height, 360u);
    EXPECT_FLOAT_EQ(r.fps, 24.0f);
    EXPECT_FLOAT_EQ(r.seconds, 2.5f);
    EXPECT_FALSE(r.drawColliders);
    EXPECT_FLOAT_EQ(r.sunDirection.y, 1.0f);  // normalised
    EXPECT_FLOAT_EQ(r.exposure, 1.5f);
    EXPECT_EQ(r.toneMap, spindrift::ToneMap::None);
    EXPECT_FLOAT_EQ(r.bloom, 0.25f);
    EXPECT_EQ(r.camera.eye, glm::vec3(0, 0, 5)) << "[camera] still lands in render.camera";
    EXPECT_EQ(r.background.kind, BackgroundKind::Image);
    EXPECT_EQ(std::filesystem::path(r.background.image), (kScenes / "data" / "sky.png").lexically_normal());
    EXPECT_EQ(r.fluid.colour, glm::vec3(0.2f, 0.5f, 0.9f));
    EXPECT_FLOAT_EQ(r.fluid.opacity, 0.5f);
    EXPECT_FLOAT_EQ(r.fluid.radiusScale, 2.0f);
    EXPECT_EQ(r.fluid.style, spindrift::FluidStyle::Splats);
    EXPECT_FLOAT_EQ(r.fluid.surfaceScale, 0.25f);
    EXPECT_FALSE(r.fluid.sizeFromDensity || r.fluid.stretch || r.fluid.refraction || r.fluid.edges ||
                 r.fluid.splashes || r.fluid.bubbles);
}

TEST(SceneRender, ColourAndGradientBackgrounds) {
    const auto colour = parse("[render.background]\nkind = \"color\"\ncolor = [1, 0.5, 0]\n").render.background;
    EXPECT_EQ(colour.kind, BackgroundKind::Colour);
    EXPECT_EQ(colour.colour, glm::vec3(1, 0.5f, 0));
    const auto gradient =
        parse("[render.background]\nkind = \"gradient\"\ntop = [0, 0, 1]\nbottom = [0, 0, 0.1]\n").render.background;
    EXPECT_EQ(gradient.kind, BackgroundKind::Gradient);
    EXPECT_EQ(gradient.top, glm::vec3(0, 0, 1));
    EXPECT_EQ(gradient.bottom, glm::vec3(0, 0, 0.1f));
}

TEST(SceneRender, FluidStepsSetTheSixFlagsAndExplicitFlagsOverride) {
    for (int n = 1; n <= 7; ++n) {
        const auto fluid = parse("[render.fluid]\nsteps = " + std::to_string(n) + "\n").render.fluid;
        const auto preset = spindrift::FluidRenderDef::upTo(n);
        EXPECT_EQ(fluid.sizeFromDensity, preset.sizeFromDensity) << n;
        EXPECT_EQ(fluid.stretch, preset.stretch) << n;
        EXPECT_EQ(fluid.refraction, preset.refraction) << n;
        EXPECT_EQ(fluid.edges, preset.edges) << n;
        EXPECT_EQ(fluid.splashes, preset.splashes) << n;
        EXPECT_EQ(fluid.bubbles, preset.bubbles) << n;
        EXPECT_EQ(fluid.style, spindrift::FluidStyle::Splats) << n << ": steps are the splat style's";
    }
    EXPECT_EQ(parse("[render.fluid]\nstyle = \"splats\"\nsteps = 3\n").render.fluid.style,
              spindrift::FluidStyle::Splats);
    EXPECT_EQ(parse("[render.fluid]\nstyle = \"surface\"\n").render.fluid.style, spindrift::FluidStyle::Surface);
    // Written before or after `steps`, a flag wins; the other keys stay.
    const auto fluid = parse("[render.fluid]\nbubbles = true\nsteps = 2\nopacity = 0.4\n").render.fluid;
    EXPECT_TRUE(fluid.sizeFromDensity);
    EXPECT_FALSE(fluid.stretch);
    EXPECT_FALSE(fluid.splashes);
    EXPECT_TRUE(fluid.bubbles);
    EXPECT_FLOAT_EQ(fluid.opacity, 0.4f);
}

TEST(SceneRender, EmitterSprite) {
    const spindrift::SceneDef scene = parse(R"(
[[emitter]]
name = "plain"
[[emitter]]
name = "smoke"
sprite = { blend = "alpha", stretch = 0.05, texture = "data/spark.png" }
)");
    EXPECT_EQ(scene.emitters[0].sprite.blend, SpriteBlend::Additive);
    EXPECT_EQ(scene.emitters[0].sprite.texture, "");
    EXPECT_EQ(scene.emitters[1].sprite.blend, SpriteBlend::Alpha);
    EXPECT_FLOAT_EQ(scene.emitters[1].sprite.stretch, 0.05f);
    EXPECT_EQ(std::filesystem::path(scene.emitters[1].sprite.texture),
              (kScenes / "data" / "spark.png").lexically_normal());
}

TEST(SceneRender, SpriteFlipbookSoftAndOit) {
    const spindrift::SceneDef scene = parse(R"(
[[emitter]]
name = "smoke"
[emitter.sprite]
blend = "oit"
texture = "data/spark.png"
soft_distance = 0.3
flipbook = { rows = 2, columns = 3, frames = 5, fps = 12, blend = true }
[[emitter]]
name = "plain"
)");
    const SpriteDef& s = scene.emitters[0].sprite;
    EXPECT_EQ(s.blend, SpriteBlend::WeightedOit);
    EXPECT_FLOAT_EQ(s.softDistance, 0.3f);
    EXPECT_EQ(s.flipbook.rows, 2u);
    EXPECT_EQ(s.flipbook.columns, 3u);
    EXPECT_EQ(s.flipbook.frameCount(), 5u);
    EXPECT_FLOAT_EQ(s.flipbook.fps, 12.0f);
    EXPECT_TRUE(s.flipbook.blend);
    const SpriteDef& plain = scene.emitters[1].sprite;  // the defaults: one frame, hard edges
    EXPECT_FALSE(plain.flipbook.animated());
    EXPECT_EQ(plain.flipbook.frameCount(), 1u);
    EXPECT_EQ(plain.softDistance, 0.0f);
}

TEST(SceneRender, BadFlipbooksAndSoftDistances) {
    const std::string emitter = "[[emitter]]\nname = \"e\"\n[emitter.sprite]\ntexture = \"data/spark.png\"\n";
    expectError(emitter + "flipbook = { rows = 0 }\n", {5, 21, "emitter[0].sprite.flipbook.rows", "[1, 64]"});
    expectError(emitter + "flipbook = { columns = 65 }\n",
                {5, 24, "emitter[0].sprite.flipbook.columns", "[1, 64]"});
    expectError(emitter + "flipbook = { rows = 2, columns = 2, frames = 5 }\n",
                {5, 46, "emitter[0].sprite.flipbook.frames", "at most rows x columns = 4"});
    expectError(emitter + "flipbook = { fps = -1 }\n", {5, 20, "emitter[0].sprite.flipbook.fps", ">= 0"});
    expectError(emitter + "flipbook = { rows = 2, loop = true }\n",
                {5, 24, "emitter[0].sprite.flipbook.loop", "[emitter.sprite.flipbook]"});
    expectError(emitter + "soft_distance = -0.5\n", {5, 17, "emitter[0].sprite.soft_distance", ">= 0"});
    expectError("[[emitter]]\nname = \"e\"\nsprite = { flipbook = { rows = 2 } }\n",
                {3, 23, "emitter[0].sprite.flipbook", "a sprite `texture`"});
}

TEST(SceneRender, BadRenderKeys) {
    expectError("[render]\nwidth = 0\n", {2, 9, "render.width", "[1, 16384]"});
    expectError("[render]\nheight = 20000\n", {2, 10, "render.height", "[1, 16384]"});
    expectError("[render]\nwidth = 1.5\n", {2, 9, "render.width", "integer"});
    expectError("[render]\nfps = 0\n", {2, 7, "render.fps", "> 0"});
    expectError("[render]\nseconds = -1\n", {2, 11, "render.seconds", "> 0"});
    expectError("[render]\nsun = [0, 0, 0]\n", {2, 7, "render.sun", "non-zero"});
    expectError("[render]\ndraw_colliders = 1\n", {2, 18, "render.draw_colliders", "true or false"});
    expectError("[render]\nwidht = 640\n", {2, 1, "render.widht", "did you mean"});
}

TEST(SceneRender, BadLightKeys) {
    expectError("[render]\nexposure = 0\n", {2, 12, "render.exposure", "> 0"});
    expectError("[render]\nexposure = \"bright\"\n", {2, 12, "render.exposure", "number"});
    expectError("[render]\ntone_map = \"filmic\"\n", {2, 12, "render.tone_map", "\"aces\""});
    expectError("[render]\ntone_map = 1\n", {2, 12, "render.tone_map", "string"});
    expectError("[render]\nbloom = -0.5\n", {2, 9, "render.bloom", "[0, 10]"});
    expectError("[render]\nbloom = 11\n", {2, 9, "render.bloom", "[0, 10]"});
    expectError("[render]\nblom = 1\n", {2, 1, "render.blom", "did you mean"});
}

TEST(SceneRender, BadBackgrounds) {
    expectError("[render.background]\ncolor = [1, 1, 1]\n",
                {1, 1, "render.background.kind", "required key is missing"});
    expectError("[render.background]\nkind = \"sky\"\n", {2, 8, "render.background.kind", "\"gradient\""});
    expectError("[render.background]\nkind = \"color\"\ntop = [1, 1, 1]\n",
                {3, 1, "render.background.top", "a background of kind \"color\""});
    expectError("[render.background]\nkind = \"color\"\ncolor = [1, -1, 1]\n",
                {3, 13, "render.background.color[1]", ">= 0"});
    expectError("[render.background]\nkind = \"image\"\n", {1, 1, "render.background.image", "a PNG file path"});
    expectError("[render.background]\nkind = \"image\"\nimage = \"data/no-such.png\"\n",
                {3, 9, "render.background.image", "cannot read"});
    expectError("[render.background]\nkind = \"image\"\nimage = \"data/swirl.flow\"\n",
                {3, 9, "render.background.image", "not a PNG"});
}

TEST(SceneRender, BadFluidKeys) {
    expectError("[render.fluid]\nsteps = 8\n", {2, 9, "render.fluid.steps", "[1, 7]"});
    expectError("[render.fluid]\nsteps = 0\n", {2, 9, "render.fluid.steps", "[1, 7]"});
    expectError("[render.fluid]\nopacity = 0\n", {2, 11, "render.fluid.opacity", "(0, 1]"});
    expectError("[render.fluid]\nopacity = 1.5\n", {2, 11, "render.fluid.opacity", "(0, 1]"});
    expectError("[render.fluid]\nradius_scale = 0\n", {2, 16, "render.fluid.radius_scale", "> 0"});
    expectError("[render.fluid]\nbubbles = \"yes\"\n", {2, 11, "render.fluid.bubbles", "true or false"});
    expectError("[render.fluid]\nsplash = true\n", {2, 1, "render.fluid.splash", "did you mean"});
    expectError("[render.fluid]\nstyle = \"blobs\"\n", {2, 9, "render.fluid.style", "\"surface\""});
    expectError("[render.fluid]\nstyle = 1\n", {2, 9, "render.fluid.style", "string"});
    expectError("[render.fluid]\nstyle = \"surface\"\nsteps = 3\n",
                {3, 9, "render.fluid.steps", "splat style"});
    expectError("[render.fluid]\nsurface_scale = 0.1\n", {2, 17, "render.fluid.surface_scale", "[0.125, 1]"});
    expectError("[render.fluid]\nsurface_scale = 2\n", {2, 17, "render.fluid.surface_scale", "[0.125, 1]"});
}

TEST(SceneRender, BadSprites) {
    const std::string emitter = "[[emitter]]\nname = \"e\"\n";
    expectError(emitter + "sprite = { blend = \"multiply\" }\n", {3, 20, "emitter[0].sprite.blend", "\"alpha\""});
    expectError(emitter + "sprite = { stretch = -0.1 }\n", {3, 22, "emitter[0].sprite.stretch", ">= 0"});
    expectError(emitter + "sprite = { texture = \"data/missing.png\" }\n",
                {3, 22, "emitter[0].sprite.texture", "cannot read"});
    expectError(emitter + "sprite = { size = 2 }\n", {3, 12, "emitter[0].sprite.size", "[emitter.sprite]"});
    expectError(emitter + "blend = \"alpha\"\n", {3, 1, "emitter[0].blend", "unknown key"});
}

}  // namespace
