// The 3D screen-space liquid (issue 15; src/render/screen_fluid_pass.cpp):
// three checks of a resting 3D tank's picture that need no reference image.
// Seen from the front, no pixel of the water's interior shows the
// background and the top's edge is level to a third of a spacing; seen from
// above with the sun overhead, the flat top reflects the sun's highlight
// nearly everywhere, which only a surface whose normals stand within about
// 6 degrees of vertical does (unsmoothed spheres would give it to about 1 %
// of their area). Validation is on (GpuTest): any message fails a test.
#include "fluid/fluid_test_util.h"
#include "render/render_test_util.h"

#include <spindrift/fluid.h>

#include <algorithm>
#include <cmath>

namespace spindrift::test {
namespace {

// A 3D tank 0.6 m wide and 0.3 m deep (front to back), filled 0.25 m high
// with particles 0.05 m apart, stepped for a second. Colliders are not
// drawn, so what is not water is the red background.
struct RestingTank3D {
    static constexpr float kWidth = 0.6f, kFill = 0.25f, kDepth = 0.3f, kSpacing = 0.05f;
    static constexpr std::uint32_t kW = 320, kH = 180;
    static constexpr float kViewHeight = 0.5f;
    static constexpr glm::vec3 kBackground{0.6f, 0.05f, 0.05f};

    RestingTank3D() {
        closedBox(world.id, {0.0f, 0.0f, 0.0f}, {kWidth, 1.0f, kDepth}, 3);
        FluidDef def;
        def.dimension = 3;
        def.spacing = kSpacing;
        def.blocks.push_back(FluidBlockDef{{0.0f, 0.0f, 0.0f}, {kWidth, kFill, kDepth}, glm::vec3(0.0f)});
        fluid = createFluid(world.id, def);
        for (int i = 0; i < 60; ++i) stepWorld(world.id, 1.0f / 60.0f);
    }
    /// An orthographic frame looking along -z (front) or -y (top) at `centre`.
    Frame render(glm::vec3 centre, bool fromAbove, const std::string& name) const {
        RenderDef r;
        r.width = kW;
        r.height = kH;
        r.drawColliders = false;
        r.camera.target = centre;
        r.camera.eye = centre + (fromAbove ? glm::vec3(0.0f, 3.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 3.0f));
        r.camera.up = fromAbove ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
        r.camera.orthographic = true;
        r.camera.orthoHeight = kViewHeight;
        r.background.kind = BackgroundKind::Colour;
        r.background.colour = kBackground;
        r.sunDirection = {0.0f, 1.0f, 0.0f};
        r.toneMap = ToneMap::None;  // codes are closed forms of linear colours
        r.bloom = 0.0f;
        ScopedRenderer renderer(world.id, r);
        Frame f = renderFrame(renderer.id);
        dumpFrame(f, name);
        return f;
    }
    static float metresPerPixel() { return kViewHeight / float(kH); }
    float topParticle() const {
        float top = 0.0f;
        for (const glm::vec3& p : readFluid(world.id, fluid).position) top = std::max(top, p.y);
        return top;
    }

    FluidWorld world;
    FluidId fluid;
};

int offBackground(const Frame& f, std::uint32_t x, std::uint32_t y) {
    int most = 0;
    for (int c = 0; c < 3; ++c) {
        most = std::max(most, std::abs(pixel(f, x, y)[c] - srgbByte(RestingTank3D::kBackground[c])));
    }
    return most;
}

class ScreenFluidRender : public GpuTest {};

TEST_F(ScreenFluidRender, RestingTankFromTheFrontShowsNoBackgroundInsideAndALevelTop) {
    const RestingTank3D tank;
    ASSERT_LT(maxSpeed(readFluid(tank.world.id, tank.fluid)), 0.1f) << "the tank has not come to rest";
    const glm::vec3 centre{0.5f * RestingTank3D::kWidth, 0.2f, 0.5f * RestingTank3D::kDepth};
    const Frame f = tank.render(centre, false, "screen_fluid_front");
    const float m = RestingTank3D::metresPerPixel();
    auto column = [&](float x) { return (x - centre.x) / m + 0.5f * float(RestingTank3D::kW); };
    auto row = [&](float y) { return (centre.y - y) / m + 0.5f * float(RestingTank3D::kH); };
    const float s = RestingTank3D::kSpacing;
    const float top = tank.topParticle();

    // The interior, a spacing in from the walls, the floor and the highest
    // particle's centre, looks through 0.3 m of water: its absorption alone
    // (water colour^(4 x 0.3) on the red channel, 0.1^1.2) takes 65 % or more
    // off the background's red, over 100 codes; 40 is a generous margin.
    const auto x0 = std::uint32_t(std::ceil(column(s)));
    const auto x1 = std::uint32_t(std::floor(column(RestingTank3D::kWidth - s)));
    const auto y0 = std::uint32_t(std::ceil(row(top - s)));
    const auto y1 = std::uint32_t(std::floor(row(s)));
    ASSERT_GT(x1, x0 + 150);
    ASSERT_GT(y1, y0 + 40);
    std::size_t background = 0;
    for (std::uint32_t y = y0; y <= y1; ++y) {
        for (std::uint32_t x = x0; x <= x1; ++x) background += offBackground(f, x, y) <= 40 ? 1 : 0;
    }
    EXPECT_EQ(background, 0u) << "of " << (x1 - x0 + 1) * (y1 - y0 + 1)
                              << " interior pixels; SPINDRIFT_RENDER_DUMP=dir writes the frame";

    // The top's edge in each column a spacing and a half in from the walls:
    // level to a third of a spacing, and within a spacing of the highest
    // particle's centre (the spheres reach 0.75 spacing above it).
    const auto e0 = std::uint32_t(std::ceil(column(1.5f * s)));
    const auto e1 = std::uint32_t(std::floor(column(RestingTank3D::kWidth - 1.5f * s)));
    const auto yFloor = std::uint32_t(row(0.0f));
    std::uint32_t highest = RestingTank3D::kH, lowest = 0;
    for (std::uint32_t x = e0; x <= e1; ++x) {
        std::uint32_t y = 0;
        while (y < yFloor && offBackground(f, x, y) <= 40) ++y;
        ASSERT_LT(y, yFloor) << "no water in column " << x;
        highest = std::min(highest, y);
        lowest = std::max(lowest, y);
    }
    EXPECT_LT(float(lowest - highest) * m, s / 3.0f) << "edge rows " << highest << ".." << lowest;
    const float edge = centre.y - (float(highest) + 0.5f - 0.5f * float(RestingTank3D::kH)) * m;
    EXPECT_NEAR(edge, top, s);
}

TEST_F(ScreenFluidRender, RestingTopFromAboveIsSmoothEnoughToReflectTheSunEverywhere) {
    const RestingTank3D tank;
    const glm::vec3 centre{0.5f * RestingTank3D::kWidth, 0.0f, 0.5f * RestingTank3D::kDepth};
    const Frame f = tank.render(centre, true, "screen_fluid_top");
    // Sun, eye and a level surface's normal all point up: the highlight is
    // 3 (screen_fluid.frag's kSpecular) where the normal is vertical and
    // falls as cos^200 of its tilt, so the pixel's red channel (water's
    // own red is 0.1 or less) saturates only where the tilt is under about
    // 6 degrees (3 cos^200 >= 0.9). The top's interior, a spacing in from
    // the walls (their mirror images are not part of the smoothing).
    const float m = RestingTank3D::metresPerPixel();
    const float s = RestingTank3D::kSpacing;
    const float halfW = 0.5f * RestingTank3D::kWidth - s, halfD = 0.5f * RestingTank3D::kDepth - s;
    const auto x0 = std::uint32_t(std::ceil(0.5f * float(RestingTank3D::kW) - halfW / m));
    const auto x1 = std::uint32_t(std::floor(0.5f * float(RestingTank3D::kW) + halfW / m));
    const auto y0 = std::uint32_t(std::ceil(0.5f * float(RestingTank3D::kH) - halfD / m));
    const auto y1 = std::uint32_t(std::floor(0.5f * float(RestingTank3D::kH) + halfD / m));
    std::size_t lit = 0, all = 0;
    for (std::uint32_t y = y0; y <= y1; ++y) {
        for (std::uint32_t x = x0; x <= x1; ++x) {
            lit += pixel(f, x, y)[0] >= 250 ? 1 : 0;
            ++all;
        }
    }
    ASSERT_GT(all, 10000u);
    EXPECT_GE(double(lit), 0.95 * double(all)) << lit << " of " << all << " top pixels show the sun's highlight";
}

}  // namespace
}  // namespace spindrift::test
