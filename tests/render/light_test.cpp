// Light (issue 15, item 2): the frame is drawn into a float target, then
// bloom and the tone map write the 8-bit sRGB image. Expected pixels are
// computed here by hand from the published ACES fit (Narkowicz 2016) and the
// sRGB transfer function (IEC 61966-2-1), never from a previous run.
// Validation is on (GpuTest): any message fails a test.
#include "kernels/light.glsl"
#include "render/render_test_util.h"

#include <spindrift/effects.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace spindrift::test {
namespace {

// The published curve, written out again here: x (2.51 x + 0.03) /
// (x (2.43 x + 0.59) + 0.14), clamped to [0, 1].
double publishedAces(double x) {
    return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

TEST(Light, SharedCurveIsThePublishedFit) {
    for (float x : {0.0f, 0.01f, 0.18f, 0.5f, 1.0f, 2.0f, 4.0f, 16.0f, 1000.0f}) {
        EXPECT_NEAR(kernels::acesFilm(x), publishedAces(x), 1e-6) << x;
    }
    // By hand: f(1) = 2.54 / 3.16 = 0.80380 (the blog's "1 maps to ~0.8").
    EXPECT_NEAR(kernels::acesFilm(1.0f), 2.54 / 3.16, 1e-6);
    // Bloom: nothing at or below 1; above it the share over 1 of the brightest channel.
    EXPECT_EQ(kernels::bloomShare(0.0f), 0.0f);
    EXPECT_EQ(kernels::bloomShare(1.0f), 0.0f);
    EXPECT_NEAR(kernels::bloomShare(4.0f), 0.75f, 1e-7);
}

// The public API names the key of a bad value as [render] spells it.
TEST(Light, BadValuesNameTheirKey) {
    auto field = [](RenderDef def) -> std::string {
        try {
            validateRenderDef(def);
        } catch (const FieldError& e) {
            return e.field();
        }
        return "accepted";
    };
    RenderDef def;
    EXPECT_EQ(field(def), "accepted");
    EXPECT_EQ(def.exposure, 1.0f) << "exposure is a multiplier, 1 by default";
    def.exposure = 0.0f;
    EXPECT_EQ(field(def), "exposure");
    def = RenderDef{};
    def.exposure = std::nanf("");
    EXPECT_EQ(field(def), "exposure");
    def = RenderDef{};
    def.toneMap = static_cast<ToneMap>(2);
    EXPECT_EQ(field(def), "tone_map");
    def = RenderDef{};
    def.bloom = -0.1f;
    EXPECT_EQ(field(def), "bloom");
    def.bloom = 0.0f;
    EXPECT_EQ(field(def), "accepted") << "0 turns bloom off";
}

class LightRender : public GpuTest {};

RenderDef flatView(glm::vec3 background) {
    RenderDef def;
    def.width = 64;
    def.height = 36;
    def.camera.eye = {0.0f, 0.0f, 5.0f};
    def.camera.orthographic = true;
    def.camera.orthoHeight = 2.0f;
    def.background.kind = BackgroundKind::Colour;
    def.background.colour = background;
    def.bloom = 0.0f;
    return def;
}

// Every pixel's rgb within `tolerance` codes of `expected`.
void expectEveryPixel(const Frame& f, const int expected[3], int tolerance) {
    for (std::uint32_t y = 0; y < f.height; ++y) {
        for (std::uint32_t x = 0; x < f.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                ASSERT_NEAR(pixel(f, x, y)[c], expected[c], tolerance) << x << "," << y << " channel " << c;
            }
        }
    }
}

// A known HDR colour through the ACES fit. By hand: f(2) = 10.1 / 11.04 =
// 0.91486, sRGB-encoded 0.96160, code 245.2; f(0.5) = 0.6425 / 1.0425 =
// 0.61631, 0.80731, code 205.9; f(0.1) = 0.0281 / 0.2233 = 0.12584, 0.38982,
// code 99.4. Tolerance one code (1/255): the background's colour is stored as
// 16-bit floats (relative error 2^-11, under 0.1 code here) and the device's
// float-to-sRGB conversion may round either way near a half code (Vulkan
// allows the encode some error); none of the three is near a half code, so
// one code is room for the device, not for a wrong curve (a plain clamp
// would give 255, 188 and 89). Exposure 2 of half the colour is the same
// light.
TEST_F(LightRender, KnownHdrColourGoesThroughTheAcesCurve) {
    const int expected[3] = {245, 206, 99};
    for (const auto& [colour, exposure] : {std::pair{glm::vec3(2.0f, 0.5f, 0.1f), 1.0f},
                                           std::pair{glm::vec3(1.0f, 0.25f, 0.05f), 2.0f}}) {
        BackendWorld world(Backend::Cpu);
        RenderDef def = flatView(colour);
        EXPECT_EQ(def.toneMap, ToneMap::Aces) << "ACES is the default";
        def.exposure = exposure;
        ScopedRenderer r(world.id, def);
        Frame f = renderFrame(r.id);
        dumpFrame(f, "light_aces");
        expectEveryPixel(f, expected, 1);
    }
}

// "none" with exposure 1 is a clamp of the linear colour, then the sRGB
// encode: what the 8-bit target gave before the float target. Tolerance one
// code: the encode's rounding (above).
TEST_F(LightRender, NoToneMapIsAClampOfTheLinearColour) {
    BackendWorld world(Backend::Cpu);
    const glm::vec3 colour{0.3f, 0.7f, 1.6f};
    RenderDef def = flatView(colour);
    def.toneMap = ToneMap::None;
    ScopedRenderer r(world.id, def);
    Frame f = renderFrame(r.id);
    const int expected[3] = {srgbByte(0.3), srgbByte(0.7), 255};
    expectEveryPixel(f, expected, 1);
}

// One resting additive sprite of `colour` (linear, alpha 1), 0.2 m across,
// at the centre of a black 160x90 frame 2 m high (45 px/m: radius 4.5 px).
Frame spriteFrame(glm::vec3 colour, float bloom) {
    BackendWorld world(Backend::Cpu);
    EmitterDef e;
    e.name = "spot";
    e.capacity = 1;
    e.rate = 0.0f;
    e.bursts = {BurstDef{0.0f, 1}};
    e.speed = {0.0f, 0.0f};
    e.lifetime = {10.0f, 10.0f};
    e.size = {0.2f, 0.2f};
    e.color = {glm::vec4(colour, 1.0f), glm::vec4(colour, 1.0f)};
    e.statelessGravity = glm::vec3(0.0f);
    createEmitter(world.id, e);
    stepWorld(world.id, 1.0f / 60.0f);
    RenderDef def = flatView(glm::vec3(0.0f));
    def.width = 160;
    def.height = 90;
    def.toneMap = ToneMap::None;  // the glow's own light, not the curve's
    def.bloom = bloom;
    ScopedRenderer r(world.id, def);
    return renderFrame(r.id);
}

// The brightest channel of the pixels between `inner` and `outer` pixels
// from the frame's centre (80, 45).
int brightestInRing(const Frame& f, double inner, double outer) {
    int most = 0;
    for (std::uint32_t y = 0; y < f.height; ++y) {
        for (std::uint32_t x = 0; x < f.width; ++x) {
            const double r = std::hypot(x + 0.5 - 80.0, y + 0.5 - 45.0);
            if (r >= inner && r < outer) {
                for (int c = 0; c < 3; ++c) most = std::max<int>(most, pixel(f, x, y)[c]);
            }
        }
    }
    return most;
}

// A sprite of 8 (linear) blooms: pixels 8 to 24 px from its centre, outside
// its 4.5 px radius, are lit, more near it than far; without bloom they stay
// black (thresholds in codes: the glow is a share of 7 x the sprite's light
// spread over a few hundred pixels). A sprite of 0.9 has nothing above 1: bloom changes no pixel.
TEST_F(LightRender, BloomSpreadsOnlyLightAboveOne) {
    const Frame off = spriteFrame(glm::vec3(8.0f), 0.0f);
    const Frame on = spriteFrame(glm::vec3(8.0f), 1.0f);
    dumpFrame(on, "light_bloom");
    EXPECT_EQ(brightestInRing(off, 6.0, 200.0), 0) << "no light outside the sprite without bloom";
    EXPECT_EQ(brightestInRing(off, 0.0, 2.0), 255) << "the sprite itself clips";
    const int near = brightestInRing(on, 8.0, 12.0);
    const int far = brightestInRing(on, 20.0, 24.0);
    EXPECT_GT(near, 20) << "the glow reaches past the sprite";
    EXPECT_GT(far, 0);
    EXPECT_GT(near, far) << "and fades with distance";

    const Frame dimOff = spriteFrame(glm::vec3(0.9f), 0.0f);
    const Frame dimOn = spriteFrame(glm::vec3(0.9f), 1.0f);
    EXPECT_EQ(dimOn.rgba, dimOff.rgba) << "nothing above 1: nothing blooms";
    EXPECT_GT(brightestInRing(dimOn, 0.0, 2.0), 200);
}

}  // namespace
}  // namespace spindrift::test
