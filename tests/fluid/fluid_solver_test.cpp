// The constraint fluid (issue 4): kernel signs, rest, momentum, containment,
// convergence with iterations, determinism, colliders and jets, in 2D and 3D.
#include "core/scoped_update_target.h"
#include "fluid/fluid_test_util.h"
#include "kernels/fluid.glsl"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <string>

namespace spindrift {
namespace {

constexpr float kDt = 1.0f / 60.0f;

FluidDef baseDef(std::uint32_t dimension, float spacing = 0.05f) {
    FluidDef def;
    def.name = "water";
    def.dimension = dimension;
    def.spacing = spacing;
    return def;
}

FluidBlockDef block(glm::vec3 lo, glm::vec3 hi, glm::vec3 v = glm::vec3(0.0f)) { return {lo, hi, v}; }

/// Mean over steps of the step's mean density error.
struct RunMetrics {
    double meanError = 0.0;
    double maxSpeed = 0.0;
};

RunMetrics run(WorldId world, int steps, int measureFrom = 0) {
    RunMetrics m;
    int measured = 0;
    for (int i = 0; i < steps; ++i) {
        const StepStats s = stepWorld(world, kDt);
        if (i >= measureFrom) {
            m.meanError += s.fluids.at(0).meanDensityError;
            m.maxSpeed = std::max(m.maxSpeed, s.fluids.at(0).maxSpeed);
            ++measured;
        }
    }
    m.meanError /= std::max(measured, 1);
    return m;
}

double meanSpeed(const FluidSnapshot& s) {
    double sum = 0.0;
    for (const glm::vec3& v : s.velocity) sum += glm::length(v);
    return sum / static_cast<double>(std::max<std::size_t>(s.count(), 1));
}

TEST(FluidKernel, WeightIsTheSlidesKernel) {
    EXPECT_FLOAT_EQ(kernels::fluidWeight(0.0f, 1.0f), 1.0f);
    EXPECT_FLOAT_EQ(kernels::fluidWeight(0.25f, 1.0f), 0.421875f);  // (1 - 0.25)^3
    EXPECT_EQ(kernels::fluidWeight(1.0f, 1.0f), 0.0f);
    EXPECT_EQ(kernels::fluidWeight(4.0f, 1.0f), 0.0f);
}

TEST(FluidKernel, ImpulsePushesApartAndNeverPulls) {
    // Neighbours approaching (rate < 0) at rest density: a positive impulse.
    kernels::FluidImpulse r = kernels::fluidSolveImpulse(-1.0f, 0.0f, 0.5f, 0.0f);
    EXPECT_FLOAT_EQ(r.delta, 0.5f);
    EXPECT_FLOAT_EQ(r.accumulated, 0.5f);
    // Over-dense (bias < 0) and at rest: pushes apart.
    EXPECT_GT(kernels::fluidSolveImpulse(0.0f, kernels::fluidBias(1.1f, 1.0f, 0.1f, 0.1f, 60.0f), 1.0f, 0.0f).delta,
              0.0f);
    // Under-dense and at rest: nothing (pressure never pulls).
    EXPECT_EQ(kernels::fluidSolveImpulse(0.0f, kernels::fluidBias(0.9f, 1.0f, 0.1f, 0.1f, 60.0f), 1.0f, 0.0f).delta,
              0.0f);
    // The accumulated impulse is clamped, not the per-visit one: a negative
    // delta is allowed while the total stays >= 0.
    r = kernels::fluidSolveImpulse(0.3f, 0.0f, 1.0f, 0.5f);
    EXPECT_FLOAT_EQ(r.delta, -0.3f);
    EXPECT_FLOAT_EQ(r.accumulated, 0.2f);
    r = kernels::fluidSolveImpulse(1.0f, 0.0f, 1.0f, 0.5f);
    EXPECT_FLOAT_EQ(r.delta, -0.5f);
    EXPECT_EQ(r.accumulated, 0.0f);
}

TEST(FluidKernel, ContactStopsApproachAtTheSurface) {
    kernels::FluidSurface floor = kernels::makeSurface(0.1f, glm::vec3(0.0f, 1.0f, 0.0f));
    // 0.05 m gap beyond the radius: may close it in one step (3 m/s at 60 Hz), not more.
    glm::vec3 v = kernels::fluidContactVelocity(glm::vec3(1.0f, -10.0f, 0.0f), floor, 0.05f, 60.0f, 0.2f, 0.0f);
    EXPECT_NEAR(v.y, -3.0f, 1e-5f);
    EXPECT_EQ(v.x, 1.0f);  // frictionless
    v = kernels::fluidContactVelocity(glm::vec3(1.0f, -10.0f, 0.0f), floor, 0.05f, 60.0f, 0.2f, 0.01f);
    EXPECT_LT(v.x, 1.0f);  // friction removes tangential speed
    EXPECT_GE(v.x, 0.0f);
}

TEST(FluidRest, LatticeRestDensityMatchesTheBlock) {
    // No gravity, no walls: a freshly laid block has no over-dense particle, so
    // nothing moves but for float rounding of the density sums (which differ
    // from the lattice sum in order only: about 1e-7 relative; times
    // baumgarte h / dt = 0.9 m/s per unit error gives < 1e-5 m/s).
    for (std::uint32_t dim : {2u, 3u}) {
        test::FluidWorld w;
        FluidDef def = baseDef(dim);
        def.gravity = glm::vec3(0.0f);
        def.blocks.push_back(block(glm::vec3(0.0f), dim == 2 ? glm::vec3(1.0f, 1.0f, 0.0f) : glm::vec3(0.5f)));
        const FluidId f = createFluid(w.id, def);
        run(w.id, 10);
        EXPECT_LT(test::maxSpeed(readFluid(w.id, f)), 1e-4f) << "dimension " << dim;
    }
}

TEST(FluidTank, AtRest2D) {
    // 40 x 20 particles in a closed tank, 3 s. Measured 2026-11-29 over the
    // last second: mean density error 0.54 %, mean speed 0.11 m/s, max speed
    // 0.83 m/s. Bounds about 2x that: the solver leaves particle-scale jitter
    // (a disordered packing re-settling, docs/performance.md), while a collapse
    // or an explosion shows as free-fall speeds, sqrt(2 g 1 m) = 4.4 m/s, and
    // density errors of 10 % and more.
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(2.0f, 1.5f, 0.0f), 2);
    FluidDef def = baseDef(2);
    def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 0.0f)));
    const FluidId f = createFluid(w.id, def);
    const RunMetrics m = run(w.id, 180, 120);
    const FluidSnapshot s = readFluid(w.id, f);
    std::printf("tank 2D: mean density error %.4f, mean speed %.3f m/s, max speed %.3f m/s\n", m.meanError,
                meanSpeed(s), m.maxSpeed);
    EXPECT_LT(m.meanError, 0.012);
    EXPECT_LT(meanSpeed(s), 0.25);
    EXPECT_LT(m.maxSpeed, 1.8);
    // Pressure (the accumulated impulse) carries the weight: it grows with
    // depth. Hydrostatics says linearly; the bottom quarter must at least be
    // well above the top (y > 0.7 m; measured 0.33 vs 0.04 m/s).
    double top = 0.0, bottom = 0.0;
    int nTop = 0, nBottom = 0;
    for (std::size_t i = 0; i < s.count(); ++i) {
        if (s.position[i].y < 0.25f) {
            bottom += s.pressure[i];
            ++nBottom;
        } else if (s.position[i].y > 0.7f) {
            top += s.pressure[i];
            ++nTop;
        }
    }
    ASSERT_GT(nTop, 0);
    ASSERT_GT(nBottom, 0);
    std::printf("tank 2D: mean pressure bottom %.3f, top %.3f m/s\n", bottom / nBottom, top / nTop);
    EXPECT_GT(bottom / nBottom, 3.0 * (top / nTop));
}

TEST(FluidTank, AtRest3D) {
    // 10 x 10 x 10 particles, 1 s. Measured 2026-11-29 over the last half
    // second: mean density error 0.38 %, mean speed 0.20 m/s, max speed 1.06
    // m/s (still settling from the cubic lattice); bounds about 2x, reasons as
    // in 2D.
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(0.5f, 1.0f, 0.5f), 3);
    FluidDef def = baseDef(3);
    def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(0.5f)));
    const FluidId f = createFluid(w.id, def);
    const RunMetrics m = run(w.id, 60, 30);
    const FluidSnapshot s = readFluid(w.id, f);
    std::printf("tank 3D: mean density error %.4f, mean speed %.3f m/s, max speed %.3f m/s\n", m.meanError,
                meanSpeed(s), m.maxSpeed);
    EXPECT_LT(m.meanError, 0.01);
    EXPECT_LT(meanSpeed(s), 0.4);
    EXPECT_LT(m.maxSpeed, 2.0);
}

TEST(FluidTank, SlidesBiasInTheVelocityStillHolds) {
    // The slides' form (bias in the real velocity, splitImpulse = false) as a
    // reference: it holds the tank up too, with more jitter (measured: mean
    // density error 1.7 %, mean speed 0.18 m/s).
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(2.0f, 1.5f, 0.0f), 2);
    FluidDef def = baseDef(2);
    def.splitImpulse = false;
    def.warmStart = 0.5f;
    def.baumgarte = 0.1f;
    def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 0.0f)));
    const FluidId f = createFluid(w.id, def);
    const RunMetrics m = run(w.id, 120, 60);
    EXPECT_LT(m.meanError, 0.04);
    EXPECT_LT(meanSpeed(readFluid(w.id, f)), 0.4);
}

TEST(FluidMomentum, ConservedWithoutGravityAndColliders) {
    // Two blocks of different sizes collide head on; every impulse is applied
    // equal and opposite, so total momentum changes only by float rounding:
    // about 1e-7 of each impulse, over ~1e6 impulse applications, summed
    // with random signs: well under 1e-3 of |P| = 0.5 * N m/s.
    for (std::uint32_t dim : {2u, 3u}) {
        test::FluidWorld w(2);
        FluidDef def = baseDef(dim);
        def.gravity = glm::vec3(0.0f);
        const float depth = dim == 3 ? 0.3f : 0.0f;
        def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(0.5f, 0.4f, depth), glm::vec3(2.0f, 0.0f, 0.0f)));
        def.blocks.push_back(block(glm::vec3(0.6f, 0.1f, 0.0f), glm::vec3(0.9f, 0.3f, depth), glm::vec3(-1.0f, 0.5f, 0.0f)));
        const FluidId f = createFluid(w.id, def);
        const glm::dvec3 before = test::momentum(readFluid(w.id, f));
        const RunMetrics m = run(w.id, 40);
        const glm::dvec3 after = test::momentum(readFluid(w.id, f));
        EXPECT_GT(m.meanError, 0.0) << "the blocks must actually collide";
        EXPECT_LT(glm::length(after - before), 1e-3 * glm::length(before)) << "dimension " << dim;
    }
}

TEST(FluidContainment, NothingLeavesAClosedBoxInAViolentSlosh) {
    // A block thrown sideways at 4 m/s into a closed box, 8 s (2D) and 2 s
    // (3D): every particle stays inside the walls at every step (the contact
    // keeps centres a radius from the walls; 1e-4 m slack for rounding).
    for (std::uint32_t dim : {2u, 3u}) {
        test::FluidWorld w(2);
        const glm::vec3 hi = dim == 2 ? glm::vec3(1.0f, 0.6f, 0.0f) : glm::vec3(0.6f, 0.5f, 0.3f);
        test::closedBox(w.id, glm::vec3(0.0f), hi, dim);
        FluidDef def = baseDef(dim);
        def.blocks.push_back(block(glm::vec3(0.0f), dim == 2 ? glm::vec3(0.4f, 0.4f, 0.0f) : glm::vec3(0.3f, 0.3f, 0.3f),
                                   glm::vec3(4.0f, 2.0f, dim == 3 ? 1.0f : 0.0f)));
        const FluidId f = createFluid(w.id, def);
        const int steps = dim == 2 ? 480 : 120;
        for (int i = 0; i < steps; ++i) {
            stepWorld(w.id, kDt);
            const FluidSnapshot s = readFluid(w.id, f);
            for (const glm::vec3& x : s.position) {
                for (std::uint32_t a = 0; a < dim; ++a) {
                    ASSERT_GE(x[a], -1e-4f) << "dimension " << dim << " step " << i;
                    ASSERT_LE(x[a], hi[a] + 1e-4f) << "dimension " << dim << " step " << i;
                }
            }
        }
    }
}

double damBreakError(std::uint32_t iterations) {
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 0.0f), 2);
    FluidDef def = baseDef(2);
    def.iterations = iterations;
    // Fixed substeps: the automatic count answers a density error with more
    // substeps, which would hide what the iterations do.
    def.substeps = 2;
    def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(0.6f, 0.8f, 0.0f)));
    createFluid(w.id, def);
    return run(w.id, 90).meanError;
}

TEST(FluidIterations, MoreIterationsGiveASmallerDensityError) {
    // Dam break, 1.5 s, mean over the steps of the mean density error.
    const double e1 = damBreakError(1);
    const double e4 = damBreakError(4);
    const double e16 = damBreakError(16);
    std::printf("dam break mean density error: 1 it %.4f, 4 it %.4f, 16 it %.4f\n", e1, e4, e16);
    EXPECT_GT(e1, e4);
    EXPECT_GT(e4, e16);
}

/// The dam-break front (the largest x of any particle, m) at t = 0.1, 0.2,
/// ..., 0.5 s of LiquidFun's Testbed dam break (issue 12: a closed 4 x 4 m
/// box, a column 1.6 m wide and 2 m high, 1.8 cm lattice, g = 10 m/s^2).
/// `reference`: the plain solver converged in time and iterations (16 fixed
/// substeps of 4 Gauss-Seidel sweeps, no over-relaxation); otherwise the
/// defaults.
std::vector<float> damBreakFronts(bool reference) {
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(4.0f, 4.0f, 0.0f), 2);
    FluidDef def = baseDef(2, 0.018f);
    def.gravity = glm::vec3(0.0f, -10.0f, 0.0f);
    if (reference) {
        def.substeps = kFluidMaxSubsteps;
        def.iterations = 4;
        def.relaxation = 1.0f;
    }
    def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(1.6f, 2.0f, 0.0f)));
    const FluidId f = createFluid(w.id, def);
    std::vector<float> fronts;
    for (int step = 1; step <= 30; ++step) {
        stepWorld(w.id, kDt);
        if (step % 6 != 0) continue;
        float front = 0.0f;
        for (const glm::vec3& x : readFluid(w.id, f).position) front = std::max(front, x.x);
        fronts.push_back(front);
    }
    return fronts;
}

TEST(FluidFront, TheDefaultsRunTheDamBreakAsTheConvergedSolver) {
    // Issue 12, item 6: speed may not be bought by slowing the flow (a
    // velocity cap, damping, or sweeps that hold particles back). The front
    // over the first 0.5 s stays within 3 % (the bound) of the
    // converged run's. From 0.4 to 0.5 s the converged front runs at about
    // 6 m/s, so 3 % at 0.5 s (11 cm) is about one frame's (1/60 s) lag.
    const std::vector<float> reference = damBreakFronts(true);
    const std::vector<float> defaults = damBreakFronts(false);
    ASSERT_EQ(reference.size(), 5u);
    ASSERT_EQ(defaults.size(), 5u);
    for (std::size_t k = 0; k < reference.size(); ++k) {
        std::printf("dam-break front at %.1f s: %.3f m at the defaults, %.3f m converged\n", 0.1 * double(k + 1),
                    defaults[k], reference[k]);
        // The converged front runs on from the column's edge (1.6 m) at every
        // sample: a reference that stood still would make the bound empty.
        EXPECT_GT(reference[k], k == 0 ? 1.6f : reference[k - 1]) << "at " << 0.1 * double(k + 1) << " s";
        EXPECT_NEAR(defaults[k], reference[k], 0.03f * reference[k]) << "at " << 0.1 * double(k + 1) << " s";
    }
    EXPECT_GT(reference.back(), 3.0f) << "the converged front must be near the far wall by 0.5 s";
}

std::vector<FluidSnapshot> determinismRun(std::uint32_t dim, std::uint32_t threads, FluidSolver solver) {
    test::FluidWorld w(threads);
    const glm::vec3 hi = dim == 2 ? glm::vec3(3.0f, 1.5f, 0.0f) : glm::vec3(1.0f, 0.8f, 0.6f);
    test::closedBox(w.id, glm::vec3(0.0f), hi, dim);
    FluidDef def = baseDef(dim);
    def.solver = solver;
    // 2D: 1800 particles in ~50 cells of 2h per colour; 3D: 2000 in ~20 cells
    // per colour: several chunks of cells per colour for two threads to split.
    def.blocks.push_back(block(glm::vec3(0.0f), dim == 2 ? glm::vec3(1.5f, 1.5f, 0.0f) : glm::vec3(0.5f, 0.4f, 0.5f),
                               glm::vec3(1.0f, 0.0f, 0.0f)));
    FluidJetDef jet;
    jet.position = dim == 2 ? glm::vec3(2.5f, 1.2f, 0.0f) : glm::vec3(0.8f, 0.6f, 0.3f);
    jet.direction = glm::vec3(-1.0f, -0.5f, 0.0f);
    jet.radius = 0.05f;
    jet.rate = 300.0f;
    def.jets.push_back(jet);
    createFluid(w.id, def);
    std::vector<FluidSnapshot> out;
    for (int i = 0; i < 20; ++i) {
        stepWorld(w.id, kDt);
        if (i % 5 == 4) out.push_back(readFluid(w.id, FluidId{1}));
    }
    return out;
}

template <class T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(FluidDeterminism, BitIdenticalForOneAndTwoThreads) {
    for (std::uint32_t dim : {2u, 3u}) {
        for (FluidSolver solver : {FluidSolver::Parallel, FluidSolver::Sequential}) {
            const auto one = determinismRun(dim, 1, solver);
            const auto two = determinismRun(dim, 2, solver);
            ASSERT_EQ(one.size(), two.size());
            for (std::size_t k = 0; k < one.size(); ++k) {
                EXPECT_GT(one[k].count(), 0u);
                EXPECT_TRUE(sameBits(one[k].position, two[k].position)) << "dimension " << dim << " dump " << k;
                EXPECT_TRUE(sameBits(one[k].velocity, two[k].velocity)) << "dimension " << dim << " dump " << k;
                EXPECT_TRUE(sameBits(one[k].density, two[k].density)) << "dimension " << dim << " dump " << k;
                EXPECT_TRUE(sameBits(one[k].pressure, two[k].pressure)) << "dimension " << dim << " dump " << k;
            }
        }
    }
}

// The setup's neighbour filter (src/fluid/neighbours.cpp) has a scalar copy
// and vector copies (AVX2, AVX-512) picked at run time: every copy this CPU
// can run keeps the same neighbours, in the same order, with the same offsets
// and distances, so whole runs are bit-identical to the scalar filter's. The
// jet into a moving block makes close and coincident pairs, and the closed
// box walls; any neighbour kept or dropped differently, or reordered, changes
// the bits of the densities and pressures.
TEST(FluidDeterminism, BitIdenticalAtEveryVectorTarget) {
    for (std::uint32_t dim : {2u, 3u}) {
        std::vector<FluidSnapshot> scalar;
        {
            test::ScopedTarget target(UpdateTarget::Scalar);
            scalar = determinismRun(dim, 1, FluidSolver::Parallel);
        }
        for (UpdateTarget t : supportedUpdateTargets()) {
            test::ScopedTarget target(t);
            const auto run = determinismRun(dim, 1, FluidSolver::Parallel);
            ASSERT_EQ(run.size(), scalar.size());
            for (std::size_t k = 0; k < run.size(); ++k) {
                const std::string where =
                    "dimension " + std::to_string(dim) + ", " + std::string(updateTargetName(t)) + ", dump " + std::to_string(k);
                EXPECT_GT(run[k].count(), 0u);
                EXPECT_TRUE(sameBits(scalar[k].position, run[k].position)) << where;
                EXPECT_TRUE(sameBits(scalar[k].velocity, run[k].velocity)) << where;
                EXPECT_TRUE(sameBits(scalar[k].density, run[k].density)) << where;
                EXPECT_TRUE(sameBits(scalar[k].pressure, run[k].pressure)) << where;
            }
        }
    }
}

TEST(FluidGrid, ParticlesFarAwayDoNotCrowdTheRest) {
    // The grid has a cell budget (src/fluid/grid.cpp); a fluid whose box is
    // wider than the budget's cells, because a few of its particles are far
    // away (the showcase's stream, 90 m below the level after 9 s), used to
    // place its window at the box's low end and clamp everything else into
    // its last row of cells: the crushed-cell bound then cut the lists (1.4e8
    // overflows in the showcase). Reference: the same tank without the far
    // particles. The window only moves the cells, so every tank particle
    // keeps the same neighbours; its density may differ by the rounding of
    // sums taken in another order (1e-5 relative, about 100 float ulps).
    auto tank = [](bool withFarParticles, std::uint64_t& overflows) {
        test::FluidWorld w;
        // A tank of boxes, not planes: below a floor plane would be solid.
        for (const glm::vec4 b : {glm::vec4(0.5f, -0.1f, 0.6f, 0.1f), glm::vec4(-0.1f, 0.6f, 0.1f, 0.7f),
                                  glm::vec4(1.1f, 0.6f, 0.1f, 0.7f)}) {
            ColliderDef wall;
            wall.kind = ColliderKind::Box;
            wall.position = {b.x, b.y, 0.0f};
            wall.halfExtents = {b.z, b.w, 1.0f};
            createCollider(w.id, wall);
        }
        FluidDef def = baseDef(2, 0.025f);
        // One substep: the densities read back are then those of the lattice
        // (the start of the last substep), before the solver's colour order,
        // which the cells decide, moves anything; and the automatic count
        // would read the fluid's depth, which the far particles change.
        def.substeps = 1;
        // 40 layers: clamped into one row of sub-cells (3 particles wide),
        // 120 a sub-cell, past the crushed-cell bound of 8 x 9.
        def.blocks.push_back(block({0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 0.0f}));
        // 8 particles 500 m down: the fluid's box is 500 m tall, 13 times the
        // 256 cells of 2h = 15 cm the budget allows along an axis.
        if (withFarParticles) def.blocks.push_back(block({0.0f, -500.2f, 0.0f}, {0.025f, -500.0f, 0.0f}));
        const FluidId fluid = createFluid(w.id, def);
        const StepStats s = stepWorld(w.id, kDt);
        overflows = s.fluids.at(0).neighbourOverflows;
        const FluidSnapshot snap = readFluid(w.id, fluid);
        std::map<std::uint32_t, float> density;  // the tank's, by id
        for (std::size_t k = 0; k < snap.count(); ++k) {
            if (snap.position[k].y > -1.0f) density[snap.id[k]] = snap.density[k];
        }
        return density;
    };
    std::uint64_t aloneOverflows = 0, withOverflows = 0;
    const std::map<std::uint32_t, float> alone = tank(false, aloneOverflows);
    const std::map<std::uint32_t, float> with = tank(true, withOverflows);
    EXPECT_EQ(aloneOverflows, 0u);
    EXPECT_EQ(withOverflows, 0u);
    ASSERT_EQ(alone.size(), with.size());
    ASSERT_GT(alone.size(), 1500u);
    std::size_t differing = 0;
    for (const auto& [id, rho] : alone) {
        const auto other = with.find(id);
        ASSERT_NE(other, with.end()) << "particle " << id;
        if (std::abs(other->second - rho) > 1.0e-5f * rho) ++differing;
    }
    EXPECT_EQ(differing, 0u) << "of " << alone.size() << " tank particles";
}

TEST(FluidColliders, NoParticleEntersAnObstacle) {
    // Fluid falls onto a sphere (circle in 2D), a rotated box and a convex
    // polygon: no particle centre is ever inside one (1e-4 m slack).
    test::FluidWorld w(2);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(2.0f, 2.0f, 0.0f), 2);
    ColliderDef sphere;
    sphere.kind = ColliderKind::Sphere;
    sphere.position = {0.5f, 0.6f, 0.0f};
    sphere.radius = 0.2f;
    createCollider(w.id, sphere);
    ColliderDef box;
    box.kind = ColliderKind::Box;
    box.position = {1.0f, 0.5f, 0.0f};
    box.halfExtents = {0.15f, 0.1f, 1.0f};
    box.rotationDegrees = {0.0f, 0.0f, 30.0f};
    createCollider(w.id, box);
    FluidDef def = baseDef(2);
    def.friction = 0.2f;
    def.polygons.push_back({{{1.4f, 0.3f}, {1.8f, 0.3f}, {1.6f, 0.8f}}});
    def.blocks.push_back(block(glm::vec3(0.2f, 1.0f, 0.0f), glm::vec3(1.8f, 1.6f, 0.0f)));
    const FluidId f = createFluid(w.id, def);
    const kernels::FluidPolygon tri = [] {
        kernels::FluidPolygon p{};
        p.count = 3;
        p.vertices[0] = {1.4f, 0.3f, 0.0f, 0.0f};
        p.vertices[1] = {1.8f, 0.3f, 0.0f, 0.0f};
        p.vertices[2] = {1.6f, 0.8f, 0.0f, 0.0f};
        return p;
    }();
    for (int i = 0; i < 90; ++i) {
        stepWorld(w.id, kDt);
        const FluidSnapshot s = readFluid(w.id, f);
        for (const glm::vec3& x : s.position) {
            ASSERT_GE(glm::length(x - sphere.position), sphere.radius - 1e-4f) << "step " << i;
            const glm::vec3 q = x - box.position;
            const float c = std::cos(glm::radians(30.0f)), sn = std::sin(glm::radians(30.0f));
            const glm::vec2 local(c * q.x + sn * q.y, -sn * q.x + c * q.y);
            ASSERT_FALSE(std::abs(local.x) < box.halfExtents.x - 1e-4f && std::abs(local.y) < box.halfExtents.y - 1e-4f)
                << "step " << i;
            ASSERT_GE(kernels::fluidPolygonSurface(tri, x).distance, -1e-4f) << "step " << i;
        }
    }
}

TEST(FluidJets, EmitAtTheirRateUntilCapacity) {
    test::FluidWorld w;
    FluidDef def = baseDef(2);
    FluidJetDef jet;
    jet.position = {0.0f, 1.0f, 0.0f};
    jet.direction = {1.0f, 0.0f, 0.0f};
    jet.speed = 3.0f;
    jet.rate = 120.0f;
    def.jets.push_back(jet);
    def.capacity = 100;
    const FluidId f = createFluid(w.id, def);
    std::uint64_t born = 0;
    for (int i = 0; i < 30; ++i) born += stepWorld(w.id, kDt).fluids.at(0).born;  // 0.5 s: 60 particles
    EXPECT_EQ(born, 60u);
    for (int i = 0; i < 60; ++i) stepWorld(w.id, kDt);
    EXPECT_EQ(readFluid(w.id, f).count(), 100u);  // capped at capacity
}

TEST(FluidErrors, BadDefinitionsAreRejected) {
    test::FluidWorld w;
    FluidDef def = baseDef(4);
    EXPECT_THROW(createFluid(w.id, def), Error);
    def = baseDef(2);
    def.iterations = 17;
    EXPECT_THROW(createFluid(w.id, def), Error);
    for (float relaxation : {0.9f, 1.6f, std::numeric_limits<float>::quiet_NaN()}) {
        def = baseDef(2);
        def.relaxation = relaxation;
        EXPECT_THROW(createFluid(w.id, def), Error) << relaxation;
    }
    def = baseDef(2);
    def.polygons.push_back({{{0.0f, 0.0f}, {1.0f, 0.0f}, {0.2f, 0.2f}, {0.0f, 1.0f}}});  // not convex
    EXPECT_THROW(createFluid(w.id, def), Error);
    def = baseDef(2);
    def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(0.01f, 1.0f, 0.0f)));  // thinner than a spacing
    EXPECT_THROW(createFluid(w.id, def), Error);
    EXPECT_THROW(readFluid(w.id, FluidId{7}), Error);
}

// A Vulkan world runs its fluids on the one CPU solver: the same fluid in a
// CPU world and in a Vulkan world (lavapipe here) ends bit-identical, since
// the same code computes both; the Vulkan world must not refuse or alter it.
TEST(FluidBackends, VulkanWorldRunsFluidsOnTheCpuSolver) {
    std::vector<FluidSnapshot> results;
    for (Backend backend : {Backend::Cpu, Backend::Vulkan}) {
        WorldDef wd;
        wd.backend = backend;
        wd.threads = 1;
        WorldId world;
        try {
            world = createWorld(wd);
        } catch (const Error& e) {
            GTEST_SKIP() << "no Vulkan device: " << e.what();
        }
        FluidDef def = baseDef(2);
        def.blocks.push_back(block(glm::vec3(0.0f), glm::vec3(0.5f, 0.5f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f)));
        FluidId f = createFluid(world, def);
        for (int s = 0; s < 20; ++s) {
            stepWorld(world, 1.0f / 60.0f);
        }
        results.push_back(readFluid(world, f));
        destroyWorld(world);
    }
    ASSERT_GT(results[0].position.size(), 0u);
    ASSERT_EQ(results[0].position.size(), results[1].position.size());
    for (std::size_t i = 0; i < results[0].position.size(); ++i) {
        ASSERT_EQ(results[0].position[i], results[1].position[i]) << "particle " << i;
        ASSERT_EQ(results[0].velocity[i], results[1].velocity[i]) << "particle " << i;
    }
}

}  // namespace
}  // namespace spindrift
