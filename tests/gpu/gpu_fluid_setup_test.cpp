// The fluid's constraint setup on the device (src/gpu/gpu_fluid_setup.h)
// against the CPU's setupConstraints (src/fluid/neighbours.cpp), particle by
// particle, on the same state.
//
// What must be equal, and why: the gather into grid order moves floats
// without arithmetic; each list holds the neighbours within h in the same
// order (the same candidates in the same order, and the test r^2 < h^2 made
// by the same correctly rounded subtractions, products and sums on both,
// without fused multiply-adds); so the lists' neighbours, their counts and
// the overflow count are compared exactly. The device stores no g (its solve
// computes each entry's again, fluidPairG): fluidPairG on the host, from the
// device's gathered positions, must give the CPU's stored g bit for bit (the
// same correctly rounded operations on the same floats); the device's own
// evaluation of it is checked by the solve's bit-for-bit test.
//
// What may differ, and by how much: the values. The device may take a
// square root and a division a few units in the last place (ulp) off the
// correctly rounded ones (Vulkan 1.3, "Precision and Operation of SPIR-V
// Instructions": 3 ulp for sqrt as 1 / inversesqrt, 2.5 for division), may
// fuse a multiply-add outside the `precise` expressions, and adds a
// particle's pair terms in list order where the CPU adds sixteen lanes and
// then the lanes as a tree (fewer roundings than in order, so the bound
// below holds). Each term is then within about 4 ulp of its own size, and
// each of the n additions rounds by at most half an ulp of the running sum,
// which is at most the sum of the terms' sizes S: so a sum of n terms
// may differ by at most about (n + 4) x 4 ulp x S, the bound used below with
// S computed from the CPU's lists (relative ulp 2^-23).
#include "gpu_fluid_test_util.h"
#include "gpu_test_util.h"

#include <spindrift/fluid.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

namespace spindrift {
namespace {

using test::GpuTest;
template <int D>
using Vec = fluid::Vec<D>;

using test::kFluidDt;
constexpr double kUlp = 1.0 / 8388608.0;  // 2^-23

class GpuFluidSetupTest : public test::GpuSuiteWith<test::FluidParts, &test::createFluidParts> {
protected:
    template <int D>
    static gpu::FluidSetupReadback runDevice(test::CpuSetup<D>& c, const test::FluidParticles<D>& in) {
        Shared& s = shared();
        test::DeviceFluid<D> device(*s.device, c, in);
        gpu::submitOnce(*s.device, [&](VkCommandBuffer cmd) { device.recordSetup(cmd, *s.part); });
        gpu::FluidSetupReadback r = gpu::readFluidSetup(*s.part->setup);
        if (r.entries > s.part->setup->listCapacity) {
            // As a step would: the lists grown to what the header asked for, and the setup again.
            gpu::reserveFluidLists(*s.part->setup, r.entries);
            gpu::submitOnce(*s.device, [&](VkCommandBuffer cmd) { device.recordSetup(cmd, *s.part); });
            r = gpu::readFluidSetup(*s.part->setup);
        }
        return r;
    }

    // The CPU's and the device's setups of `in` under `def`, compared.
    template <int D>
    static void expectSameSetup(const FluidDef& def, const test::FluidParticles<D>& in, const std::string& what) {
        test::CpuSetup<D> c;
        test::runCpuSetup<D>(c, def, in);
        const gpu::FluidSetupReadback r = runDevice<D>(c, in);
        const fluid::Particles<D>& p = c.f.template particles<D>();
        const fluid::Constraints& k = c.f.constraints;
        const std::size_t n = p.size();
        ASSERT_EQ(r.counts.size(), n) << what;

        // Equal: the gather, the lists' neighbours, the counts, the overflows.
        std::size_t gatherDiffs = 0;
        for (std::size_t i = 0; i < n; ++i) {
            for (int a = 0; a < D; ++a) {
                gatherDiffs += r.x[D * i + a] != p.position[i][a];
                gatherDiffs += r.v[D * i + a] != p.velocity[i][a];
            }
            gatherDiffs += r.p[i] != p.pressure[i];
        }
        EXPECT_EQ(gatherDiffs, 0u) << what;
        EXPECT_EQ(r.overflows, c.stats.neighbourOverflows) << what;
        std::uint64_t total = 0;
        for (std::size_t i = 0; i < n; ++i) total += k.count[i];
        EXPECT_EQ(r.entries, total) << what;
        ASSERT_LE(r.entries, r.listIndex.size()) << what << ": the lists' room";

        // Every particle's neighbours within h, by brute force: at least the
        // density's terms (the setup reads fewer from crushed sub-cells).
        std::vector<std::size_t> within(n, 0);
        const float h2 = c.f.h * c.f.h;
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = 0; j < n; ++j) {
                const Vec<D> o = p.position[j] - p.position[i];
                within[i] += j != i && glm::dot(o, o) < h2;
            }
        }
        std::vector<double> fastestTolerance(n, 0.0);
        const fluid::NeighbourChunks<D>& lists = c.f.template neighbours<D>();
        const double scale = def.baumgarte * kernels::SD_FLUID_RATE_PER_DENSITY * c.f.h / kFluidDt;  // bias per density
        std::size_t countDiffs = 0, indexDiffs = 0, gDiffs = 0, densityDiffs = 0, massDiffs = 0, biasDiffs = 0,
                    warmDiffs = 0;
        std::string first;
        for (std::size_t i = 0; i < n; ++i) {
            if (r.counts[i] != k.count[i]) {
                ++countDiffs;
                continue;
            }
            const fluid::Neighbour<D>* list = fluid::neighbourList<D>(lists, k, i);
            // The sizes of the sums' terms (see the file's comment).
            double massSize = 0.0, gSize[D] = {}, warmSize[D] = {};
            const glm::vec4& wall = c.wall[i];
            const double lambdaI = p.pressure[i] * k.warmFraction;
            for (int a = 0; a < D; ++a) {
                gSize[a] = std::abs(wall[a + 1]);
                warmSize[a] = std::abs(wall[a + 1]) * lambdaI;
            }
            double fastestSize = 0.0;
            for (std::uint32_t e = 0; e < k.count[i]; ++e) {
                const std::uint32_t j = list[e].index;
                const std::size_t entry = r.first[i] + e;
                indexDiffs += r.listIndex[entry] != j;
                double w2 = 0.0;
                // The device stores no g: its solve computes each entry's
                // again from the gathered positions (fluidPairG, the same
                // operations as the CPU's pairTerm). Computed here from the
                // device's positions, it must be the CPU's stored g bit for
                // bit (same inputs, same correctly rounded operations).
                glm::vec3 offset(0.0f);
                for (int a = 0; a < D; ++a) offset[a] = r.x[D * j + a] - r.x[D * i + a];
                float r2 = offset.x * offset.x + offset.y * offset.y;
                if (D == 3) r2 += offset.z * offset.z;
                const glm::vec3 recomputed = kernels::fluidPairG(offset, r2, static_cast<std::uint32_t>(i), j,
                                                                  1.0f / (c.f.h * c.f.h));
                for (int a = 0; a < D; ++a) {
                    const float g = list[e].g[a];
                    gDiffs += std::bit_cast<std::uint32_t>(recomputed[a]) != std::bit_cast<std::uint32_t>(g);
                    w2 += static_cast<double>(g) * g;
                    gSize[a] += std::abs(g);
                    warmSize[a] += std::abs(g) * (lambdaI + p.pressure[j] * k.warmFraction);
                }
                massSize += w2;
                fastestSize = std::max(fastestSize, static_cast<double>(glm::length(p.velocity[i] - p.velocity[j])));
            }
            const double terms = (static_cast<double>(k.count[i]) + 4.0) * 4.0 * kUlp;
            // Density: W of every neighbour within h (more than the stored
            // ones past a cap), all positive: their sum is its own size.
            const double density = static_cast<double>(p.density[i]) * c.f.restDensity;
            const double densityTolerance = (static_cast<double>(within[i]) + 4.0) * 4.0 * kUlp * density;
            const double gpuDensity = static_cast<double>(r.constraints[i].z) * c.f.restDensity;
            densityDiffs += !(std::abs(gpuDensity - density) <= densityTolerance);
            // Effective mass A = sum w^2 + |sum g|^2, compared as A.
            double gSum2 = 0.0;
            for (int a = 0; a < D; ++a) gSum2 += gSize[a] * gSize[a];
            if (k.invMass[i] > 0.0f) {
                const double mass = 1.0 / k.invMass[i], gpuMass = 1.0 / r.constraints[i].y;
                massDiffs += !(std::abs(gpuMass - mass) <= terms * (massSize + gSum2) + 4.0 * kUlp * mass);
            } else {
                massDiffs += r.constraints[i].y != 0.0f;
            }
            // Bias: linear in the density, then rounded a few times.
            const double bias = k.bias[i];
            biasDiffs += !(std::abs(r.constraints[i].x - bias) <=
                           densityTolerance * scale + 8.0 * kUlp * std::abs(bias));
            for (int a = 0; a < D; ++a) {
                warmDiffs += !(std::abs(r.warm[i][a] - k.warmVelocity[i][a]) <= terms * warmSize[a] + 1e-30);
            }
            // The fastest closing speed: a maximum (exact) of terms each
            // within (D + 4) x 4 ulp of the pair's relative speed.
            fastestTolerance[i] = (D + 4) * 4.0 * kUlp * fastestSize;
            if (first.empty() && (indexDiffs || gDiffs || densityDiffs || massDiffs || biasDiffs || warmDiffs)) {
                first = "first at particle " + std::to_string(i) + ": density " + std::to_string(density) + " / " +
                        std::to_string(gpuDensity) + ", invMass " + std::to_string(k.invMass[i]) + " / " +
                        std::to_string(r.constraints[i].y) + ", bias " + std::to_string(bias) + " / " +
                        std::to_string(r.constraints[i].x);
            }
        }
        EXPECT_EQ(countDiffs, 0u) << what;
        EXPECT_EQ(indexDiffs, 0u) << what;
        EXPECT_EQ(gDiffs, 0u) << what << "; " << first;
        EXPECT_EQ(densityDiffs, 0u) << what << "; " << first;
        EXPECT_EQ(massDiffs, 0u) << what << "; " << first;
        EXPECT_EQ(biasDiffs, 0u) << what << "; " << first;
        EXPECT_EQ(warmDiffs, 0u) << what << "; " << first;
        // The fastest closing speeds as the substep rule reads them, binned
        // (fluid_state.h, approachBin): the same histogram, but for particles
        // within their tolerance of a bin's edge, which may fall on either side.
        fluid::ApproachHistogram bins{};
        std::size_t nearEdge = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const float fastest = r.constraints[i].w;
            bins[fluid::approachBin(fastest)] += 1;
            const double edge = std::round(fastest / fluid::kApproachBin) * fluid::kApproachBin;
            nearEdge += std::abs(fastest - edge) <= fastestTolerance[i];
        }
        std::uint64_t binDiffs = 0;
        for (std::size_t b = 0; b < bins.size(); ++b) {
            binDiffs += bins[b] > c.f.approach[b] ? bins[b] - c.f.approach[b] : c.f.approach[b] - bins[b];
        }
        EXPECT_LE(binDiffs, 2 * nearEdge) << what;
    }
};

TEST_F(GpuFluidSetupTest, DamBreak2DMatchesTheCpuSetup) {
    const FluidDef def = test::damBreakDef(2, 0.02f, {1.0f, 1.2f, 0.0f});
    const test::FluidParticles<2> p = test::damBreakParticles<2>(def, {3.0f, 2.0f, 0.0f}, 30);
    ASSERT_GT(p.x.size(), 2500u);  // dozens of tiles of the prefix sum
    expectSameSetup<2>(def, p, "2D dam break");
    // The lists capped: the stored neighbours are the first `cap`, the
    // density still counts all of them, the rest are overflows.
    FluidDef capped = def;
    capped.maxNeighbours = 12;
    expectSameSetup<2>(capped, p, "2D dam break, 12 neighbours at most");
}

TEST_F(GpuFluidSetupTest, DamBreak3DMatchesTheCpuSetup) {
    const FluidDef def = test::damBreakDef(3, 0.04f, {0.4f, 0.5f, 0.4f});
    const test::FluidParticles<3> p = test::damBreakParticles<3>(def, {1.2f, 0.8f, 0.6f}, 20);
    ASSERT_GT(p.x.size(), 1000u);
    expectSameSetup<3>(def, p, "3D dam break");
}

// A crushed pile: particles several to a point and sub-cells far past the
// setup's read limit (kCrushedSubCell), so the coincident pairs' direction
// rule and the crushed sub-cells' overflows are compared too.
TEST_F(GpuFluidSetupTest, CrushedPileMatchesTheCpuSetup) {
    const FluidDef def = test::damBreakDef(2, 0.02f, {0.1f, 0.1f, 0.0f});
    test::FluidParticles<2> p;
    std::mt19937 rng(11u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 900; ++i) {
        // 300 points in a square of 1.5 spacings, each taken three times.
        const Vec<2> at(0.03f * unit(rng), 0.03f * unit(rng));
        for (int copy = 0; copy < (i % 3 == 0 ? 3 : 0); ++copy) {
            p.x.push_back(at);
            p.v.push_back(Vec<2>(unit(rng) - 0.5f, unit(rng) - 0.5f));
            p.pressure.push_back(0.1f * unit(rng));
        }
    }
    expectSameSetup<2>(def, p, "crushed pile");
    test::CpuSetup<2> c;
    test::runCpuSetup<2>(c, def, p);
    EXPECT_GT(c.stats.neighbourOverflows, 0u) << "the pile should crush its sub-cells past the read limit";
}

TEST_F(GpuFluidSetupTest, NoParticles) {
    const FluidDef def = test::damBreakDef(2, 0.02f, {0.1f, 0.1f, 0.0f});
    expectSameSetup<2>(def, test::FluidParticles<2>{}, "no particle");
}

}  // namespace
}  // namespace spindrift
