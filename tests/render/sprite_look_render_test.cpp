// Flipbooks, soft particles and weighted blended OIT drawn on both backends,
// against closed forms: the frame a particle shows from its age, the fade
// from the gap to the surface behind it, and the OIT composite from the
// paper's equations (McGuire and Bavoil 2013) and the "over" operator.
// Sprites use opaque PNGs written here, so a pixel's coverage is exactly the
// particle's alpha.
#include "render/render_test_util.h"

#include <filesystem>
#include <vector>

namespace spindrift::test {
namespace {

class SpriteLookTest : public GpuTest, public ::testing::WithParamInterface<Backend> {};

// 8-bit quantisation is +-0.5 code; interpolation and the blending unit's
// 8-bit sRGB round trip add at most another code.
constexpr int kCodeTolerance = 2;

EmitterDef restingBurst(glm::vec3 at, float size, glm::vec4 colour) {
    EmitterDef e;
    e.name = "spot";
    e.capacity = 4;
    e.rate = 0.0f;
    e.bursts = {BurstDef{0.0f, 1}};
    e.shape.center = at;
    e.speed = {0.0f, 0.0f};
    e.lifetime = {10.0f, 10.0f};
    e.size = {size, size};
    e.color = {colour, colour};
    e.statelessGravity = glm::vec3(0.0f);
    return e;
}

// An opaque PNG of `w` x `h` texels, each from `texel(x, y)` (y = 0 the top row).
template <class F>
std::string writePng(const std::string& name, int w, int h, F texel) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "spindrift_sprite_look_test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    std::vector<std::uint8_t> rgba(4 * w * h);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const glm::ivec3 c = texel(x, y);
            for (int k = 0; k < 3; ++k) {
                rgba[4 * (y * w + x) + k] = static_cast<std::uint8_t>(c[k]);
            }
            rgba[4 * (y * w + x) + 3] = 255;
        }
    }
    EXPECT_NE(stbi_write_png(path.c_str(), w, h, 4, rgba.data(), 4 * w), 0);
    return path;
}

// A 2 x 2 sheet of 4 x 4 texel frames in reading order: red, green (top
// row), blue, white (bottom row).
const glm::ivec3 kFrameColours[4] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}};
std::string sheetPng() {
    return writePng("sheet.png", 8, 8, [](int x, int y) { return kFrameColours[(y / 4) * 2 + x / 4]; });
}

// `emitters` (and a collider) stepped for `seconds`, then one frame; the
// emitters' particles' ages in `ages` (one particle each).
Frame renderAfter(Backend backend, const std::vector<EmitterDef>& emitters, float seconds, const RenderDef& def,
                  std::vector<float>* ages = nullptr, const ColliderDef* collider = nullptr) {
    BackendWorld world(backend);
    if (collider) {
        createCollider(world.id, *collider);
    }
    for (const EmitterDef& e : emitters) {
        createEmitter(world.id, e);
    }
    const int steps = static_cast<int>(std::ceil(seconds / 0.5f));  // stepWorld takes at most 1 s
    for (int i = 0; i < steps; ++i) {
        stepWorld(world.id, seconds / float(steps));
    }
    flushWorld(world.id);
    for (std::uint32_t i = 0; ages && i < emitters.size(); ++i) {
        ParticleSnapshot p = readParticles(world.id, EmitterId{i + 1});
        EXPECT_EQ(p.count(), 1u) << "emitter " << i;
        ages->push_back(p.count() == 1 ? p.age[0] : -1.0f);
    }
    ScopedRenderer r(world.id, def);
    return renderFrame(r.id);
}

// One world per backend (a Vulkan world costs seconds to make on lavapipe):
// 32 px per m, sprites side by side along x at x_i = -3.5 + i m.
constexpr std::uint32_t kRowWidth = 256;
RenderDef rowView(glm::vec3 background = glm::vec3(0.0f)) { return orthoView(kRowWidth, 64, 2.0f, background); }
std::uint32_t columnOf(int i) { return static_cast<std::uint32_t>(kRowWidth / 2 + (-3.5 + i) * 32.0); }

// Over the life: frame floor(4 age / life) of the sheet, read left to right,
// top row first; stored and stateless alike. Eight emitters whose bursts
// come at different times show eight ages in one frame.
TEST_P(SpriteLookTest, FlipbookShowsTheFrameOfTheParticlesAge) {
    const std::string sheet = sheetPng();
    const float seconds = 9.0f;
    const float burstAt[4] = {8.0f, 6.0f, 3.0f, 0.5f};  // ages about 1, 3, 6 and 8.5 s: frames 0 to 3
    std::vector<EmitterDef> emitters;
    for (int i = 0; i < 8; ++i) {
        EmitterDef e = restingBurst({-3.5f + float(i), 0.0f, 0.0f}, 0.8f, glm::vec4(1.0f));
        e.bursts = {BurstDef{burstAt[i % 4], 1}};
        e.stateless = i >= 4;
        e.sprite.texture = sheet;
        e.sprite.flipbook.rows = 2;
        e.sprite.flipbook.columns = 2;
        emitters.push_back(e);
    }
    std::vector<float> ages;
    Frame f = renderAfter(GetParam(), emitters, seconds, rowView(), &ages);
    dumpFrame(f, "flipbook_ages");
    for (int i = 0; i < 8; ++i) {
        const float position = 4.0f * ages[i] / 10.0f;
        const int frame = static_cast<int>(std::floor(position));
        ASSERT_GE(frame, 0);
        ASSERT_LT(frame, 4);
        ASSERT_GT(position - float(frame), 0.05f);  // away from a frame change
        ASSERT_LT(position - float(frame), 0.95f);
        EXPECT_EQ(frame, i % 4) << "the bursts' times give frames 0 to 3 in turn";
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(pixel(f, columnOf(i), 32)[c], kFrameColours[frame][c], kCodeTolerance)
                << (i >= 4 ? "stateless" : "stored") << ", age " << ages[i] << ", channel " << c;
        }
    }
}

// At a rate with blending: 1 frame/s, so at age a the sheet shows frame
// floor(a) mod 4 mixed (linear light) toward the next by fract(a). And the
// image is upright: a sprite of a red-over-blue image is red at its top.
TEST_P(SpriteLookTest, FlipbookAtARateLoopsAndCrossFadesAndImagesAreUpright) {
    EmitterDef e = restingBurst({-3.5f, 0.0f, 0.0f}, 0.8f, glm::vec4(1.0f));
    e.sprite.texture = sheetPng();
    e.sprite.flipbook = {2, 2, 0, 1.0f, true};
    EmitterDef upright = restingBurst({-2.5f, 0.0f, 0.0f}, 1.0f, glm::vec4(1.0f));
    upright.sprite.texture = writePng("top_red.png", 4, 4, [](int, int y) {
        return y < 2 ? glm::ivec3(255, 0, 0) : glm::ivec3(0, 0, 255);
    });
    std::vector<float> ages;
    Frame f = renderAfter(GetParam(), {e, upright}, 7.25f, rowView(), &ages);
    dumpFrame(f, "flipbook_rate");
    const float age = ages[0];
    const int a = static_cast<int>(std::floor(age)) % 4, b = (a + 1) % 4;
    const double share = age - std::floor(age);
    ASSERT_GT(share, 0.1);  // a real mix, the test can tell
    ASSERT_LT(share, 0.9);
    for (int c = 0; c < 3; ++c) {
        const double linear = (1.0 - share) * (kFrameColours[a][c] / 255.0) + share * (kFrameColours[b][c] / 255.0);
        EXPECT_NEAR(pixel(f, columnOf(0), 32)[c], srgbByte(linear), kCodeTolerance) << "age " << age << ", channel " << c;
    }
    // The 1 m quad spans rows 16..47; its top quarter is red, its bottom blue.
    EXPECT_GT(pixel(f, columnOf(1), 22)[0], 250);
    EXPECT_EQ(pixel(f, columnOf(1), 22)[2], 0);
    EXPECT_GT(pixel(f, columnOf(1), 42)[2], 250);
    EXPECT_EQ(pixel(f, columnOf(1), 42)[0], 0);
}

// Soft particles: a sprite 0.1 m in front of a box's face adds light scaled
// by gap / distance = 0.25 of what a hard sprite adds; 1 m in front (beyond
// the distance) all of it. Hard and soft sprites side by side, the bare
// face beside them.
TEST_P(SpriteLookTest, SoftParticlesFadeByTheGapToTheSurfaceBehind) {
    ColliderDef box;
    box.kind = ColliderKind::Box;
    box.position = {0.0f, 0.0f, -0.5f};
    box.halfExtents = {5.0f, 3.0f, 0.5f};  // its front face is the plane z = 0
    const std::string white = writePng("white.png", 4, 4, [](int, int) { return glm::ivec3(255); });
    const float gaps[2] = {0.1f, 1.0f};
    std::vector<EmitterDef> emitters;
    for (int i = 0; i < 4; ++i) {  // hard, soft at 0.1 m; hard, soft at 1 m
        EmitterDef e = restingBurst({-3.5f + float(i), 0.0f, gaps[i / 2]}, 0.8f, {0.25f, 0.25f, 0.25f, 1.0f});
        e.sprite.texture = white;
        e.sprite.softDistance = i % 2 == 1 ? 0.4f : 0.0f;
        emitters.push_back(e);
    }
    Frame f = renderAfter(GetParam(), emitters, 0.1f, rowView(), nullptr, &box);
    dumpFrame(f, "soft");
    auto lit = [&](int i) { return srgbDecode(pixel(f, columnOf(i), 32)[1] / 255.0); };
    const double face = lit(6);
    ASSERT_GT(face, 0.0) << "no box face behind the sprites";
    for (int g = 0; g < 2; ++g) {
        const double hard = lit(2 * g) - face, soft = lit(2 * g + 1) - face;
        ASSERT_GT(hard, 0.1) << "the hard sprite added nothing: the test would not tell";
        // One code near 0.4 linear is about 0.005; over the added 0.25: 0.03.
        EXPECT_NEAR(soft / hard, std::min(1.0, gaps[g] / 0.4), 0.04) << "gap " << gaps[g];
    }
}

// One OIT layer is exactly "over": c a + background (1 - a).
TEST_P(SpriteLookTest, OitOfOneLayerIsOver) {
    const glm::vec3 background(0.2f, 0.3f, 0.5f);
    const glm::vec4 c(0.9f, 0.4f, 0.1f, 0.6f);
    EmitterDef e = restingBurst({0.0f, 0.0f, 0.0f}, 1.0f, c);
    e.sprite.texture = writePng("white.png", 4, 4, [](int, int) { return glm::ivec3(255); });
    e.sprite.blend = SpriteBlend::WeightedOit;
    Frame f = renderAfter(GetParam(), {e}, 0.1f, orthoView(64, 64, 2.0f, background));
    for (int k = 0; k < 3; ++k) {
        const double expected = c[k] * c.a + background[k] * (1.0 - c.a);
        EXPECT_NEAR(pixel(f, 32, 32)[k], srgbByte(expected), kCodeTolerance) << "channel " << k;
    }
}

// Two OIT layers at one depth (equal weights but for alpha): the paper's
// composite, sum(w c a) / sum(w a) x (1 - prod(1 - a)) + background x
// prod(1 - a), with w = a x (the depth term, equal here): the same image
// whichever emitter is drawn first (emitters draw in the order they were
// made: red then blue at x = -3.5 m, blue then red at x = -2.5 m).
TEST_P(SpriteLookTest, OitOfTwoLayersIsThePapersCompositeInEitherOrder) {
    const glm::vec3 background(0.1f, 0.1f, 0.1f);
    const glm::vec4 red(1.0f, 0.1f, 0.1f, 0.7f), blue(0.1f, 0.2f, 1.0f, 0.4f);
    const std::string white = writePng("white.png", 4, 4, [](int, int) { return glm::ivec3(255); });
    auto layer = [&](glm::vec4 c, float x) {
        EmitterDef e = restingBurst({x, 0.0f, 0.0f}, 0.8f, c);
        e.sprite.texture = white;
        e.sprite.blend = SpriteBlend::WeightedOit;
        return e;
    };
    Frame f = renderAfter(GetParam(), {layer(red, -3.5f), layer(blue, -3.5f), layer(blue, -2.5f), layer(red, -2.5f)},
                          0.1f, rowView(background));
    const double revealed = (1.0 - red.a) * (1.0 - blue.a);
    for (int i = 0; i < 2; ++i) {
        for (int k = 0; k < 3; ++k) {
            const double average = (red[k] * red.a * red.a + blue[k] * blue.a * blue.a) /
                                   (red.a * red.a + blue.a * blue.a);
            const double expected = average * (1.0 - revealed) + background[k] * revealed;
            EXPECT_NEAR(pixel(f, columnOf(i), 32)[k], srgbByte(expected), kCodeTolerance)
                << (i == 0 ? "red first" : "blue first") << ", channel " << k;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, SpriteLookTest, ::testing::Values(Backend::Cpu, Backend::Vulkan),
                         [](const auto& info) { return info.param == Backend::Cpu ? "cpu" : "vulkan"; });

}  // namespace
}  // namespace spindrift::test
