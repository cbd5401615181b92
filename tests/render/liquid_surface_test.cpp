// The 2D liquid surface (issue 15): the field's constants against their
// definitions, and two checks of a resting tank's picture that need no
// reference image: no pixel of the liquid's interior shows the background,
// and the flat top's edge is level to a third of a particle spacing.
// Validation is on (GpuTest): any message fails a test.
#include "render/surface_field.h"

#include "fluid/fluid_test_util.h"
#include "render/render_test_util.h"

#include <spindrift/fluid.h>

#include <algorithm>
#include <cmath>

namespace spindrift::test {
namespace {

// The kernel as surface_field.frag evaluates it, q = distance / radius.
double kernel(double q) { return q < 1.0 ? std::pow(1.0 - q * q, 3.0) : 0.0; }

TEST(LiquidSurface, KernelsSumToOneAtRestDensity) {
    // The field at a point of a square lattice of particles at rest density,
    // summed directly; at lattice points, between them and off-centre.
    const double s = 0.02, radius = render::kSurfaceKernelSpacings * s;
    for (const glm::dvec2 at : {glm::dvec2(0.0, 0.0), glm::dvec2(0.5 * s, 0.5 * s), glm::dvec2(0.3 * s, 0.1 * s)}) {
        double sum = 0.0;
        for (int i = -10; i <= 10; ++i) {
            for (int j = -10; j <= 10; ++j) {
                sum += render::surfaceAmplitude(1.0f) * kernel(glm::length(glm::dvec2(i * s, j * s) - at) / radius);
            }
        }
        EXPECT_NEAR(sum, 1.0, 0.02) << at.x << ", " << at.y;
    }
    // Sparse particles carry more volume, at most kSurfaceMaxVolume.
    EXPECT_FLOAT_EQ(render::surfaceAmplitude(0.5f), 2.0f * render::surfaceAmplitude(1.0f));
    EXPECT_FLOAT_EQ(render::surfaceAmplitude(0.01f), render::kSurfaceMaxVolume * render::surfaceAmplitude(1.0f));
    EXPECT_FLOAT_EQ(render::surfaceAmplitude(1.5f), render::surfaceAmplitude(1.0f));
}

TEST(LiquidSurface, FoamWhereFastOrSparse) {
    EXPECT_EQ(render::surfaceFoam(0.0f, 1.0f), 0.0f);   // water at rest
    EXPECT_EQ(render::surfaceFoam(0.5f, 0.5f), 0.0f);   // a calm flat top (rho/rho0 about 0.5)
    EXPECT_EQ(render::surfaceFoam(0.0f, 0.01f), 1.0f);  // spray
    EXPECT_GT(render::surfaceFoam(20.0f, 1.0f), 0.0f);  // a fast jet whitens ...
    EXPECT_LT(render::surfaceFoam(20.0f, 1.0f), 0.5f);  // ... but stays water
    EXPECT_LE(render::surfaceFoam(4.0f, 1.0f), render::surfaceFoam(6.0f, 1.0f));
    // Velocity stretch: the distance moved in 0.02 s, at most one radius more.
    EXPECT_FLOAT_EQ(render::surfaceStretch(0.0f, 0.04f), 1.0f);
    EXPECT_FLOAT_EQ(render::surfaceStretch(1.0f, 0.04f), 1.5f);
    EXPECT_FLOAT_EQ(render::surfaceStretch(100.0f, 0.04f), 2.0f);
}

TEST(LiquidSurface, KernelsNearAPlaneGetAMirrorImage) {
    FluidWorld world;
    createCollider(world.id, wall({0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}));  // floor y = 0
    FluidDef def;
    def.spacing = 0.02f;
    // Two particles: 0.01 m above the floor (inside the kernel radius) and
    // 0.5 m above it (outside).
    def.blocks.push_back(FluidBlockDef{{0.0f, 0.0f, 0.0f}, {0.02f, 0.02f, 0.0f}, glm::vec3(0.0f)});
    def.blocks.push_back(FluidBlockDef{{0.0f, 0.49f, 0.0f}, {0.02f, 0.51f, 0.0f}, glm::vec3(0.0f)});
    const FluidId fluid = createFluid(world.id, def);
    std::vector<render::SplatInstance> out(2);
    const FluidSnapshot s = readFluid(world.id, fluid);
    ASSERT_EQ(s.count(), 2u);
    for (std::size_t i = 0; i < 2; ++i) out[i].centre = glm::vec4(s.position[i], 0.0f);
    out.push_back(render::SplatInstance{});  // a splash after the water: stays last
    out.back().shade.z = static_cast<float>(render::SplatKind::Splash);
    ASSERT_EQ(render::surfaceInstances(world.id, fluid, false, out), 3u);
    ASSERT_EQ(out.size(), 4u);
    const float low = std::min(s.position[0].y, s.position[1].y);
    EXPECT_NEAR(out[2].centre.y, -low, 1e-6f) << "the mirror of the low particle, behind the floor";
    EXPECT_FLOAT_EQ(out[2].centre.w, render::kSurfaceKernelSpacings * def.spacing);
    EXPECT_EQ(out[3].shade.z, static_cast<float>(render::SplatKind::Splash));
}

TEST(LiquidSurface, StyleAndScaleAreCheckedWhereTheyEnter) {
    RenderDef def;
    EXPECT_EQ(def.fluid.style, FluidStyle::Surface);
    EXPECT_EQ(FluidRenderDef::upTo(7).style, FluidStyle::Splats) << "the splat steps select the splat style";
    validateRenderDef(def);
    def.fluid.style = static_cast<FluidStyle>(7);
    EXPECT_THROW(validateRenderDef(def), Error);
    def.fluid.style = FluidStyle::Splats;
    def.fluid.surfaceScale = 0.1f;
    EXPECT_THROW(validateRenderDef(def), Error);
    def.fluid.surfaceScale = 1.0f;
    validateRenderDef(def);
}

// A tank 1 m wide (floor and walls drawn), filled 0.3 m deep with particles
// 0.05 m apart, stepped for `seconds`, seen from the front at 300 pixels per
// metre (a spacing is 15 pixels) against a red background.
struct RestingTank {
    static constexpr float kWidth = 1.0f, kDepth = 0.3f, kSpacing = 0.05f;
    static constexpr std::uint32_t kW = 320, kH = 180;
    static constexpr float kViewHeight = 0.6f;
    static constexpr glm::vec2 kViewCentre{0.5f, 0.2f};
    static constexpr glm::vec3 kBackground{0.6f, 0.05f, 0.05f};

    explicit RestingTank(float seconds) {
        closedBox(world.id, {0.0f, 0.0f, 0.0f}, {kWidth, 2.0f, 1.0f}, 2);
        FluidDef def;
        def.spacing = kSpacing;
        def.blocks.push_back(FluidBlockDef{{0.0f, 0.0f, 0.0f}, {kWidth, kDepth, 0.0f}, glm::vec3(0.0f)});
        fluid = createFluid(world.id, def);
        for (int i = 0; i < int(seconds * 60.0f); ++i) stepWorld(world.id, 1.0f / 60.0f);
        RenderDef r;
        r.width = kW;
        r.height = kH;
        r.camera.eye = {kViewCentre.x, kViewCentre.y, 4.0f};
        r.camera.target = {kViewCentre.x, kViewCentre.y, 0.0f};
        r.camera.orthographic = true;
        r.camera.orthoHeight = kViewHeight;
        r.background.kind = BackgroundKind::Colour;
        r.background.colour = kBackground;
        r.toneMap = ToneMap::None;  // the background's code is a closed form of its linear colour
        r.bloom = 0.0f;
        ScopedRenderer renderer(world.id, r);
        frame = renderFrame(renderer.id);
        dumpFrame(frame, "resting_tank");
    }
    static float metresPerPixel() { return kViewHeight / float(kH); }
    static float column(float x) { return (x - kViewCentre.x) / metresPerPixel() + 0.5f * float(kW); }
    static float row(float y) { return (kViewCentre.y - y) / metresPerPixel() + 0.5f * float(kH); }
    /// How far pixel (x, y) is from the background (largest channel difference, codes).
    int offBackground(std::uint32_t x, std::uint32_t y) const {
        int most = 0;
        for (int c = 0; c < 3; ++c) most = std::max(most, std::abs(pixel(frame, x, y)[c] - srgbByte(kBackground[c])));
        return most;
    }
    float topParticle() const {
        const FluidSnapshot s = readFluid(world.id, fluid);
        float top = 0.0f;
        for (const glm::vec3& p : s.position) top = std::max(top, p.y);
        return top;
    }
    float fastestParticle() const {
        const FluidSnapshot s = readFluid(world.id, fluid);
        float fastest = 0.0f;
        for (const glm::vec3& v : s.velocity) fastest = std::max(fastest, glm::length(v));
        return fastest;
    }

    FluidWorld world;
    FluidId fluid;
    Frame frame;
};

class LiquidSurfaceRender : public GpuTest {};

// A pixel "shows the background" when it is closer to it than half the
// change one layer of water of the scene's opacity makes (the largest
// channel's, in codes): less than half covered. Clear water in front of a
// uniform background, refracted or not, changes it by the whole.
int showsBackgroundWithin() {
    const FluidRenderDef water;
    const glm::vec3 layer = glm::mix(RestingTank::kBackground, water.colour, water.opacity);
    int change = 0;
    for (int c = 0; c < 3; ++c) change = std::max(change, std::abs(srgbByte(layer[c]) - srgbByte(RestingTank::kBackground[c])));
    return change / 2;
}

TEST_F(LiquidSurfaceRender, RestingTankShowsNoBackgroundInside) {
    const RestingTank tank(1.0f);
    ASSERT_LT(tank.fastestParticle(), 0.1f) << "the tank has not come to rest";
    // The interior: a spacing in from the walls, the floor and the highest
    // particle's centre.
    const float top = tank.topParticle();
    const auto x0 = std::uint32_t(std::ceil(RestingTank::column(RestingTank::kSpacing)));
    const auto x1 = std::uint32_t(std::floor(RestingTank::column(RestingTank::kWidth - RestingTank::kSpacing)));
    const auto y0 = std::uint32_t(std::ceil(RestingTank::row(top - RestingTank::kSpacing)));
    const auto y1 = std::uint32_t(std::floor(RestingTank::row(RestingTank::kSpacing)));
    ASSERT_GT(x1, x0 + 200);
    ASSERT_GT(y1, y0 + 40);
    const int within = showsBackgroundWithin();
    ASSERT_GT(within, 48);
    std::size_t background = 0;
    int nearest = 255;
    for (std::uint32_t y = y0; y <= y1; ++y) {
        for (std::uint32_t x = x0; x <= x1; ++x) {
            background += tank.offBackground(x, y) <= within ? 1 : 0;
            nearest = std::min(nearest, tank.offBackground(x, y));
        }
    }
    EXPECT_EQ(background, 0u) << "of " << (x1 - x0 + 1) * (y1 - y0 + 1) << " interior pixels (the nearest is "
                              << nearest << " codes off); SPINDRIFT_RENDER_DUMP=dir writes the frame";
}

TEST_F(LiquidSurfaceRender, RestingFlatTopIsLevelToAThirdOfASpacing) {
    const RestingTank tank(1.0f);
    ASSERT_LT(tank.fastestParticle(), 0.1f) << "the tank has not come to rest";
    // Each column's edge: the first row from the top off the background.
    // Columns a spacing and a half in from the walls.
    const auto x0 = std::uint32_t(std::ceil(RestingTank::column(1.5f * RestingTank::kSpacing)));
    const auto x1 = std::uint32_t(std::floor(RestingTank::column(RestingTank::kWidth - 1.5f * RestingTank::kSpacing)));
    const auto yFloor = std::uint32_t(RestingTank::row(0.0f));
    std::uint32_t highest = RestingTank::kH, lowest = 0;
    for (std::uint32_t x = x0; x <= x1; ++x) {
        std::uint32_t y = 0;
        while (y < yFloor && tank.offBackground(x, y) <= 40) ++y;
        ASSERT_LT(y, yFloor) << "no liquid in column " << x;
        highest = std::min(highest, y);
        lowest = std::max(lowest, y);
    }
    const float variation = float(lowest - highest) * RestingTank::metresPerPixel();
    EXPECT_LT(variation, RestingTank::kSpacing / 3.0f)
        << "edge rows " << highest << ".." << lowest << " across columns " << x0 << ".." << x1;
    // And it is the liquid's top: within a spacing of the highest particle.
    const float edge = RestingTank::kViewCentre.y - (float(highest) + 0.5f - 0.5f * float(RestingTank::kH)) *
                                                       RestingTank::metresPerPixel();
    EXPECT_NEAR(edge, tank.topParticle(), RestingTank::kSpacing);
}

// The depth tint where the surface leaves the frame: a block of water seen
// by a camera rolled 15 degrees, so its flat top crosses the frame's top edge
// (right of the crossing the surface is out of the frame, left of it in).
// On a row 6 pixels under the top edge, from 4 pixels left of the crossing's
// column to 16 right (where the surface is 5 pixels or more above the row,
// clear of the rim), the water's colour stays within 4 codes: its depth
// under the surface, or under the frame's edge, is about the same 6 pixels
// on both sides. Counting lookups above the frame as water tinted the right
// side as deep: this test against that shader saw the colour change by 42,
// 21 and 25 codes (red, green, blue) over those 20 pixels.
TEST_F(LiquidSurfaceRender, DepthTintHasNoSeamWhereTheSurfaceLeavesTheFrame) {
    FluidWorld world;
    FluidDef def;
    def.spacing = 0.05f;
    def.blocks.push_back(FluidBlockDef{{0.0f, 0.0f, 0.0f}, {1.0f, 0.3f, 0.0f}, glm::vec3(0.0f)});
    createFluid(world.id, def);
    RenderDef r = orthoView(320, 180, 0.3f, RestingTank::kBackground);
    r.camera.eye = {0.5f, 0.2f, 4.0f};
    r.camera.target = {0.5f, 0.2f, 0.0f};
    r.camera.up = {std::sin(glm::radians(15.0f)), std::cos(glm::radians(15.0f)), 0.0f};
    r.fluid.refraction = false;  // the tint alone
    ScopedRenderer renderer(world.id, r);
    const Frame f = renderFrame(renderer.id);
    dumpFrame(f, "tint_at_the_frame_top");
    auto water = [&](std::uint32_t x, std::uint32_t y) {
        int most = 0;
        for (int c = 0; c < 3; ++c) {
            most = std::max(most, std::abs(pixel(f, x, y)[c] - srgbByte(RestingTank::kBackground[c])));
        }
        return most > 40;
    };
    // The crossing: the first water pixel of the top row, with air left of it.
    std::uint32_t crossing = 0;
    while (crossing < f.width && !water(crossing, 0)) ++crossing;
    ASSERT_GT(crossing, 40u) << "the surface does not cross the frame's top edge";
    ASSERT_LT(crossing, f.width - 40u) << "the surface does not cross the frame's top edge";
    const std::uint32_t y = 6;
    for (int c = 0; c < 3; ++c) {
        int lowest = 255, highest = 0;
        for (std::uint32_t x = crossing - 4; x <= crossing + 16; ++x) {
            ASSERT_TRUE(water(x, y)) << "pixel " << x << " of row " << y << " is not water";
            lowest = std::min(lowest, int(pixel(f, x, y)[c]));
            highest = std::max(highest, int(pixel(f, x, y)[c]));
        }
        EXPECT_LE(highest - lowest, 4) << "channel " << c << " along row " << y << " around column " << crossing
                                       << ", where the surface leaves the frame";
    }
}


// The depth tint under a pocket of air: a block of water 0.6 m deep with a
// 0.2 m square pocket 0.35 m above the floor. On a row 0.2 m under the
// pocket (within the tint's 0.5 m reach), across the pocket's left edge, no
// two neighbouring pixels differ by more than 4 codes: the water above a
// point changes by the pocket's 0.15 m across the edge (0.3 of the reach)
// and should be spread over the pocket's neighbourhood, not drawn as a seam.
// The tint taken from the first air going up, averaged over three columns,
// jumped 0.5 of the reach at the edge: this test against that shader saw a
// step of 6 codes between two pixels; the water above, averaged over five
// columns, gives 3.
TEST_F(LiquidSurfaceRender, DepthTintHasNoSeamUnderAPocketOfAir) {
    FluidWorld world;
    FluidDef def;
    def.spacing = 0.025f;
    def.blocks.push_back(FluidBlockDef{{0.0f, 0.0f, 0.0f}, {1.0f, 0.35f, 0.0f}, glm::vec3(0.0f)});
    def.blocks.push_back(FluidBlockDef{{0.0f, 0.35f, 0.0f}, {0.4f, 0.6f, 0.0f}, glm::vec3(0.0f)});
    def.blocks.push_back(FluidBlockDef{{0.6f, 0.35f, 0.0f}, {1.0f, 0.6f, 0.0f}, glm::vec3(0.0f)});
    def.blocks.push_back(FluidBlockDef{{0.4f, 0.55f, 0.0f}, {0.6f, 0.6f, 0.0f}, glm::vec3(0.0f)});
    createFluid(world.id, def);
    constexpr std::uint32_t kW = 320, kH = 180;
    constexpr float kHeight = 0.8f;  // m, seen by the orthographic camera
    RenderDef r = orthoView(kW, kH, kHeight, RestingTank::kBackground);
    r.camera.eye = {0.5f, 0.3f, 4.0f};
    r.camera.target = {0.5f, 0.3f, 0.0f};
    r.fluid.refraction = false;  // the tint alone
    ScopedRenderer renderer(world.id, r);
    const Frame f = renderFrame(renderer.id);
    dumpFrame(f, "tint_under_a_pocket");
    const float pixelsPerMetre = float(kH) / kHeight;
    auto column = [&](float x) { return std::uint32_t(0.5f * float(kW) + (x - 0.5f) * pixelsPerMetre); };
    const auto y = std::uint32_t(0.5f * float(kH) - (0.15f - 0.3f) * pixelsPerMetre);
    // The pocket is drawn: air (the background) in its middle.
    const auto pocketRow = std::uint32_t(0.5f * float(kH) - (0.45f - 0.3f) * pixelsPerMetre);
    int offBackground = 0;
    for (int c = 0; c < 3; ++c) {
        offBackground = std::max(offBackground, std::abs(pixel(f, column(0.5f), pocketRow)[c] -
                                                          srgbByte(RestingTank::kBackground[c])));
    }
    ASSERT_LE(offBackground, 40) << "no pocket of air drawn";
    int largest = 0;
    for (std::uint32_t x = column(0.25f); x < column(0.55f); ++x) {
        for (int c = 0; c < 3; ++c) {
            largest = std::max(largest, std::abs(int(pixel(f, x + 1, y)[c]) - int(pixel(f, x, y)[c])));
        }
    }
    EXPECT_LE(largest, 4) << "largest step between neighbouring pixels on row " << y << " under the pocket's edge";
    // And the tint sees the pocket: the water under it is lighter than the
    // water under the full 0.6 m (0.3 of the reach less water above).
    int lighter = 0;
    for (int c = 0; c < 3; ++c) {
        lighter = std::max(lighter, int(pixel(f, column(0.5f), y)[c]) - int(pixel(f, column(0.15f), y)[c]));
    }
    EXPECT_GE(lighter, 10) << "the water under the pocket is not lighter";
}

}  // namespace
}  // namespace spindrift::test
