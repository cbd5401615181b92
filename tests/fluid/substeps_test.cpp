// The automatic substep count (src/fluid/fluid_step.cpp, substepsOfStep) and
// what it reports of each rule (FluidStepStats::substepsFor*), checked
// against the rules' closed forms for a geometry the test sets up.
#include "fluid/fluid_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace spindrift {
namespace {

constexpr float kDt = 1.0f / 60.0f;

std::uint32_t mostOf(const FluidStepStats& f) {
    return std::max({1u, f.substepsForSpeed, f.substepsForDepth, f.substepsForCompression});
}

TEST(FluidSubsteps, TheDepthRuleAsksWhatATanksDepthImplies) {
    // A 2D tank 60 layers deep at 1 cm (h = 3.5 cm). Before the first step
    // the depth is the particles' extent along gravity, 59 spacings, and the
    // rule (docs/fluid.md, "Substeps") asks for ceil(sqrt(layers g dt^2 /
    // (0.8 h))) = ceil(sqrt(5.85)) = 3; nothing has moved, so the speed and the
    // compression rules ask for nothing, and the step takes 3.
    test::FluidWorld w;
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(0.6f, 1.0f, 0.0f), 2);
    FluidDef def;
    def.spacing = 0.01f;
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(0.6f, 0.6f, 0.0f), glm::vec3(0.0f)});
    createFluid(w.id, def);
    const float g = std::abs(def.gravity.y);
    const float layers = 59.0f;
    const auto expected = static_cast<std::uint32_t>(std::ceil(std::sqrt(layers * g * kDt * kDt / (0.8f * 0.03f))));
    ASSERT_EQ(expected, 3u);
    const FluidStepStats s = stepWorld(w.id, kDt).fluids.at(0);
    EXPECT_EQ(s.substepsForDepth, expected);
    EXPECT_EQ(s.substepsForSpeed, 0u);
    EXPECT_EQ(s.substepsForCompression, 0u);
    EXPECT_EQ(s.substeps, expected);
}

TEST(FluidSubsteps, BlocksMeetingHeadOnAskForTheirClosingSpeed) {
    // Two blocks without gravity, 2 cm spacing (h = 7 cm), moving at 3 m/s
    // toward each other: where they meet, neighbours close in at 6 m/s, and
    // the speed rule lets them close by 0.4 h a substep: ceil(6 dt / (0.4 h))
    // = ceil(3.57) = 4. The histogram counts a speed at its bin's top, which
    // can add at most one substep (bins are 0.5 m/s wide: 6.5 m/s still asks
    // for 4). Every step takes the most of what the rules ask.
    test::FluidWorld w;
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 0.0f), 2);
    FluidDef def;
    def.spacing = 0.02f;
    def.gravity = glm::vec3(0.0f);
    def.blocks.push_back({glm::vec3(0.2f, 0.3f, 0.0f), glm::vec3(0.6f, 0.7f, 0.0f), glm::vec3(3.0f, 0.0f, 0.0f)});
    def.blocks.push_back({glm::vec3(1.4f, 0.3f, 0.0f), glm::vec3(1.8f, 0.7f, 0.0f), glm::vec3(-3.0f, 0.0f, 0.0f)});
    createFluid(w.id, def);
    std::uint32_t beforeMeeting = 0, most = 0;
    for (int step = 0; step < 20; ++step) {
        const FluidStepStats s = stepWorld(w.id, kDt).fluids.at(0);
        EXPECT_EQ(s.substeps, mostOf(s)) << "step " << step;
        EXPECT_EQ(s.substepsForDepth, 0u) << "no gravity, no depth";
        if (step < 6) beforeMeeting = std::max(beforeMeeting, s.substepsForSpeed);  // 0.8 m apart, 0.1 m closer a step
        most = std::max(most, s.substepsForSpeed);
    }
    EXPECT_LE(beforeMeeting, 1u) << "each block moves as one before they meet";
    EXPECT_GE(most, 4u);
    EXPECT_LE(most, 5u);
}

TEST(FluidSubsteps, TheBackstopHoldsADamBreakUnderTheIssuesBound) {
    // LiquidFun's dam break (docs/performance.md) at 2 cm: a 1.6 x 2.0 m
    // column in a 4 x 4 m box, through its first impact on the far wall
    // (t = 0.55 s) and the run-up. Issue 12, item 7 bounds the mean density
    // error at 3 % on every step; the speed and depth rules alone ask for at
    // most 3 and 4 substeps here (measured), which compress it past that
    // (with the backstop switched off: 4.6 %), so the bound holds only if
    // the compression backstop answers (it triggers at 1.5 %, docs/fluid.md
    // "Substeps").
    test::FluidWorld w;
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(4.0f, 4.0f, 0.0f), 2);
    FluidDef def;
    def.spacing = 0.02f;
    def.gravity = glm::vec3(0.0f, -10.0f, 0.0f);
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(1.6f, 2.0f, 0.0f), glm::vec3(0.0f)});
    createFluid(w.id, def);
    double worst = 0.0;
    std::uint32_t mostForCompression = 0;
    for (int step = 0; step < 90; ++step) {
        const FluidStepStats s = stepWorld(w.id, kDt).fluids.at(0);
        worst = std::max(worst, s.meanDensityError);
        mostForCompression = std::max(mostForCompression, s.substepsForCompression);
    }
    std::printf("dam break at 2 cm: largest mean density error %.4f, most substeps for compression %u\n", worst,
                mostForCompression);
    EXPECT_LT(worst, 0.03);
    EXPECT_GT(mostForCompression, 3u) << "the backstop answered";
}

TEST(FluidSubsteps, AFixedCountReportsNoRule) {
    test::FluidWorld w;
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(0.6f, 1.0f, 0.0f), 2);
    FluidDef def;
    def.spacing = 0.01f;
    def.substeps = 2;
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(0.6f, 0.6f, 0.0f), glm::vec3(0.0f)});
    createFluid(w.id, def);
    const FluidStepStats s = stepWorld(w.id, kDt).fluids.at(0);
    EXPECT_EQ(s.substeps, 2u);
    EXPECT_EQ(s.substepsForSpeed + s.substepsForDepth + s.substepsForCompression, 0u);
}

}  // namespace
}  // namespace spindrift
