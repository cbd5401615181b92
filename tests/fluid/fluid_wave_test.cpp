// Standing waves in a tank (issue 12, "physics kept"): the sloshing mode's
// period against linear water-wave theory, 2D and 3D, and sleeping that lets
// a wave swing instead of freezing it on a slope.
#include "fluid/fluid_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace spindrift {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kPi = 3.14159265f;
constexpr float kAmplitude = 0.04f;  // m, at each end wall
constexpr float kSpacing = 0.02f;

/// A tank whose water starts in its first sloshing mode: the surface raised
/// at the left wall and lowered at the right by kAmplitude, cos(pi x / L).
struct SloshingTank {
    std::uint32_t dimension;
    float width;   // m, along x (L)
    float depth;   // m, of the water at rest (d)
    float across;  // m, along z (3D only)
    /// Linear theory's period (s): omega^2 = g k tanh(k d), k = pi / L.
    float theoryPeriod() const {
        const float k = kPi / width;
        return 2.0f * kPi / std::sqrt(9.81f * k * std::tanh(k * depth));
    }
};

// 2D: 1.6 m wide, 0.5 m deep, 2,000 particles. 3D: 0.8 m long, 0.3 m deep,
// 0.1 m across, 3,000 particles.
constexpr SloshingTank kTank2D{2, 1.6f, 0.5f, 0.0f};
constexpr SloshingTank kTank3D{3, 0.8f, 0.3f, 0.1f};

/// The tank's water, each one-spacing column's surface at the mode's height
/// (rounded to the lattice). sleepSpeed 0: never sleeps.
FluidId fillTank(WorldId world, const SloshingTank& t, float sleepSpeed) {
    test::closedBox(world, glm::vec3(0.0f), glm::vec3(t.width, 2.0f, t.across), t.dimension);
    FluidDef def;
    def.name = "water";
    def.dimension = t.dimension;
    def.spacing = kSpacing;
    def.sleepSpeed = sleepSpeed;
    const int columns = static_cast<int>(std::lround(t.width / kSpacing));
    for (int c = 0; c < columns; ++c) {
        const float x0 = static_cast<float>(c) * kSpacing;
        const float height = t.depth + kAmplitude * std::cos(kPi * (x0 + 0.5f * kSpacing) / t.width);
        def.blocks.push_back({glm::vec3(x0, 0.0f, 0.0f),
                              glm::vec3(x0 + kSpacing, kSpacing * std::round(height / kSpacing), t.across),
                              glm::vec3(0.0f)});
    }
    return createFluid(world, def);
}

/// The surface at the left wall minus the surface at the right (m): the mean
/// of the top particles of the five columns (10 cm) next to each wall.
float tilt(const FluidSnapshot& s, const SloshingTank& t) {
    const int columns = static_cast<int>(std::lround(t.width / kSpacing));
    std::vector<float> top(static_cast<std::size_t>(columns), 0.0f);
    for (const glm::vec3& x : s.position) {
        const int c = static_cast<int>(x.x / kSpacing);
        if (c >= 0 && c < columns) top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], x.y);
    }
    float left = 0.0f, right = 0.0f;
    for (int c = 0; c < 5; ++c) {
        left += top[static_cast<std::size_t>(c)] / 5.0f;
        right += top[static_cast<std::size_t>(columns - 1 - c)] / 5.0f;
    }
    return left - right;
}

/// The times (s) at which the tilt changed sign over `steps` steps, linearly
/// interpolated within the step; the tilt at the end in `last`.
std::vector<float> tiltCrossings(WorldId world, FluidId fluid, const SloshingTank& t, int steps, float& last) {
    std::vector<float> crossings;
    float before = tilt(readFluid(world, fluid), t);
    for (int i = 1; i <= steps; ++i) {
        stepWorld(world, kDt);
        const float now = tilt(readFluid(world, fluid), t);
        if ((before > 0.0f) != (now > 0.0f)) {
            crossings.push_back((static_cast<float>(i) - now / (now - before)) * kDt);
        }
        before = now;
    }
    last = before;
    return crossings;
}

/// The period (s) from the first five crossings (four half periods).
float sloshingPeriod(const SloshingTank& t) {
    test::FluidWorld w;
    const FluidId water = fillTank(w.id, t, 0.0f);
    float last = 0.0f;
    const std::vector<float> crossings = tiltCrossings(w.id, water, t, 4 * static_cast<int>(t.theoryPeriod() / kDt), last);
    if (crossings.size() < 5u) return 0.0f;  // the wave stopped
    return 2.0f * (crossings[4] - crossings[0]) / 4.0f;
}

// Linear theory of water waves: a standing wave of wavenumber k in water d
// deep has omega^2 = g k tanh(k d); the first mode of a tank L wide has
// k = pi / L: 1.649 s for the 2D tank, 1.113 s for the 3D one. The solver's
// period, from the zero crossings of the tilt (four half periods), without
// sleeping: measured 1.631 s (2D; 1.646 s at 1 cm) and 1.124 s (3D).
// Tolerance 3 %: the amplitude is finite (k A = 0.08 in 2D, 0.16 in 3D; the
// frequency's correction goes as (k A)^2, 1 to 2 %; 3D at 3 cm instead of
// 4 measured 1.102 s, below theory instead of above), the depth the surface
// stands for is known to half a spacing (0.6 % of the period in 2D), and the
// start is a staircase of whole particles.
TEST(FluidWaves, ASloshingTankHasLinearTheorysPeriod) {
    for (const SloshingTank& t : {kTank2D, kTank3D}) {
        const float period = sloshingPeriod(t);
        std::printf("%uD sloshing period %.4f s against %.4f s (linear theory)\n", t.dimension, period,
                    t.theoryPeriod());
        EXPECT_NEAR(period, t.theoryPeriod(), 0.03f * t.theoryPeriod()) << t.dimension << "D";
    }
}

// With the default sleeping, the wave swings on and ends near level. The
// sleep circle was sleepSpeed x sleepTime (2.5 cm) alone: the particles
// slowed near the first turn fell asleep and the surface froze 4.6 cm
// higher at one wall than at the other, after one crossing. A wave may sleep
// once its particles swing by under half a spacing (the circle's bound), so
// each wall may end up to about half a spacing off level: the tilt must end
// under one spacing, after at least two crossings (a whole period).
TEST(FluidWaves, SleepingLetsAWaveSwingAndEndNearLevel) {
    test::FluidWorld w;
    const FluidId water = fillTank(w.id, kTank2D, FluidDef{}.sleepSpeed);
    float last = 0.0f;
    const std::vector<float> crossings = tiltCrossings(w.id, water, kTank2D, 360, last);
    std::printf("sloshing with sleeping: %zu crossings, tilt after 6 s %.4f m\n", crossings.size(), last);
    EXPECT_GE(crossings.size(), 2u);
    EXPECT_LT(std::abs(last), kSpacing);
}

}  // namespace
}  // namespace spindrift
