// The sprite look rules against their definitions: which flipbook frame a
// particle shows (frames share the life evenly, or play at a rate and
// loop), the soft-particle fade, and the OIT weight of McGuire and Bavoil.
#include "kernels/sprite_look.glsl"

#include <gtest/gtest.h>

namespace spindrift::kernels {
namespace {

// Over the life: 4 frames of a 2 s life are 0.5 s each; the last holds at
// and after death; no cross-fade unless asked.
TEST(SpriteLook, FlipbookFramesShareTheLife) {
    EXPECT_EQ(flipbookFrames(0.0f, 2.0f, 4u, 0.0f, 0u), vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(flipbookFrames(0.49f, 2.0f, 4u, 0.0f, 0u).x, 0.0f);
    EXPECT_EQ(flipbookFrames(0.51f, 2.0f, 4u, 0.0f, 0u).x, 1.0f);
    EXPECT_EQ(flipbookFrames(1.6f, 2.0f, 4u, 0.0f, 0u), vec3(3.0f, 3.0f, 0.0f));
    EXPECT_EQ(flipbookFrames(5.0f, 2.0f, 4u, 0.0f, 0u), vec3(3.0f, 3.0f, 0.0f));
    // Blending: 0.6 s is 1.2 frames in: 20 % of the way from frame 1 to 2.
    const vec3 blended = flipbookFrames(0.6f, 2.0f, 4u, 0.0f, 1u);
    EXPECT_EQ(blended.x, 1.0f);
    EXPECT_EQ(blended.y, 2.0f);
    EXPECT_NEAR(blended.z, 0.2f, 1e-5f);
}

// At a rate: 10 frames/s over 6 frames loops every 0.6 s, whatever the life.
TEST(SpriteLook, FlipbookFramesLoopAtTheirRate) {
    EXPECT_EQ(flipbookFrames(0.05f, 100.0f, 6u, 10.0f, 0u).x, 0.0f);
    EXPECT_EQ(flipbookFrames(0.35f, 100.0f, 6u, 10.0f, 0u).x, 3.0f);
    EXPECT_EQ(flipbookFrames(0.65f, 100.0f, 6u, 10.0f, 0u).x, 0.0f);  // 6.5 frames: looped
    const vec3 wrap = flipbookFrames(0.575f, 100.0f, 6u, 10.0f, 1u);     // 5.75: last toward first
    EXPECT_EQ(wrap.x, 5.0f);
    EXPECT_EQ(wrap.y, 0.0f);
    EXPECT_NEAR(wrap.z, 0.75f, 1e-4f);
}

TEST(SpriteLook, SoftFadeIsLinearOverTheDistance) {
    EXPECT_EQ(softFade(0.3f, 0.0f), 1.0f);  // off
    EXPECT_EQ(softFade(0.0f, 0.5f), 0.0f);  // touching
    EXPECT_NEAR(softFade(0.1f, 0.4f), 0.25f, 1e-6f);
    EXPECT_EQ(softFade(0.6f, 0.5f), 1.0f);   // beyond the distance
    EXPECT_EQ(softFade(-0.2f, 0.5f), 0.0f);  // behind the surface (not drawn anyway)
}

// Eq. 7 of McGuire and Bavoil 2013: alpha x clamp(10 / (1e-5 + (z/5)^2 +
// (z/200)^6), 1e-2, 3e3).
TEST(SpriteLook, OitWeightIsEquationSeven) {
    EXPECT_NEAR(oitWeight(1.0f, 5.0f), 10.0f / (1e-5f + 1.0f + std::pow(5.0f / 200.0f, 6.0f)), 1e-4f);
    EXPECT_NEAR(oitWeight(0.5f, 5.0f), 0.5f * oitWeight(1.0f, 5.0f), 1e-5f);
    EXPECT_EQ(oitWeight(1.0f, 0.01f), 3e3f);       // near: clamped above
    EXPECT_EQ(oitWeight(1.0f, 1.0e4f), 1e-2f);     // far: clamped below
    EXPECT_GT(oitWeight(1.0f, 2.0f), oitWeight(1.0f, 4.0f));  // nearer counts more
}

}  // namespace
}  // namespace spindrift::kernels
