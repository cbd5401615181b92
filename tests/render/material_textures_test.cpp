// Textures on colliders and bodies (issue 15, item 3; SurfaceTexture,
// src/render/material_textures.cpp, collider_mesh.cpp's projection and
// mesh.frag): a box's front face shows the quadrant of an 8 x 8 test image
// that its texture coordinates say, in the body's own frame (it turns with
// the body) or the world's (a collider), with the image's colour times the
// light computed by hand; a body made after the renderer brings its texture
// in; bad values are refused at their key. Validation is on (GpuTest).
#include "render/render_test_util.h"
#include "scene/scene_error_expect.h"

#include "particles/params.h"  // validateColliderDef, what createCollider checks

#include <spindrift/bodies.h>

#include <filesystem>
#include <string>

namespace spindrift::test {
namespace {

namespace fs = std::filesystem;

// 8-bit quantisation of the read-back is +-0.5 code; float rounding in the
// shader and the texture's own 8-bit sRGB storage add about a code.
constexpr int kCodeTolerance = 2;

// Quadrants of 4 x 4 texels, sRGB bytes: red top left, green top right,
// blue bottom left, white bottom right. Inside a quadrant bilinear filtering
// returns the quadrant's colour exactly.
const std::uint8_t kQuadrants[4][3] = {{230, 40, 40}, {40, 230, 40}, {40, 40, 230}, {255, 255, 255}};
enum Quadrant { kRed = 0, kGreen = 1, kBlue = 2, kWhite = 3 };

std::string writeQuadrants(const std::string& name) {
    std::vector<std::uint8_t> rgba;
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
            const std::uint8_t* c = kQuadrants[(y / 4) * 2 + x / 4];
            rgba.insert(rgba.end(), {c[0], c[1], c[2], 255});
        }
    }
    const fs::path path = fs::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + ".png");
    stbi_write_png(path.string().c_str(), 8, 8, 4, rgba.data(), 8 * 4);
    return path.string();
}

// 64 x 64 pixels over 2 m (32 px per m, the origin at pixel (32, 32), y up),
// a clamp for a tone map, no bloom, the sun at (0.48, 0.6, 0.64): a face
// toward the camera (n = +z) gets 0.35 + 0.65 x 0.64 of its colour.
RenderDef flatView() {
    RenderDef def = orthoView(64, 64, 2.0f);
    def.sunDirection = {0.48f, 0.6f, 0.64f};  // a unit vector: n . sun = 0.64 on a face toward the camera
    return def;
}
constexpr double kFaceLight = 0.35 + 0.65 * 0.64;

// The pixel whose centre is nearest the world point (x, y).
const std::uint8_t* pixelAt(const Frame& f, float x, float y) {
    return pixel(f, static_cast<std::uint32_t>(32.0f + 32.0f * x), static_cast<std::uint32_t>(32.0f - 32.0f * y));
}

void expectQuadrant(const Frame& f, float x, float y, Quadrant q, const char* what) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(pixelAt(f, x, y)[c], srgbByte(srgbDecode(kQuadrants[q][c] / 255.0) * kFaceLight), kCodeTolerance)
            << what << " at (" << x << ", " << y << "), channel " << c;
    }
}

class MaterialTexturesRender : public GpuTest {
protected:
    void TearDown() override {
        for (const std::string& p : files) fs::remove(p);
    }
    std::vector<std::string> files;
};

// staticBox(), its texture repeating every 0.4 m. Its front
// face's coordinates are (x, -y) / 0.4 in the body's frame, so the point
// (0.1, 0.1) from its origin is at (0.25, 0.75): the bottom-left (blue)
// quadrant; (-0.1, 0.1) wraps to (0.75, 0.75), white; (0.1, -0.1) red;
// (-0.1, -0.1) green. Turned by 90 degrees the body carries its texture:
// the same body points, now rotated in the world, show the same colours.
TEST_F(MaterialTexturesRender, BodyTextureShowsItsQuadrantsAndTurnsWithTheBody) {
    files.push_back(writeQuadrants("quadrants"));
    for (float angle : {0.0f, 1.5707963f}) {
        WorldId world = worldWithoutBodyGravity();
        BodyDef box = staticBox();
        box.angle = angle;
        box.texture = {files.back(), 0.4f};  // no colour: the image's own
        createBody(world, box);
        {
            ScopedRenderer r(world, flatView());
            Frame f = renderFrame(r.id);
            dumpFrame(f, "body_texture_" + std::to_string(angle));
            const float c = std::cos(angle), s = std::sin(angle);
            auto world_ = [&](float lx, float ly) { return glm::vec2(c * lx - s * ly, s * lx + c * ly + 0.4f); };
            const struct { float x, y; Quadrant q; } points[] = {
                {0.1f, 0.1f, kBlue}, {-0.1f, 0.1f, kWhite}, {0.1f, -0.1f, kRed}, {-0.1f, -0.1f, kGreen}};
            for (const auto& p : points) {
                const glm::vec2 at = world_(p.x, p.y);
                expectQuadrant(f, at.x, at.y, p.q, angle == 0.0f ? "body" : "turned body");
            }
        }
        destroyWorld(world);
    }
}

// A collider's texture is in world coordinates, times its colour: a box
// collider whose front face (z = 0.5) at world (0.1, -0.5) is at
// (0.25, 1.25) -> (0.25, 0.25), the red quadrant, and at (-0.1, -0.5)
// green, each times the colour (0.5, 1, 0.25).
TEST_F(MaterialTexturesRender, ColliderTextureIsInWorldCoordinatesTimesItsColour) {
    files.push_back(writeQuadrants("collider"));
    WorldDef wd;
    WorldId world = createWorld(wd);
    ColliderDef slab;
    slab.kind = ColliderKind::Box;
    slab.position = {0.0f, -0.5f, 0.0f};
    slab.halfExtents = {0.6f, 0.3f, 0.5f};
    slab.colour = glm::vec3(0.5f, 1.0f, 0.25f);
    slab.texture = {files.back(), 0.4f};
    createCollider(world, slab);
    {
        ScopedRenderer r(world, flatView());
        Frame f = renderFrame(r.id);
        dumpFrame(f, "collider_texture");
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(pixelAt(f, 0.1f, -0.5f)[c],
                        srgbByte(srgbDecode(kQuadrants[kRed][c] / 255.0) * (*slab.colour)[c] * kFaceLight),
                        kCodeTolerance)
                << "channel " << c;
            EXPECT_NEAR(pixelAt(f, -0.1f, -0.5f)[c],
                        srgbByte(srgbDecode(kQuadrants[kGreen][c] / 255.0) * (*slab.colour)[c] * kFaceLight),
                        kCodeTolerance)
                << "channel " << c;
        }
    }
    destroyWorld(world);
}

// A body made after the renderer, with a texture the renderer has not
// loaded, is drawn with it from the next frame on.
TEST_F(MaterialTexturesRender, BodyMadeLaterBringsItsTexture) {
    files.push_back(writeQuadrants("later"));
    WorldId world = worldWithoutBodyGravity();
    {
        ScopedRenderer r(world, flatView());
        renderFrame(r.id);
        BodyDef box = staticBox();
        box.texture = {files.back(), 0.4f};
        createBody(world, box);
        expectQuadrant(renderFrame(r.id), 0.1f, 0.5f, kBlue, "body made later");
    }
    destroyWorld(world);
}

TEST_F(MaterialTexturesRender, UnreadableTextureIsAnErrorNamingIt) {
    WorldDef wd;
    WorldId world = createWorld(wd);
    ColliderDef plane;
    plane.texture = {"no-such-texture.png", 1.0f};
    createCollider(world, plane);
    try {
        ScopedRenderer r(world, flatView());
        ADD_FAILURE() << "a renderer was made with a missing texture";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no-such-texture.png"), std::string::npos) << e.what();
    }
    destroyWorld(world);
}

TEST(MaterialTextures, ApiNamesTextureScale) {
    ColliderDef plane;
    plane.texture.scale = 0.0f;
    try {
        validateColliderDef(plane);
        ADD_FAILURE() << "accepted texture scale 0";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "texture_scale");
    }
    BodyDef body;
    body.shapes = {boxShape({1.0f, 1.0f})};
    body.texture.scale = -1.0f;
    try {
        validateBodyDef(body);
        ADD_FAILURE() << "accepted texture scale -1";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "texture_scale");
    }
}

// Scene files: data paths are relative to the scene's folder (here the
// bundled scenes' own, with scenes/data/tiles.png).
const std::string kScenes = std::string(SPINDRIFT_SOURCE_DIR) + "/scenes";

TEST(MaterialTextures, SceneKeysArriveInTheDefs) {
    const SceneDef scene = parseScene("[[collider]]\nname = \"floor\"\nkind = \"plane\"\ntexture = \"data/tiles.png\"\n"
                                      "texture_scale = 2.5\n"
                                      "[[body]]\nname = \"crate\"\ntexture = \"data/tiles.png\"\n"
                                      "shape = [{ box = [1, 1] }]\n",
                                      "ok.toml", kScenes);
    ASSERT_EQ(scene.colliders.size(), 1u);
    EXPECT_NE(scene.colliders[0].texture.path.find("tiles.png"), std::string::npos);
    EXPECT_EQ(scene.colliders[0].texture.scale, 2.5f);
    ASSERT_EQ(scene.bodies.size(), 1u);
    EXPECT_NE(scene.bodies[0].texture.path.find("tiles.png"), std::string::npos);
    EXPECT_EQ(scene.bodies[0].texture.scale, 1.0f) << "1 m by default";
}

TEST(MaterialTextures, BadSceneValuesAreRefusedWhereTheyAre) {
    const std::string plane = "[[collider]]\nname = \"c\"\nkind = \"plane\"\n";
    // "texture_scale = 0": the value is column 17 of line 4.
    expectError(plane + "texture_scale = 0\n", {4, 17, "collider[0].texture_scale", "expected a number > 0, got 0"},
                kScenes);
    expectError(plane + "texture = \"data/missing.png\"\n", {4, 11, "collider[0].texture", "missing.png"}, kScenes);
    expectError("[[body]]\nname = \"b\"\ntexture = 3\nshape = [{ box = [1, 1] }]\n",
                {3, 11, "body[0].texture", "a string"}, kScenes);
}

}  // namespace
}  // namespace spindrift::test
