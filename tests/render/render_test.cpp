// The renderer against closed forms: every expected pixel comes from the
// camera's projection, the sRGB transfer function (IEC 61966-2-1) and the
// blend equations, not from a previous run. Validation is on (GpuTest): any
// message fails the test.
#include "render/render_test_util.h"

#include <spindrift/bodies.h>
#include <spindrift/fluid.h>

#include <filesystem>

namespace spindrift::test {
namespace {

class RenderTest : public GpuTest, public ::testing::WithParamInterface<Backend> {};

// 8-bit quantisation of the read-back is +-0.5 code; interpolation and the
// blending unit's own 8-bit sRGB round trip add at most another code.
constexpr int kCodeTolerance = 2;

// One or more particles born at `at` at rest, white unless told, lasting 10 s.
EmitterDef restingBurst(glm::vec3 at, std::uint32_t count, float size, glm::vec4 colour = glm::vec4(1.0f)) {
    EmitterDef e;
    e.name = "spot";
    e.capacity = 8;
    e.rate = 0.0f;
    e.bursts = {BurstDef{0.0f, count}};
    e.shape.center = at;
    e.speed = {0.0f, 0.0f};
    e.lifetime = {10.0f, 10.0f};
    e.size = {size, size};
    e.color = {colour, colour};
    e.statelessGravity = glm::vec3(0.0f);
    return e;
}

TEST_P(RenderTest, ColourBackgroundFillsEveryPixel) {
    BackendWorld world(GetParam());
    RenderDef def = orthoView(40, 30, 2.0f);
    def.background.colour = {0.2f, 0.5f, 0.8f};
    ScopedRenderer r(world.id, def);
    Frame f = renderFrame(r.id);
    ASSERT_EQ(f.rgba.size(), 40u * 30u * 4u);
    for (std::uint32_t y = 0; y < f.height; ++y) {
        for (std::uint32_t x = 0; x < f.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                ASSERT_NEAR(pixel(f, x, y)[c], srgbByte(def.background.colour[c]), 1) << x << "," << y;
            }
            ASSERT_EQ(pixel(f, x, y)[3], 255);
        }
    }
}

TEST_P(RenderTest, GradientRunsFromTopToBottomAtPixelCentres) {
    BackendWorld world(GetParam());
    RenderDef def = orthoView(8, 64, 2.0f);
    def.background.kind = BackgroundKind::Gradient;
    def.background.top = {0.8f, 0.1f, 0.0f};
    def.background.bottom = {0.0f, 0.2f, 0.6f};
    ScopedRenderer r(world.id, def);
    Frame f = renderFrame(r.id);
    for (std::uint32_t y = 0; y < f.height; ++y) {
        const float t = (float(y) + 0.5f) / float(f.height);  // row y's centre
        const glm::vec3 expected = glm::mix(def.background.top, def.background.bottom, t);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(pixel(f, 3, y)[c], srgbByte(expected[c]), kCodeTolerance) << "row " << y;
        }
    }
}

TEST_P(RenderTest, ImageBackgroundShowsTheImageCorners) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "spindrift_render_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "corners.png").string();
    const std::uint8_t texels[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    ASSERT_NE(stbi_write_png(path.c_str(), 2, 2, 4, texels, 8), 0);
    BackendWorld world(GetParam());
    RenderDef def = orthoView(64, 64, 2.0f);
    def.background.kind = BackgroundKind::Image;
    def.background.image = path;
    ScopedRenderer r(world.id, def);
    Frame f = renderFrame(r.id);
    // A corner pixel's centre lies within a quarter texel of the image's
    // corner, where clamp-to-edge linear filtering returns the corner texel.
    const std::uint32_t corners[4][2] = {{0, 0}, {63, 0}, {0, 63}, {63, 63}};
    for (int k = 0; k < 4; ++k) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(pixel(f, corners[k][0], corners[k][1])[c], texels[4 * k + c], kCodeTolerance) << "corner " << k;
        }
    }
}

// Where a resting sprite lands and how large it is, from the orthographic
// projection: 1 m is height / orthoHeight pixels, the view centred on the
// target, y up.
TEST_P(RenderTest, SpriteLandsWhereTheCameraProjectsIt) {
    for (bool stateless : {false, true}) {
        BackendWorld world(GetParam());
        EmitterDef e = restingBurst({0.5f, 0.25f, 0.0f}, 1, 0.5f);
        e.stateless = stateless;
        createEmitter(world.id, e);
        stepWorld(world.id, 1.0f / 60.0f);
        RenderDef def = orthoView(96, 64, 2.0f);
        ScopedRenderer r(world.id, def);
        Frame f = renderFrame(r.id);
        dumpFrame(f, stateless ? "sprite_stateless" : "sprite_stored");
        const double pxPerM = 64.0 / 2.0;
        const double cx = 48.0 + 0.5 * pxPerM, cy = 32.0 - 0.25 * pxPerM;  // in pixel units, pixel centres at +0.5
        double sum = 0.0, sx = 0.0, sy = 0.0, farthest = 0.0;
        int brightest = 0;
        for (std::uint32_t y = 0; y < f.height; ++y) {
            for (std::uint32_t x = 0; x < f.width; ++x) {
                const double v = srgbDecode(pixel(f, x, y)[0] / 255.0);
                if (v <= 0.0) {
                    continue;
                }
                sum += v;
                sx += v * (x + 0.5);
                sy += v * (y + 0.5);
                farthest = std::max(farthest, std::hypot(x + 0.5 - cx, y + 0.5 - cy));
                brightest = std::max(brightest, int(pixel(f, x, y)[0]));
            }
        }
        ASSERT_GT(sum, 0.0) << (stateless ? "stateless" : "stored") << ": nothing drawn";
        // The spot is symmetric about its centre: the centroid is the centre
        // up to pixel sampling (0.25 px).
        EXPECT_NEAR(sx / sum, cx, 0.25) << (stateless ? "stateless" : "stored");
        EXPECT_NEAR(sy / sum, cy, 0.25) << (stateless ? "stateless" : "stored");
        // Radius 0.25 m = 8 px: nothing lit beyond it (plus a pixel's half diagonal).
        EXPECT_LE(farthest, 0.25 * pxPerM + 0.71);
        EXPECT_GE(brightest, 240);  // (1 - r^2)^2 of white near the centre
    }
}

// Additive blending adds light: two coincident dim particles give twice the
// linear intensity of one at the centre.
TEST_P(RenderTest, AdditiveSpritesAddLinearLight) {
    double centre[2] = {};
    for (std::uint32_t count : {1u, 2u}) {
        BackendWorld world(GetParam());
        createEmitter(world.id, restingBurst({0.0f, 0.0f, 0.0f}, count, 1.0f, {0.2f, 0.2f, 0.2f, 1.0f}));
        stepWorld(world.id, 1.0f / 60.0f);
        ScopedRenderer r(world.id, orthoView(64, 64, 2.0f));
        Frame f = renderFrame(r.id);
        centre[count - 1] = srgbDecode(pixel(f, 32, 32)[1] / 255.0);
    }
    // One code near 0.2 linear is about 1.5 % of the value; allow 4 %.
    EXPECT_NEAR(centre[1] / centre[0], 2.0, 0.08);
}

// Alpha sprites are drawn back to front: the centre pixel is the "over"
// composite of the nearer particle on the farther one, computed from the
// particles' own positions and colours.
TEST_P(RenderTest, AlphaSpritesCompositeNearOverFar) {
    BackendWorld world(GetParam());
    EmitterDef e = restingBurst({0.0f, 0.0f, 0.0f}, 2, 0.6f);
    e.speed = {0.5f, 2.0f};
    e.shape.direction = {0.0f, 0.0f, 1.0f};  // toward the camera, along its axis
    e.color = {{1.0f, 0.0f, 0.0f, 0.6f}, {0.0f, 0.0f, 1.0f, 0.6f}};
    e.sprite.blend = SpriteBlend::Alpha;
    createEmitter(world.id, e);
    stepWorld(world.id, 0.5f);
    flushWorld(world.id);
    ParticleSnapshot p = readParticles(world.id, EmitterId{1});
    ASSERT_EQ(p.count(), 2u);
    const std::size_t nearI = p.position[0].z > p.position[1].z ? 0 : 1;
    const glm::vec4 nearC = p.color[nearI], farC = p.color[1 - nearI];
    ASSERT_GT(std::abs(nearC.r - farC.r), 0.2f) << "seed gave two similar colours: the test would not tell";
    ASSERT_GT(std::abs(p.position[0].z - p.position[1].z), 0.1f);
    RenderDef def = orthoView(64, 64, 2.0f);
    def.camera.orthographic = false;
    ScopedRenderer r(world.id, def);
    Frame f = renderFrame(r.id);
    // The centre pixel's centre is half a pixel off the axis in x and y; the
    // spot's weight there is (1 - r^2)^2 with r that offset over the
    // particle's radius in pixels (perspective: 32 px / tan(22.5 deg) per
    // unit of x / depth).
    const double pxPerUnit = 32.0 / std::tan(glm::radians(22.5));
    auto weighted = [&](glm::vec4 c, float z) {
        const double radiusPx = 0.3 / (5.0 - z) * pxPerUnit;
        const double r2 = 0.5 / (radiusPx * radiusPx);
        c.a *= static_cast<float>((1.0 - r2) * (1.0 - r2));
        return c;
    };
    const glm::vec4 nearW = weighted(nearC, p.position[nearI].z), farW = weighted(farC, p.position[1 - nearI].z);
    auto over = [](glm::vec4 top, glm::vec3 below) { return glm::vec3(top) * top.a + (1.0f - top.a) * below; };
    const glm::vec3 right = over(nearW, over(farW, glm::vec3(0.0f)));
    const glm::vec3 wrong = over(farW, over(nearW, glm::vec3(0.0f)));
    for (int c : {0, 2}) {
        // Plus one code: the far particle's composite is stored in 8-bit sRGB
        // before the near one is blended over it.
        EXPECT_NEAR(pixel(f, 32, 32)[c], srgbByte(right[c]), kCodeTolerance + 1) << "channel " << c;
        EXPECT_GT(std::abs(srgbByte(right[c]) - srgbByte(wrong[c])), 2 * (kCodeTolerance + 1)) << "channel " << c;
    }
}

// Raw splats (step 1) cover a 2D block of water: inside the block every
// pixel is water, beyond the splats' reach every pixel is background.
TEST_P(RenderTest, RawSplatsCoverTheBlockAndNothingBeyond) {
    BackendWorld world(GetParam());
    FluidDef fluid;
    fluid.spacing = 0.05f;
    fluid.blocks = {FluidBlockDef{{-0.5f, -0.25f, 0.0f}, {0.5f, 0.25f, 0.0f}, glm::vec3(0.0f)}};
    createFluid(world.id, fluid);
    RenderDef def = orthoView(128, 96, 1.5f);
    def.fluid = FluidRenderDef::upTo(1);
    def.fluid.refraction = false;
    def.fluid.opacity = 1.0f;
    def.fluid.colour = {0.1f, 0.4f, 0.9f};
    ScopedRenderer r(world.id, def);
    Frame f = renderFrame(r.id);
    dumpFrame(f, "raw_splats");
    const double pxPerM = 96.0 / 1.5;
    const double reach = 0.5 * fluid.spacing * def.fluid.radiusScale;  // splat radius (m) beyond the outer particles
    const double outerX = 0.5 - 0.5 * fluid.spacing, outerY = 0.25 - 0.5 * fluid.spacing;  // outer particle centres
    int inside = 0, insideWater = 0;
    for (std::uint32_t y = 0; y < f.height; ++y) {
        for (std::uint32_t x = 0; x < f.width; ++x) {
            const double mx = (x + 0.5 - 64.0) / pxPerM, my = (48.0 - (y + 0.5)) / pxPerM;
            const bool background = pixel(f, x, y)[2] == 0;
            if (std::abs(mx) > outerX + reach + 1.0 / pxPerM || std::abs(my) > outerY + reach + 1.0 / pxPerM) {
                ASSERT_TRUE(background) << "pixel " << x << "," << y << " is beyond every splat";
            } else if (std::abs(mx) < outerX && std::abs(my) < outerY) {
                ++inside;
                insideWater += srgbDecode(pixel(f, x, y)[2] / 255.0) >= 0.5 ? 1 : 0;
            }
        }
    }
    // Splats of radius 0.75 spacing overlap everywhere inside. The thinnest
    // point is a lattice cell's centre, 0.707 spacing from four particles:
    // each covers 1 - r^4 = 0.21 there (r = 0.707 / 0.75), together
    // 1 - 0.79^4 = 0.61, so blue is at least 0.9 x 0.61 = 0.55 linear.
    EXPECT_EQ(insideWater, inside);
}

TEST_P(RenderTest, SphereColliderIsDrawnWhereItIs) {
    BackendWorld world(GetParam());
    ColliderDef sphere;
    sphere.kind = ColliderKind::Sphere;
    sphere.position = {-0.5f, 0.0f, 0.0f};
    sphere.radius = 0.3f;
    createCollider(world.id, sphere);
    ScopedRenderer r(world.id, orthoView(64, 64, 2.0f));
    Frame f = renderFrame(r.id);
    // Centre at x = 32 - 0.5 * 32 = 16 px, radius 9.6 px.
    EXPECT_GT(pixel(f, 16, 32)[0], 20);
    EXPECT_EQ(pixel(f, 16 + 12, 32)[0], 0);
    EXPECT_EQ(pixel(f, 48, 32)[0], 0);
}

// A sprite image replaces the round spot: an opaque green square PNG makes
// the whole quad green, corners included; a moving sprite with a stretch is
// lengthened along its velocity by speed x stretch.
TEST_P(RenderTest, SpriteImageAndVelocityStretchShapeTheQuad) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "spindrift_render_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "green.png").string();
    std::vector<std::uint8_t> green(4 * 4 * 4);
    for (std::size_t i = 0; i < green.size(); i += 4) {
        green[i + 1] = 255;
        green[i + 3] = 255;
    }
    ASSERT_NE(stbi_write_png(path.c_str(), 4, 4, 4, green.data(), 16), 0);
    for (float stretch : {0.0f, 0.2f}) {
        BackendWorld world(GetParam());
        EmitterDef e = restingBurst({0.0f, 0.0f, 0.0f}, 1, 0.5f);
        e.speed = {2.0f, 2.0f};
        e.shape.direction = {1.0f, 0.0f, 0.0f};
        e.sprite.texture = path;
        e.sprite.stretch = stretch;
        createEmitter(world.id, e);
        stepWorld(world.id, 0.05f);
        flushWorld(world.id);
        ParticleSnapshot p = readParticles(world.id, EmitterId{1});
        ASSERT_EQ(p.count(), 1u);
        ScopedRenderer r(world.id, orthoView(128, 64, 2.0f));
        Frame f = renderFrame(r.id);
        // Lit pixels (green) span the quad: their centres lie within it.
        std::uint32_t minX = f.width, maxX = 0, minY = f.height, maxY = 0;
        for (std::uint32_t y = 0; y < f.height; ++y) {
            for (std::uint32_t x = 0; x < f.width; ++x) {
                if (pixel(f, x, y)[1] > 128) {
                    EXPECT_EQ(pixel(f, x, y)[0], 0);
                    minX = std::min(minX, x), maxX = std::max(maxX, x);
                    minY = std::min(minY, y), maxY = std::max(maxY, y);
                }
            }
        }
        ASSERT_LE(minX, maxX) << "nothing drawn";
        const double pxPerM = 32.0;
        const double halfLength = 0.25 + (stretch > 0.0f ? 0.5 * 2.0 * stretch : 0.0);  // m, along x
        const double cx = 64.0 + p.position[0].x * pxPerM;
        // Pixel centres inside [c - h, c + h]: the extremes are within a pixel of the edges.
        EXPECT_NEAR(minX + 0.5, cx - halfLength * pxPerM, 1.0) << "stretch " << stretch;
        EXPECT_NEAR(maxX + 0.5, cx + halfLength * pxPerM, 1.0) << "stretch " << stretch;
        EXPECT_NEAR(maxY - minY + 1.0, 0.5 * pxPerM, 1.0) << "stretch " << stretch;
    }
}

// A Box2D body is drawn where it is now: a box rotated by 90 degrees covers
// the pixels of its rotated outline and nothing just beyond it.
TEST_P(RenderTest, BodyIsDrawnWhereItIsNow) {
    WorldDef wd;
    wd.backend = GetParam();
    wd.bodyGravity = glm::vec2(0.0f);
    WorldId world = createWorld(wd);
    BodyDef box;
    box.type = BodyType::Dynamic;
    box.position = {0.5f, 0.0f};
    box.angle = glm::radians(90.0f);
    box.shapes = {boxShape({0.4f, 0.1f})};  // after the turn: 0.2 m wide, 0.8 m tall
    createBody(world, box);
    stepWorld(world, 1.0f / 60.0f);
    {
        ScopedRenderer r(world, orthoView(64, 64, 2.0f));
        Frame f = renderFrame(r.id);
        dumpFrame(f, "body");
        // 32 px per m, centre (32, 32): the box spans x in [0.4, 0.6] m -> px
        // [44.8, 51.2], y in [-0.4, 0.4] m -> px [19.2, 44.8].
        EXPECT_GT(pixel(f, 48, 32)[0], 20);
        EXPECT_GT(pixel(f, 48, 22)[0], 20);
        EXPECT_EQ(pixel(f, 48, 16)[0], 0);  // 0.5 m up: beyond the top
        EXPECT_EQ(pixel(f, 54, 32)[0], 0);  // 0.2 m right of the centre: beyond the side
        EXPECT_EQ(pixel(f, 41, 32)[0], 0);
    }
    destroyWorld(world);
}

// Colours of a body and a collider (BodyDef::colour, ColliderDef::colour)
// reach the pixels through mesh.frag's shading rule, computed here by hand:
// colour x (ambient + 0.65 x max(n . sun, 0)), ambient = 0.35 + 0.15 n.y.
// Both faces seen look at the camera (n = +z): the static box's front cap,
// and the front of the slab that stands for the floor plane (below y = -0.25).
// The sun (0.48, 0.6, 0.64) is a unit vector, so n . sun = 0.64 and the
// factor is 0.35 + 0.65 x 0.64 = 0.766. Tolerance kCodeTolerance (2 codes):
// the read-back's 8-bit sRGB rounding (+-0.5 code) and float rounding in the
// shader; the default grey (0.42, 0.40, 0.37) or wood would be off by 40+.
TEST_P(RenderTest, BodyAndColliderColoursAreShadedBySunAndAmbient) {
    WorldDef wd;
    wd.backend = GetParam();
    wd.bodyGravity = glm::vec2(0.0f);
    WorldId world = createWorld(wd);
    ColliderDef floor;
    floor.kind = ColliderKind::Plane;
    floor.position = {0.0f, -0.25f, 0.0f};
    floor.normal = {0.0f, 1.0f, 0.0f};
    floor.colour = glm::vec3(0.1f, 0.3f, 0.6f);
    createCollider(world, floor);
    BodyDef box = staticBox();
    box.colour = glm::vec3(0.8f, 0.2f, 0.1f);
    createBody(world, box);
    {
        RenderDef def = orthoView(64, 64, 2.0f);
        def.sunDirection = {0.48f, 0.6f, 0.64f};
        ScopedRenderer r(world, def);
        Frame f = renderFrame(r.id);
        dumpFrame(f, "colours");
        const double factor = 0.35 + 0.65 * 0.64;
        // 32 px per m, world origin at pixel (32, 32), y up: the box's centre
        // (0, 0.4) m is at pixel row 32 - 12.8 = 19.2; the floor at y = -0.7 m
        // (0.45 m below its surface) at row 32 + 22.4 = 54.4.
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(pixel(f, 32, 19)[c], srgbByte((*box.colour)[c] * factor), kCodeTolerance)
                << "body, channel " << c;
            EXPECT_NEAR(pixel(f, 32, 54)[c], srgbByte((*floor.colour)[c] * factor), kCodeTolerance)
                << "floor, channel " << c;
            EXPECT_EQ(pixel(f, 32, 32)[c], 0) << "background between them, channel " << c;
        }
    }
    destroyWorld(world);
}


// A slope seen from above by a perspective camera is lit from above even
// where it turns away from the view's centre line: terrain rising 0.1 m per
// metre toward a camera that looks straight ahead (normal (0, 1, -0.1), at a
// positive angle to the view direction, yet facing the eye from below it),
// under a sun straight up. Expected, from surfaceLight's closed form with
// the default white sky and sun: colour x (0.35 + 0.15 n.y + 0.65 n.y). Turning the
// normal toward the camera by the view's centre line instead of the pixel's
// ray flipped it downward, to colour x (0.35 - 0.15 n.y): the dark jagged
// patches of the rain scene's hills.
TEST_P(RenderTest, TerrainSlopeIsLitFromAboveAtTheEdgeOfAPerspectiveView) {
    BackendWorld world(GetParam());
    ColliderDef hills;
    hills.kind = ColliderKind::Terrain;
    hills.position = {-10.0f, -1.0f, -10.0f};
    hills.terrainNx = 2;
    hills.terrainNz = 2;
    hills.terrainSizeX = 20.0f;
    hills.terrainSizeZ = 20.0f;
    hills.heights = {0.0f, 0.0f, 2.0f, 2.0f};  // z = -10: 0 m, z = +10: 2 m
    hills.colour = glm::vec3(0.5f);
    createCollider(world.id, hills);
    RenderDef def = orthoView(64, 64, 2.0f);
    def.camera.orthographic = false;
    def.camera.eye = {0.0f, 1.0f, 3.0f};
    def.camera.target = {0.0f, 1.0f, 0.0f};
    def.sunDirection = {0.0f, 1.0f, 0.0f};
    ScopedRenderer r(world.id, def);
    Frame f = renderFrame(r.id);
    dumpFrame(f, "terrain_slope");
    const double ny = 1.0 / std::sqrt(1.0 + 0.1 * 0.1);
    const double factor = 0.35 + 0.15 * ny + 0.65 * ny;
    // The bottom rows look down onto the slope (about 20 degrees below the
    // horizon at the bottom of a 45 degree view), the middle row at the horizon.
    for (std::uint32_t y : {50u, 56u, 62u}) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(pixel(f, 32, y)[c], srgbByte(0.5 * factor), kCodeTolerance) << "row " << y << ", channel " << c;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, RenderTest, ::testing::Values(Backend::Cpu, Backend::Vulkan),
                         [](const auto& info) { return info.param == Backend::Cpu ? "cpu" : "vulkan"; });

}  // namespace
}  // namespace spindrift::test
