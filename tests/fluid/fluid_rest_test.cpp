// The constraint fluid at rest (issue 12): the density kernel, the walls'
// share of the density, a tank that comes to rest and stays there, a deep tank
// that keeps its volume, and sleeping that never stops a moving particle.
#include "fluid/fluid_test_util.h"
#include "fluid/fluid_world.h"
#include "kernels/fluid.glsl"

#include <gtest/gtest.h>

#include <cstdio>

namespace spindrift {
namespace {

constexpr float kDt = 1.0f / 60.0f;

FluidDef tankDef(std::uint32_t dimension, float spacing) {
    FluidDef def;
    def.name = "water";
    def.dimension = dimension;
    def.spacing = spacing;
    return def;
}

/// The largest particle speed over steps [from, to) of a run that starts now.
float maxSpeedOver(WorldId world, int from, int to) {
    float fastest = 0.0f;
    for (int i = 0; i < to; ++i) {
        const StepStats s = stepWorld(world, kDt);
        if (i >= from) fastest = std::max(fastest, static_cast<float>(s.fluids.at(0).maxSpeed));
    }
    return fastest;
}

/// Free-surface height (m) of a 2D tank: the mean, over columns two spacings
/// wide in the middle half of [0, width], of the highest particle's centre
/// plus its radius (half a spacing). A block laid at the lattice reads exactly
/// its fill height.
float surfaceHeight2D(const FluidSnapshot& s, float width, float spacing) {
    const int columns = static_cast<int>(width / (2.0f * spacing));
    std::vector<float> top(static_cast<std::size_t>(columns), 0.0f);
    for (const glm::vec3& x : s.position) {
        const int c = static_cast<int>(x.x / (2.0f * spacing));
        if (c >= 0 && c < columns) top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], x.y);
    }
    double sum = 0.0;
    int used = 0;
    for (int c = columns / 4; c < columns - columns / 4; ++c) {
        sum += top[static_cast<std::size_t>(c)];
        ++used;
    }
    return static_cast<float>(sum / used) + 0.5f * spacing;
}

/// Free-surface height (m) of a 3D tank over [0, width]^2 in x and z: as
/// surfaceHeight2D, over square columns two spacings wide in the middle half.
float surfaceHeight3D(const FluidSnapshot& s, float width, float spacing) {
    const int columns = static_cast<int>(width / (2.0f * spacing));
    std::vector<float> top(static_cast<std::size_t>(columns * columns), 0.0f);
    for (const glm::vec3& x : s.position) {
        const int cx = static_cast<int>(x.x / (2.0f * spacing));
        const int cz = static_cast<int>(x.z / (2.0f * spacing));
        if (cx < 0 || cx >= columns || cz < 0 || cz >= columns) continue;
        float& t = top[static_cast<std::size_t>(cz * columns + cx)];
        t = std::max(t, x.y);
    }
    double sum = 0.0;
    int used = 0;
    for (int cz = columns / 4; cz < columns - columns / 4; ++cz) {
        for (int cx = columns / 4; cx < columns - columns / 4; ++cx) {
            sum += top[static_cast<std::size_t>(cz * columns + cx)];
            ++used;
        }
    }
    return static_cast<float>(sum / used) + 0.5f * spacing;
}

TEST(FluidKernel, DensityKernelSlopeIsTheSlidesWeight) {
    // W(d) = 1 - (35/16)(d - d^3 + 3d^5/5 - d^7/7) (fluid.glsl): W(0) = 1,
    // W(1) = 0 and dW/dd = -(35/16) w with w = (1 - d^2)^3 the slides' weight,
    // the identity that makes g = w dir the density gradient. Central
    // differences in double of the float kernel: error about 1e-7 / step, so
    // 2e-3 with a step of 1e-3.
    EXPECT_FLOAT_EQ(kernels::fluidDensityKernel(0.0f), 1.0f);
    EXPECT_NEAR(kernels::fluidDensityKernel(1.0f), 0.0f, 1e-6f);
    for (float d = 0.05f; d < 0.99f; d += 0.1f) {
        const double step = 1e-3;
        const double slope = (static_cast<double>(kernels::fluidDensityKernel(d + 1e-3f)) -
                              static_cast<double>(kernels::fluidDensityKernel(d - 1e-3f))) /
                             (2.0 * step);
        const double w = std::pow(1.0 - static_cast<double>(d) * d, 3.0);
        EXPECT_NEAR(slope, -2.1875 * w, 2e-3) << "d = " << d;
    }
}

TEST(FluidWalls, ABlockFillingABoxStartsAtRestDensityEverywhere) {
    // Without gravity, a block that fills a closed box exactly: every
    // particle's neighbourhood is the lattice, cut by the walls, and the walls'
    // ghosts continue the lattice through them, so each particle's density is
    // the interior lattice sum, rho0 (a particle beside one wall: 1 up to
    // float rounding; the table interpolates linearly between 128 entries,
    // 2e-3 of rho0 measured on the table's own spacing). In a corner the two
    // walls' ghosts both count the diagonal quadrant, so corners read high
    // (and push their neighbours a little): particles within h of two walls
    // are left out.
    for (std::uint32_t dimension : {2u, 3u}) {
        const float spacing = 0.05f;
        const glm::vec3 hi = dimension == 2 ? glm::vec3(1.0f, 0.5f, 0.0f) : glm::vec3(0.5f);
        test::FluidWorld w;
        test::closedBox(w.id, glm::vec3(0.0f), hi, dimension);
        FluidDef def = tankDef(dimension, spacing);
        def.gravity = glm::vec3(0.0f);
        def.blocks.push_back({glm::vec3(0.0f), hi, glm::vec3(0.0f)});
        const FluidId f = createFluid(w.id, def);
        stepWorld(w.id, kDt);
        const FluidSnapshot s = readFluid(w.id, f);
        const float h = (dimension == 2 ? fluid::kDefaultSmoothing2 : fluid::kDefaultSmoothing3) * spacing;
        int checked = 0;
        for (std::size_t i = 0; i < s.count(); ++i) {
            int near = 0;
            for (std::uint32_t a = 0; a < dimension; ++a) {
                if (s.position[i][a] < h || s.position[i][a] > hi[a] - h) ++near;
            }
            if (near >= 2) continue;
            EXPECT_NEAR(s.density[i], 1.0f, 2e-3f) << dimension << "D particle at " << s.position[i].x << ", "
                                                   << s.position[i].y << ", " << s.position[i].z;
            ++checked;
        }
        EXPECT_GT(checked, 0);
    }
}

TEST(FluidRest, A2DTankComesToRestAtAnyIterationCount) {
    // Issue 12's tank: 2 m x 0.5 m of water at 2.5 cm, released at rest. After
    // 3 s the largest particle speed stays below 0.01 m/s on every step of
    // the next 2 s, for 1, 2, 4 and 8 iterations (more never worse). Sleeping
    // (FluidDef::sleepSpeed) is what stops the last jitter; the bound is the
    // issue's.
    for (std::uint32_t iterations : {1u, 2u, 4u, 8u}) {
        test::FluidWorld w;
        test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 0.0f), 2);
        FluidDef def = tankDef(2, 0.025f);
        def.iterations = iterations;
        def.blocks.push_back({glm::vec3(0.0f), glm::vec3(2.0f, 0.5f, 0.0f), glm::vec3(0.0f)});
        createFluid(w.id, def);
        const float fastest = maxSpeedOver(w.id, 180, 300);
        std::printf("2D tank, %u iterations: largest speed over 3 to 5 s %.4f m/s\n", iterations, fastest);
        EXPECT_LT(fastest, 0.01f) << iterations << " iterations";
    }
}

TEST(FluidRest, A3DTankComesToRest) {
    // A 0.5 m cube of water at 2.5 cm (issue 12), released at rest: below
    // 0.02 m/s on every step from 3 s to 5 s.
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(0.5f, 1.0f, 0.5f), 3);
    FluidDef def = tankDef(3, 0.025f);
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(0.5f), glm::vec3(0.0f)});
    createFluid(w.id, def);
    const float fastest = maxSpeedOver(w.id, 180, 300);
    std::printf("3D tank: largest speed over 3 to 5 s %.4f m/s\n", fastest);
    EXPECT_LT(fastest, 0.02f);
}

TEST(FluidVolume, A2DTank60ParticlesDeepKeepsItsVolume) {
    // 60 x 60 particles at 1 cm: filled to 0.6 m. After 3 s the free surface
    // must be within 1 % of 0.6 m (issue 12): the walls lend the density the
    // floor would otherwise crowd in for, and the density kernel reads a
    // settled packing as the lattice at the same particles per area.
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(0.6f, 1.2f, 0.0f), 2);
    FluidDef def = tankDef(2, 0.01f);
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(0.6f, 0.6f, 0.0f), glm::vec3(0.0f)});
    const FluidId f = createFluid(w.id, def);
    maxSpeedOver(w.id, 0, 180);
    const float height = surfaceHeight2D(readFluid(w.id, f), 0.6f, 0.01f);
    std::printf("2D deep tank: surface %.4f m against 0.6 m\n", height);
    EXPECT_NEAR(height, 0.6f, 0.006f);
}

TEST(FluidVolume, A3DTank30ParticlesDeepKeepsItsVolume) {
    // 20 x 30 x 20 particles at 2.5 cm: filled to 0.75 m. After 3 s the free
    // surface must be within 1 % of 0.75 m (issue 12), for the reasons of the
    // 2D tank above. A block laid at the lattice reads exactly 0.75 m, so the
    // measure itself adds no offset.
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(0.5f, 1.5f, 0.5f), 3);
    FluidDef def = tankDef(3, 0.025f);
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(0.5f, 0.75f, 0.5f), glm::vec3(0.0f)});
    const FluidId f = createFluid(w.id, def);
    EXPECT_NEAR(surfaceHeight3D(readFluid(w.id, f), 0.5f, 0.025f), 0.75f, 1e-4f);
    maxSpeedOver(w.id, 0, 180);
    const float height = surfaceHeight3D(readFluid(w.id, f), 0.5f, 0.025f);
    std::printf("3D deep tank: surface %.4f m against 0.75 m\n", height);
    EXPECT_NEAR(height, 0.75f, 0.0075f);
}

TEST(FluidSleep, AParticleInFlightNeverSleeps) {
    // A lone particle thrown up at 1 m/s passes its apex (where its speed goes
    // through 0, slower than sleepSpeed for a few steps) and falls on:
    // semi-implicit Euler with no neighbours and no walls gives exactly
    // y_n = y_0 + v0 n dt - g dt^2 n (n + 1) / 2 (about 3.99 m below the start
    // after 1 s), to float rounding over 60 steps (1e-3 m).
    test::FluidWorld w;
    FluidDef def = tankDef(2, 0.02f);
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(0.02f, 0.02f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)});
    const FluidId f = createFluid(w.id, def);
    const float y0 = readFluid(w.id, f).position.at(0).y;
    for (int i = 0; i < 60; ++i) stepWorld(w.id, kDt);
    const float n = 60.0f;
    const float expected = y0 + 1.0f * n * kDt - 9.81f * kDt * kDt * n * (n + 1.0f) / 2.0f;
    EXPECT_NEAR(readFluid(w.id, f).position.at(0).y, expected, 1e-3f);
}

}  // namespace
}  // namespace spindrift
