// The fluid's solve on the device (src/gpu/gpu_fluid_solve.h) against the
// CPU's solveConstraints (src/fluid/solver.cpp), on the same setup: the CPU's
// lists and constraints are uploaded into the device setup's buffers, so the
// two solves start from the same bits.
//
// Why equality: the device visits every cell's particles in the CPU's order,
// one colour at a time, and cells of one colour share no particle, so each
// particle sees the same sequence of impulses; and every sum and product is
// the CPU's, operation for operation (`precise` in fluid_solve.comp). On a
// device that rounds to nearest, as lavapipe does, the results are then the
// same bits; anything else is a different order of visits or a different
// formula. (A device that may round otherwise is outside this test: see
// src/gpu/gpu_sort.h.)
#include "gpu_fluid_test_util.h"
#include "gpu_test_util.h"

#include <spindrift/fluid.h>

#include <cstdint>
#include <random>
#include <string>

namespace spindrift {
namespace {

using test::kFluidDt;


class GpuFluidSolveTest : public test::GpuSuiteWith<test::FluidParts, &test::createFluidParts> {
protected:
    // The CPU's and the device's solves of the same setup, compared bit for bit.
    template <int D>
    static void expectSameSolve(const FluidDef& def, const test::FluidParticles<D>& in, const std::string& what) {
        Shared& s = shared();
        test::CpuSetup<D> c;
        test::runCpuSetup<D>(c, def, in);
        test::DeviceFluid<D> device(*s.device, c, in);
        gpu::submitOnce(*s.device, [&](VkCommandBuffer cmd) { device.recordSetup(cmd, *s.part); });
        test::uploadCpuSetup<D>(*s.device, c, *s.part->setup);
        gpu::FluidSolveParams params;
        params.iterations = def.iterations;
        params.split = def.splitImpulse;
        params.warmFraction = c.f.constraints.warmFraction;
        params.restDensity = c.f.restDensity;
        params.baumgarte = def.baumgarte;
        params.h = c.f.h;
        params.dt = kFluidDt;
        gpu::submitOnce(*s.device, [&](VkCommandBuffer cmd) {
            gpu::recordFluidSolve(cmd, *s.part->solve, *s.part->grid, *s.part->setup, device.wall, params);
        });
        const gpu::FluidSolveReadback r = gpu::readFluidSolve(*s.part->solve, *s.part->setup);
        WorkerPool pool(2);
        fluid::solveConstraints<D>(pool, c.f, kFluidDt);
        const fluid::Particles<D>& p = c.f.template particles<D>();
        const std::size_t n = p.size();
        ASSERT_EQ(r.velocity.size(), n * D) << what;
        std::size_t velocityDiffs = 0, pseudoDiffs = 0, pressureDiffs = 0, pseudoImpulseDiffs = 0;
        std::string first;
        for (std::size_t i = 0; i < n; ++i) {
            for (int a = 0; a < D; ++a) {
                velocityDiffs += r.velocity[D * i + a] != p.velocity[i][a];
                pseudoDiffs += r.motion[2 * D * i + D + a] != p.motion[i].pseudo[a];
            }
            pressureDiffs += r.pressure[i] != p.pressure[i];
            pseudoImpulseDiffs += r.pseudoImpulse[i] != c.f.pseudoImpulse[i];
            if (first.empty() && (velocityDiffs || pressureDiffs)) {
                first = "first at particle " + std::to_string(i) + ": vx " + std::to_string(p.velocity[i][0]) + " / " +
                        std::to_string(r.velocity[D * i]) + ", pressure " + std::to_string(p.pressure[i]) + " / " +
                        std::to_string(r.pressure[i]);
            }
        }
        EXPECT_EQ(velocityDiffs, 0u) << what << "; " << first;
        EXPECT_EQ(pseudoDiffs, 0u) << what;
        EXPECT_EQ(pressureDiffs, 0u) << what << "; " << first;
        EXPECT_EQ(pseudoImpulseDiffs, 0u) << what;
        // Not a solve that did nothing: the pressures moved the particles.
        double change = 0.0;
        for (std::size_t i = 0; i < n; ++i) change += glm::length(p.velocity[i] - in.v[p.id[i]]);
        EXPECT_GT(change, 0.0) << what;
    }
};

TEST_F(GpuFluidSolveTest, DamBreak2DMatchesTheCpuSolveBitForBit) {
    FluidDef def = test::damBreakDef(2, 0.02f, {1.0f, 1.2f, 0.0f});
    const test::FluidParticles<2> p = test::damBreakParticles<2>(def, {3.0f, 2.0f, 0.0f}, 30);
    ASSERT_GT(p.x.size(), 2500u);
    expectSameSolve<2>(def, p, "2D dam break, split impulses");
    def.splitImpulse = false;
    def.iterations = 2;
    expectSameSolve<2>(def, p, "2D dam break, the slides' single impulse, 2 iterations");
}

TEST_F(GpuFluidSolveTest, DamBreak3DMatchesTheCpuSolveBitForBit) {
    FluidDef def = test::damBreakDef(3, 0.04f, {0.4f, 0.5f, 0.4f});
    const test::FluidParticles<3> p = test::damBreakParticles<3>(def, {1.2f, 0.8f, 0.6f}, 20);
    ASSERT_GT(p.x.size(), 1000u);
    expectSameSolve<3>(def, p, "3D dam break, split impulses");
    def.splitImpulse = false;
    def.iterations = 1;
    expectSameSolve<3>(def, p, "3D dam break, the slides' single impulse, 1 iteration");
}

// Lists cut short (a cap on the neighbours): the warm start cannot be
// gathered from asymmetric lists and is scattered, colour by colour.
TEST_F(GpuFluidSolveTest, ScatteredWarmStartMatchesTheCpuBitForBit) {
    FluidDef def = test::damBreakDef(2, 0.02f, {1.0f, 1.2f, 0.0f});
    const test::FluidParticles<2> p = test::damBreakParticles<2>(def, {3.0f, 2.0f, 0.0f}, 30);
    def.maxNeighbours = 12;
    expectSameSolve<2>(def, p, "2D dam break, 12 neighbours at most");
}

}  // namespace
}  // namespace spindrift
