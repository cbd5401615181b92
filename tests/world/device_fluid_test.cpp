// The constraint fluid stepped on the device (issue 16; src/world/
// device_fluid.h) against the CPU's step of the same fluid, on lavapipe with
// validation on: whole runs, from the same start, through the same substep
// rule. Every pass is the CPU's bit for bit given the same inputs except the
// setup's sums, which are added in another order
// (tests/gpu/gpu_fluid_setup_test.cpp), so a moving fluid's two runs part
// after a few steps the way any two runs a rounding apart do; the tolerances
// below are stated against that spread.
#include "coupling/fluid_link.h"
#include "fluid/body_contacts.h"
#include "fluid/fluid_state.h"
#include "fluid/fluid_test_util.h"
#include "fluid/number_density.h"
#include "gpu/gpu_fluid_contacts.h"
#include "gpu/gpu_test_util.h"
#include "gpu/vulkan_device.h"
#include "world/device_fluid.h"
#include "world/world.h"

#include <spindrift/bodies.h>
#include <spindrift/errors.h>
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace spindrift {
namespace {

constexpr float kDt = 1.0f / 60.0f;

struct NoPart {};
std::unique_ptr<NoPart> makeNoPart(gpu::Device&) { return std::make_unique<NoPart>(); }
using DeviceFluidTest = test::GpuSuiteWith<NoPart, makeNoPart>;

/// The positions (z 0 in 2D) of a fluid state's particles.
std::vector<glm::vec3> positionsOf(const fluid::FluidState& f) {
    std::vector<glm::vec3> x;
    if (f.def.dimension == 2) {
        for (const glm::vec2& p : f.p2.position) x.emplace_back(p, 0.0f);
    } else {
        x = f.p3.position;
    }
    return x;
}

/// One fluid in a closed box, stepped on the CPU (the world's own step) and,
/// from a copy of the same state, on the device.
struct TwoRuns {
    test::FluidWorld world{1};
    fluid::FluidState* cpu = nullptr;
    fluid::FluidState device;
    DeviceFluidPtr onDevice;

    TwoRuns(gpu::Device& d, const FluidDef& def, glm::vec3 box) {
        test::closedBox(world.id, glm::vec3(0.0f), box, def.dimension);
        createFluid(world.id, def);
        cpu = worldFromId(world.id).fluids.at(0).get();
        device = *cpu;
        onDevice = createDeviceFluid(d, device);
    }
    /// One step of both: (CPU stats, device stats).
    std::pair<FluidStepStats, FluidStepStats> step() {
        const StepStats s = stepWorld(world.id, kDt);
        const FluidStepStats onGpu =
            stepDeviceFluid(*onDevice, device, worldFromId(world.id).colliders, FluidId{1}, kDt);
        return {s.fluids.at(0), onGpu};
    }
    std::vector<glm::vec3> cpuPositions() const { return positionsOf(*cpu); }
    /// Each particle's position by its creation serial, on the CPU and on
    /// the device (readDeviceFluid first).
    static std::vector<glm::vec3> bySerial(const fluid::FluidState& f) {
        const std::vector<glm::vec3> x = positionsOf(f);
        const std::vector<std::uint32_t>& id = f.def.dimension == 2 ? f.p2.id : f.p3.id;
        std::vector<glm::vec3> out(x.size(), glm::vec3(1.0e30f));
        for (std::size_t i = 0; i < x.size(); ++i) {
            if (id[i] < out.size()) out[id[i]] = x[i];
        }
        return out;
    }
    std::vector<glm::vec3> devicePositions() {
        readDeviceFluid(*onDevice, device);
        return positionsOf(device);
    }
};

/// The largest x of the particles: a dam break's front (m).
float front(const std::vector<glm::vec3>& x) {
    float f = -1.0e30f;
    for (const glm::vec3& p : x) f = std::max(f, p.x);
    return f;
}

/// Free-surface height (m) of a 2D tank: as tests/fluid/fluid_rest_test.cpp,
/// the mean over columns two spacings wide in the middle half of [0, width]
/// of the highest particle's centre plus half a spacing.
float surfaceHeight(const std::vector<glm::vec3>& x, float width, float spacing) {
    const int columns = static_cast<int>(width / (2.0f * spacing));
    std::vector<float> top(static_cast<std::size_t>(columns), 0.0f);
    for (const glm::vec3& p : x) {
        const int c = static_cast<int>(p.x / (2.0f * spacing));
        if (c >= 0 && c < columns) top[static_cast<std::size_t>(c)] = std::max(top[static_cast<std::size_t>(c)], p.y);
    }
    double sum = 0.0;
    int used = 0;
    for (int c = columns / 4; c < columns - columns / 4; ++c, ++used) sum += top[static_cast<std::size_t>(c)];
    return static_cast<float>(sum / used) + 0.5f * spacing;
}

FluidDef waterDef(std::uint32_t dimension, float spacing, glm::vec3 block) {
    FluidDef def;
    def.name = "water";
    def.dimension = dimension;
    def.spacing = spacing;
    def.blocks.push_back({glm::vec3(0.0f), block, glm::vec3(0.0f)});
    return def;
}

TEST_F(DeviceFluidTest, TankAtRestMatchesTheCpu) {
    // A tank (1 m x 0.25 m of water at 2.5 cm, 400 particles) released at
    // rest, 4 s on both. Tolerances:
    // - the same particles (none lost on either);
    // - at rest on the device as on the CPU: below issue 12's 0.01 m/s on
    //   every step from 3 s on (tests/fluid/fluid_rest_test.cpp holds the
    //   CPU to it on the larger tank);
    // - the surface within 1 % of the fill line (issue 12's volume bound),
    //   and within a tenth of a spacing of the CPU's: a settled surface is
    //   a layer of particles, so rounding cannot move it by a layer;
    // - the number-density ratios (median, 95th percentile) within 0.01 of
    //   the CPU's: one neighbour more or fewer moves a ratio by 1/45;
    // - the substeps within 5 % of the CPU's over the run (the same rule,
    //   on statistics summed in another order);
    // - every particle, found by its creation serial, within half a spacing
    //   of the CPU's particle of that serial: a serial carried wrong lands
    //   a spacing away. Both runs settle on the same sites but for rounding,
    //   which the settling amplifies: at most 0.05 spacings apart under the
    //   compression backstop's old 1 % trigger (660 substeps), one particle
    //   0.31 spacings apart under today's 1.5 % (502; docs/fluid.md).
    //   That holds at h = 3 spacings, set here: at the default 3.5 the
    //   settling leaves a few particles a site over (the farthest 0.98
    //   spacings from its serial's CPU particle and 0.65 from any, the
    //   surface, number density and rest the same), which this bound cannot
    //   tell from a serial carried wrong. DamBreak2DMatchesTheCpu runs
    //   the device at the default h.
    constexpr float kSpacing = 0.025f, kFill = 0.25f;
    FluidDef def = waterDef(2, kSpacing, glm::vec3(1.0f, kFill, 0.0f));
    def.smoothing = 3.0f * kSpacing;
    TwoRuns runs(*shared().device, def, glm::vec3(1.0f, 0.5f, 0.0f));
    float cpuFastest = 0.0f, deviceFastest = 0.0f;
    std::uint32_t cpuSubsteps = 0, deviceSubsteps = 0;
    for (int i = 0; i < 240; ++i) {
        const auto [c, g] = runs.step();
        ASSERT_EQ(g.particles, c.particles) << "step " << i;
        EXPECT_EQ(g.nonFinite, 0u);
        cpuSubsteps += c.substeps;
        deviceSubsteps += g.substeps;
        // The device's step reports its substep rules as the CPU's does (the
        // same function, on the statistics the device read back).
        EXPECT_EQ(g.substeps, std::max({1u, g.substepsForSpeed, g.substepsForDepth, g.substepsForCompression}))
            << "step " << i;
        if (i >= 180) {
            cpuFastest = std::max(cpuFastest, static_cast<float>(c.maxSpeed));
            deviceFastest = std::max(deviceFastest, static_cast<float>(g.maxSpeed));
        }
    }
    const std::vector<glm::vec3> cx = runs.cpuPositions(), gx = runs.devicePositions();
    ASSERT_EQ(gx.size(), 400u);
    const float cpuSurface = surfaceHeight(cx, 1.0f, kSpacing), deviceSurface = surfaceHeight(gx, 1.0f, kSpacing);
    const FluidNumberDensity cn = fluid::measureNumberDensity(cx, 2, kSpacing);
    const FluidNumberDensity gn = fluid::measureNumberDensity(gx, 2, kSpacing);
    std::printf("tank at rest, CPU / device: largest speed 3-4 s %.4f / %.4f m/s, substeps %u / %u, surface "
                "%.4f / %.4f m, number density %.3f %.3f / %.3f %.3f\n",
                cpuFastest, deviceFastest, cpuSubsteps, deviceSubsteps, cpuSurface, deviceSurface, cn.median, cn.p95,
                gn.median, gn.p95);
    EXPECT_LT(deviceFastest, 0.01f);
    EXPECT_NEAR(deviceSurface, kFill, 0.01f * kFill);
    EXPECT_NEAR(deviceSurface, cpuSurface, 0.1f * kSpacing);
    EXPECT_NEAR(gn.median, cn.median, 0.01);
    EXPECT_NEAR(gn.p95, cn.p95, 0.01);
    EXPECT_NEAR(static_cast<double>(deviceSubsteps), static_cast<double>(cpuSubsteps), 0.05 * cpuSubsteps);
    const std::vector<glm::vec3> cs = TwoRuns::bySerial(*runs.cpu), gs = TwoRuns::bySerial(runs.device);
    int apart = 0;
    float farthest = 0.0f;
    for (std::size_t k = 0; k < cs.size(); ++k) {
        const float distance = glm::length(gs[k] - cs[k]);
        apart += distance > 0.5f * kSpacing ? 1 : 0;
        farthest = std::max(farthest, distance);
    }
    std::printf("  the farthest particle %.3f spacings from the CPU's of the same serial\n", farthest / kSpacing);
    EXPECT_EQ(apart, 0) << "particles away from the CPU's particle of the same serial";
}

/// A dam break on both for `steps` steps, and a second device run of the
/// same start: (largest front difference (m), largest mean density error on
/// the CPU, on the device, whether the two device runs ended bit for bit
/// equal).
struct DamBreakOutcome {
    float frontGap = 0.0f;
    double cpuWorst = 0.0, deviceWorst = 0.0;
    float cpuFastest = 0.0f, deviceFastest = 0.0f;
    int substepGap = 0;  // largest difference of a step's substeps
    std::uint64_t binGap = 0;    // most particles an early step's closing-speed histograms differ by
    std::uint64_t counted = 0;   // particles the CPU's histograms counted, all steps
    std::uint64_t earlyCounted = 0;  // the fewest counts of an early step's histogram
    std::uint32_t substeps = 0;  // the device's, all steps
    bool repeated = false;
    FluidNumberDensity cpuDensity, deviceDensity;  // at the end
};

/// Steps in which the two runs have not yet had time to part (the column
/// falls and spreads; the runs part slowly after the front's impact).
constexpr int kEarlySteps = 12;

DamBreakOutcome damBreak(gpu::Device& d, std::uint32_t dimension, float spacing, glm::vec3 column, glm::vec3 box,
                         int steps) {
    TwoRuns runs(d, waterDef(dimension, spacing, column), box);
    fluid::FluidState again = runs.device;
    DeviceFluidPtr second = createDeviceFluid(d, again);
    DamBreakOutcome out;
    for (int i = 0; i < steps; ++i) {
        const auto [c, g] = runs.step();
        EXPECT_EQ(g.particles, c.particles) << "step " << i;
        stepDeviceFluid(*second, again, worldFromId(runs.world.id).colliders, FluidId{1}, kDt);
        out.substepGap = std::max(out.substepGap, std::abs(static_cast<int>(g.substeps) - static_cast<int>(c.substeps)));
        out.substeps += g.substeps;
        std::uint64_t gap = 0, early = 0;
        for (std::size_t b = 0; b < runs.cpu->approach.size(); ++b) {
            const std::uint64_t cb = runs.cpu->approach[b], gb = runs.device.approach[b];
            gap += cb > gb ? cb - gb : gb - cb;
            out.counted += cb;
            if (i < kEarlySteps) early += cb;
        }
        if (i < kEarlySteps) {
            out.binGap = std::max(out.binGap, gap);
            out.earlyCounted = out.earlyCounted == 0 ? early : std::min(out.earlyCounted, early);
        }
        out.cpuWorst = std::max(out.cpuWorst, c.meanDensityError);
        out.deviceWorst = std::max(out.deviceWorst, g.meanDensityError);
        out.cpuFastest = std::max(out.cpuFastest, static_cast<float>(c.maxSpeed));
        out.deviceFastest = std::max(out.deviceFastest, static_cast<float>(g.maxSpeed));
        const float cpuFront = front(runs.cpuPositions()), deviceFront = front(runs.devicePositions());
        out.frontGap = std::max(out.frontGap, std::abs(deviceFront - cpuFront));
    }
    out.cpuDensity = fluid::measureNumberDensity(runs.cpuPositions(), dimension, spacing);
    out.deviceDensity = fluid::measureNumberDensity(runs.devicePositions(), dimension, spacing);
    readDeviceFluid(*second, again);
    const std::vector<glm::vec3> first = positionsOf(runs.device), repeat = positionsOf(again);
    out.repeated = first.size() == repeat.size() &&
                   std::memcmp(first.data(), repeat.data(), first.size() * sizeof(first[0])) == 0;
    std::printf("%uD dam break, %d steps, CPU / device: front apart by at most %.5f m, largest mean density error "
                "%.4f / %.4f, largest speed %.3f / %.3f m/s, substeps %u (at most %d apart), closing-speed histograms at most %llu apart in the first steps (of %llu counts in all), device run twice %s\n",
                dimension, steps, out.frontGap, out.cpuWorst, out.deviceWorst, out.cpuFastest, out.deviceFastest,
                out.substeps, out.substepGap,
                static_cast<unsigned long long>(out.binGap), static_cast<unsigned long long>(out.counted), out.repeated ? "bit for bit" : "DIFFERENT");
    std::printf("  number density at the end, CPU / device: %.3f %.3f / %.3f %.3f\n", out.cpuDensity.median,
                out.cpuDensity.p95, out.deviceDensity.median, out.deviceDensity.p95);
    return out;
}

// A dam break's tolerances, device against CPU:
// - the front (the largest x) within half a spacing at every step: the flow
//   is the same, and what rounding changes is which particle leads, by less
//   than a particle's size (issue 12's item 6 allows 3 % of the front against
//   a run with other substeps, a far larger change);
// - the largest mean density error within issue 12's bound of 3 % on both,
//   and within 50 % of the CPU's (it is one step's worst, and the two runs'
//   worst steps may differ by rounding);
// - the largest speed within 15 % of the CPU's (a splash's fastest particle);
// - in the first kEarlySteps steps, each step's closing-speed histogram
//   (particles by their fastest approach, 0.5 m/s bins) within 1 % of its
//   counts of the CPU's: a particle changes bin only if rounding moves its
//   speed across a bin's edge;
// - each step's automatic substeps within one of the CPU's: the same rule
//   on the device's statistics (closing-speed histogram, depth under
//   pressure, compression), whose rounding may tip a ceil() at its edge;
// - the number-density ratio's median and 95th percentile at the end within
//   0.03 of the CPU's (one neighbour more or fewer in 45 moves a ratio by
//   0.022 in 2D, in 251 by 0.004 in 3D);
// - two device runs of the same start bit for bit the same (no float atomics
//   in anything fed back, fixed-order sums).
void expectDamBreakLikeTheCpu(const DamBreakOutcome& o, float spacing) {
    EXPECT_LT(o.frontGap, 0.5f * spacing);
    EXPECT_LT(o.deviceWorst, 0.03);
    EXPECT_NEAR(o.deviceWorst, o.cpuWorst, 0.5 * o.cpuWorst);
    EXPECT_NEAR(o.deviceFastest, o.cpuFastest, 0.15f * o.cpuFastest);
    EXPECT_LE(o.substepGap, 1);
    EXPECT_LE(static_cast<double>(o.binGap), 0.01 * static_cast<double>(o.earlyCounted));
    EXPECT_NEAR(o.deviceDensity.median, o.cpuDensity.median, 0.03);
    EXPECT_NEAR(o.deviceDensity.p95, o.cpuDensity.p95, 0.03);
    EXPECT_TRUE(o.repeated);
}

TEST_F(DeviceFluidTest, DamBreak2DMatchesTheCpuAndRepeatsBitForBit) {
    // 288 particles at 3 cm, a 0.36 x 0.72 m column in a 1.44 m box, 2/3 s:
    // the front crosses the floor and strikes the far wall.
    const DamBreakOutcome o = damBreak(*shared().device, 2, 0.03f, glm::vec3(0.36f, 0.72f, 0.0f),
                                       glm::vec3(1.44f, 1.44f, 0.0f), 40);
    expectDamBreakLikeTheCpu(o, 0.03f);
}

TEST_F(DeviceFluidTest, DamBreak3DMatchesTheCpuAndRepeatsBitForBit) {
    // 432 particles at 2.5 cm, a 0.15 x 0.3 x 0.15 m column in a 0.6 x 0.6 x
    // 0.15 m box, 1/3 s: the column falls and spreads.
    const DamBreakOutcome o = damBreak(*shared().device, 3, 0.025f, glm::vec3(0.15f, 0.3f, 0.15f),
                                       glm::vec3(0.6f, 0.6f, 0.15f), 20);
    expectDamBreakLikeTheCpu(o, 0.025f);
}

/// A world of `backend` owned by the test.
struct OwnedWorld {
    explicit OwnedWorld(Backend backend) {
        WorldDef def;
        def.backend = backend;
        def.threads = 1;
        id = createWorld(def);
    }
    ~OwnedWorld() { destroyWorld(id); }
    OwnedWorld(const OwnedWorld&) = delete;
    OwnedWorld& operator=(const OwnedWorld&) = delete;
    WorldId id;
};

TEST_F(DeviceFluidTest, AVulkanWorldSolvesAGpuFluidOnTheDeviceAndTakesEdits) {
    // The same tank in a CPU world and, with backend gpu, in a Vulkan world
    // (lavapipe): the step reports where it ran, and the brushes' edits reach
    // the device's particles. Tolerance: after each edit the same particle
    // count as the CPU world's (the edits are the same host code), and each
    // particle within a quarter spacing of the CPU's of the same serial (the
    // tank barely moves; a serial carried wrong lands a spacing away). The
    // sweeps are not over-relaxed here: the removal's hole collapses and the
    // pour splashes, and with FluidDef's relaxation of 1.2 two runs a
    // rounding apart part by 1.9 cm in those 20 steps (1.1 mm at 1.0,
    // growing smoothly step by step at both: the flow's sensitivity, not an
    // edit lost). The device relaxes as the CPU does (GpuFluidSetupTest
    // compares the effective masses, GpuFluidSolveTest the sweeps). For the
    // same reason the substeps are fixed: under the automatic count's
    // looser compression backstop (1.5 %, docs/fluid.md) a particle of the
    // pour parted by 0.59 spacings; the automatic count on the device is
    // TankAtRestMatchesTheCpu's. And for the same reason h is 3 spacings:
    // at the default 3.5 a particle of the pour parted by 0.74 spacings.
    constexpr float kSpacing = 0.025f;
    OwnedWorld cpu(Backend::Cpu), vulkan(Backend::Vulkan);
    FluidDef def = waterDef(2, kSpacing, glm::vec3(1.0f, 0.25f, 0.0f));
    def.relaxation = 1.0f;
    def.substeps = 3;
    def.smoothing = 3.0f * kSpacing;
    def.capacity = 2000;
    for (WorldId w : {cpu.id, vulkan.id}) test::closedBox(w, glm::vec3(0.0f), glm::vec3(1.0f, 0.5f, 0.0f), 2);
    def.backend = FluidBackend::Cpu;
    const FluidId onCpu = createFluid(cpu.id, def);
    def.backend = FluidBackend::Gpu;
    const FluidId onGpu = createFluid(vulkan.id, def);
    const auto stepBoth = [&](int steps) {
        for (int i = 0; i < steps; ++i) {
            const StepStats c = stepWorld(cpu.id, kDt), g = stepWorld(vulkan.id, kDt);
            ASSERT_FALSE(c.fluids.at(0).device);
            ASSERT_TRUE(g.fluids.at(0).device);
            ASSERT_EQ(g.fluids.at(0).particles, c.fluids.at(0).particles) << "step " << i;
        }
    };
    const auto samePlaces = [&](const char* when) {
        const FluidSnapshot c = readFluid(cpu.id, onCpu), g = readFluid(vulkan.id, onGpu);
        ASSERT_EQ(g.count(), c.count()) << when;
        int apart = 0;
        float farthest = 0.0f;
        for (std::size_t k = 0; k < c.count(); ++k) {
            EXPECT_EQ(g.id[k], c.id[k]) << when;
            const float distance = glm::length(g.position[k] - c.position[k]);
            apart += distance > 0.25f * kSpacing ? 1 : 0;
            farthest = std::max(farthest, distance);
        }
        std::printf("%s: %zu particles, the farthest %.3f spacings from the CPU's\n", when, c.count(),
                    farthest / kSpacing);
        EXPECT_EQ(apart, 0) << when;
    };
    stepBoth(20);
    samePlaces("after 20 steps");
    const glm::vec3 centre(0.5f, 0.2f, 0.0f);
    const std::uint32_t removed = removeFluid(cpu.id, onCpu, centre, 0.1f);
    EXPECT_GT(removed, 20u);
    EXPECT_EQ(removeFluid(vulkan.id, onGpu, centre, 0.1f), removed);
    stepBoth(10);
    samePlaces("after a removal");
    const std::uint32_t poured = pourFluid(cpu.id, onCpu, glm::vec3(0.3f, 0.4f, 0.0f), 0.05f, glm::vec3(0.0f));
    EXPECT_GT(poured, 5u);
    EXPECT_EQ(pourFluid(vulkan.id, onGpu, glm::vec3(0.3f, 0.4f, 0.0f), 0.05f, glm::vec3(0.0f)), poured);
    stepBoth(10);
    samePlaces("after a pour");
}

TEST_F(DeviceFluidTest, AJetIntoABoxMatchesTheCpu) {
    // A 2D jet (750 particles/s at 3 m/s, 5 particles across at 2 cm, open
    // for 0.5 s) into a closed 0.8 x 0.6 m box, 2.5 s, on the CPU and on the
    // device (backend gpu). The jet's births are the host's on both, so the
    // same particles are born in the same steps. Tolerances:
    // - the same particle count at every step (no particle lost or doubled);
    // - for the first 1/3 s, while the stream flies and strikes the far wall
    //   (at about 0.23 s), every particle within a quarter spacing of the
    //   CPU's particle of the same serial (a birth appended at the wrong
    //   place or time is a spacing or more away; the splash that follows
    //   parts the runs by rounding from about 0.4 s on);
    // - after that the pool sloshes, and two runs a rounding apart slosh out
    //   of phase, so the statistics are compared as means over 1 to 2.5 s:
    //   the mean density error below the substep rule's 1 % on both and
    //   within 0.1 % of rest density of the CPU's; the number density's
    //   median within 0.05 (two neighbours in 45); the substeps within 10 %.
    constexpr float kSpacing = 0.02f;
    OwnedWorld cpu(Backend::Cpu), vulkan(Backend::Vulkan);
    FluidDef def;
    def.name = "water";
    def.dimension = 2;
    def.spacing = kSpacing;
    FluidJetDef jet;
    jet.position = glm::vec3(0.1f, 0.45f, 0.0f);
    jet.direction = glm::vec3(1.0f, 0.2f, 0.0f);
    jet.speed = 3.0f;
    jet.rate = 750.0f;
    jet.radius = 0.04f;
    jet.duration = 0.5f;
    def.jets.push_back(jet);
    for (WorldId w : {cpu.id, vulkan.id}) test::closedBox(w, glm::vec3(0.0f), glm::vec3(0.8f, 0.6f, 0.0f), 2);
    def.backend = FluidBackend::Cpu;
    const FluidId onCpu = createFluid(cpu.id, def);
    def.backend = FluidBackend::Gpu;
    const FluidId onGpu = createFluid(vulkan.id, def);
    int apartEarly = 0, samples = 0;
    std::uint64_t cpuSubsteps = 0, deviceSubsteps = 0, particles = 0;
    double cpuError = 0.0, deviceError = 0.0, cpuDensity = 0.0, deviceDensity = 0.0;
    for (int i = 0; i < 150; ++i) {
        const StepStats c = stepWorld(cpu.id, kDt), g = stepWorld(vulkan.id, kDt);
        const FluidStepStats& fc = c.fluids.at(0);
        const FluidStepStats& fg = g.fluids.at(0);
        ASSERT_TRUE(fg.device);
        ASSERT_EQ(fg.born, fc.born) << "step " << i;
        ASSERT_EQ(fg.particles, fc.particles) << "step " << i;
        particles = fc.particles;
        if (i < 20 || (i >= 60 && i % 10 == 9)) {
            const FluidSnapshot cs = readFluid(cpu.id, onCpu), gs = readFluid(vulkan.id, onGpu);
            if (i < 20) {
                for (std::size_t k = 0; k < cs.count(); ++k) {
                    apartEarly += glm::length(gs.position[k] - cs.position[k]) > 0.25f * kSpacing ? 1 : 0;
                }
            } else {
                cpuDensity += fluid::measureNumberDensity(cs.position, 2, kSpacing).median;
                deviceDensity += fluid::measureNumberDensity(gs.position, 2, kSpacing).median;
                ++samples;
            }
        }
        if (i >= 60) {
            cpuError += fc.meanDensityError / 90.0;
            deviceError += fg.meanDensityError / 90.0;
            cpuSubsteps += fc.substeps;
            deviceSubsteps += fg.substeps;
        }
    }
    cpuDensity /= samples;
    deviceDensity /= samples;
    std::printf("jet into a box, CPU / device: %llu particles on both, none apart in the first 1/3 s: %s; over 1 to "
                "2.5 s mean density error %.5f / %.5f, number density median %.3f / %.3f, substeps %llu / %llu\n",
                static_cast<unsigned long long>(particles), apartEarly == 0 ? "yes" : "NO", cpuError, deviceError,
                cpuDensity, deviceDensity, static_cast<unsigned long long>(cpuSubsteps),
                static_cast<unsigned long long>(deviceSubsteps));
    EXPECT_EQ(particles, 375u);  // 750 a second for 0.5 s
    EXPECT_EQ(apartEarly, 0);
    EXPECT_LT(cpuError, 0.01);
    EXPECT_LT(deviceError, 0.01);
    EXPECT_NEAR(deviceError, cpuError, 0.001);
    EXPECT_NEAR(deviceDensity, cpuDensity, 0.05);
    EXPECT_NEAR(static_cast<double>(deviceSubsteps), static_cast<double>(cpuSubsteps), 0.1 * cpuSubsteps);
}

TEST_F(DeviceFluidTest, ParticlesThatStopBeingFiniteAreRemovedAndCounted) {
    // tests/fluid/fluid_non_finite_test.cpp on the device: a fluid whose
    // gravity is 3e38 m/s^2 (finite, so accepted) overflows within its first
    // steps; each such particle is removed in the substep where it arises and
    // counted, a calm fluid in the same world keeps every particle, and no
    // snapshot holds NaN or infinity.
    OwnedWorld w(Backend::Vulkan);
    const auto smallFluid = [](const char* name, glm::vec3 gravity, float x0) {
        FluidDef def = waterDef(2, 0.1f, glm::vec3(0.6f, 0.6f, 0.0f));
        def.name = name;
        def.gravity = gravity;
        def.blocks[0].min.x = x0;
        def.blocks[0].max.x = x0 + 0.6f;
        def.backend = FluidBackend::Gpu;
        return def;
    };
    const FluidId wild = createFluid(w.id, smallFluid("wild", glm::vec3(3.0e38f, 3.0e38f, 0.0f), 0.0f));
    const FluidId calm = createFluid(w.id, smallFluid("calm", glm::vec3(0.0f, -9.81f, 0.0f), 10.0f));
    ASSERT_EQ(readFluid(w.id, wild).count(), 36u);
    std::uint64_t removedWild = 0, removedCalm = 0;
    for (int i = 0; i < 40; ++i) {
        const StepStats s = stepWorld(w.id, kDt);
        ASSERT_TRUE(s.fluids.at(0).device && s.fluids.at(1).device);
        removedWild += s.fluids[0].nonFinite;
        removedCalm += s.fluids[1].nonFinite;
        EXPECT_EQ(s.fluids[0].particles + removedWild, 36u);  // removed ones are gone, and counted
    }
    EXPECT_GT(removedWild, 0u);
    EXPECT_EQ(removedCalm, 0u);
    for (const FluidId id : {wild, calm}) {
        const FluidSnapshot s = readFluid(w.id, id);
        for (std::size_t i = 0; i < s.count(); ++i) {
            EXPECT_TRUE(std::isfinite(glm::length(s.position[i])) && std::isfinite(glm::length(s.velocity[i])))
                << "particle " << i;
        }
    }
    EXPECT_EQ(readFluid(w.id, calm).count(), 36u);
}

TEST_F(DeviceFluidTest, ListsLongerThanTheirRoomAreGrownAndTheSubstepRunAgain) {
    // Four blocks laid on the same lattice sites (particles on one point,
    // four times the neighbours of the lattice: about 80 a particle in these
    // small blocks, past the device lists' first room of 64 a particle),
    // stepped once on the CPU and on the device. The device's setup finds
    // more entries than its lists hold, grows them and runs the substep
    // again, so nothing is dropped: the same neighbours a particle as the
    // CPU's (an integer count, exact), no overflow on either, the same
    // particles, and each within a hundredth of a spacing of the CPU's of the
    // same serial after the step (one substep from the same state; lists cut
    // short would leave some particles' pressure unsolved, a push of the
    // order of the spacing).
    constexpr float kSpacing = 0.05f;
    OwnedWorld cpu(Backend::Cpu), vulkan(Backend::Vulkan);
    FluidDef def = waterDef(2, kSpacing, glm::vec3(0.5f, 0.5f, 0.0f));
    for (int copy = 0; copy < 3; ++copy) def.blocks.push_back(def.blocks[0]);
    def.substeps = 1;  // the step's statistics are then of the first setup, from the same particles
    for (WorldId w : {cpu.id, vulkan.id}) test::closedBox(w, glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 0.0f), 2);
    def.backend = FluidBackend::Cpu;
    createFluid(cpu.id, def);
    def.backend = FluidBackend::Gpu;
    createFluid(vulkan.id, def);
    const FluidStepStats c = stepWorld(cpu.id, kDt).fluids.at(0), g = stepWorld(vulkan.id, kDt).fluids.at(0);
    std::printf("four blocks on one lattice: %llu particles, neighbours a particle %.3f / %.3f, overflows %llu / "
                "%llu\n",
                static_cast<unsigned long long>(c.particles), c.meanNeighbours, g.meanNeighbours,
                static_cast<unsigned long long>(c.neighbourOverflows),
                static_cast<unsigned long long>(g.neighbourOverflows));
    ASSERT_TRUE(g.device);
    EXPECT_EQ(g.particles, c.particles);
    EXPECT_GT(c.meanNeighbours, 64.0);
    EXPECT_EQ(g.meanNeighbours, c.meanNeighbours);
    EXPECT_EQ(g.neighbourOverflows, c.neighbourOverflows);
    EXPECT_EQ(c.neighbourOverflows, 0u);
    const FluidSnapshot cs = readFluid(cpu.id, FluidId{1}), gs = readFluid(vulkan.id, FluidId{1});
    ASSERT_EQ(gs.count(), cs.count());
    float farthest = 0.0f, moved = 0.0f;
    for (std::size_t k = 0; k < cs.count(); ++k) {
        farthest = std::max(farthest, glm::length(gs.position[k] - cs.position[k]));
        moved = std::max(moved, glm::length(cs.velocity[k]) * kDt);
    }
    std::printf("after the step: particles apart by at most %.2e m (the CPU's moved up to %.4f m)\n", farthest, moved);
    EXPECT_LT(farthest, 0.01f * kSpacing);
}

TEST_F(DeviceFluidTest, AGridCappedByItsCellBudgetIsPlacedAsTheCpus) {
    // A column of water against the right wall of a 61 m box and a small
    // block 60 m to its left on the same floor: the particles' box spans more
    // cells than the budget allows (256 a side for a small fluid), so both
    // the CPU and the device centre the capped window on the particles'
    // median, in the column (grid.cpp, cappedWindowOrigin; the device reads
    // the coordinates back for it), and clamp the small block into the edge
    // cells. A window anchored at the box's low end instead would clamp the
    // whole column into one row of cells, where the crushed-cell bound cuts
    // its lists. Tolerance: the same particles and neighbour overflows, each
    // particle within a quarter spacing of the CPU's of the same serial after
    // 20 steps.
    constexpr float kSpacing = 0.025f;
    FluidDef def = waterDef(2, kSpacing, glm::vec3(0.25f, 0.5f, 0.0f));
    def.blocks[0].min.x = 60.75f;
    def.blocks[0].max.x = 61.0f;
    def.blocks.push_back({glm::vec3(0.0f), glm::vec3(0.1f, 0.1f, 0.0f), glm::vec3(0.0f)});
    TwoRuns runs(*shared().device, def, glm::vec3(61.0f, 1.0f, 0.0f));
    std::uint64_t overflows = 0;
    for (int i = 0; i < 20; ++i) {
        const auto [c, g] = runs.step();
        ASSERT_EQ(g.particles, c.particles);
        EXPECT_EQ(g.neighbourOverflows, c.neighbourOverflows) << "step " << i;
        overflows += g.neighbourOverflows;
    }
    runs.devicePositions();
    const std::vector<glm::vec3> cs = TwoRuns::bySerial(*runs.cpu), gs = TwoRuns::bySerial(runs.device);
    int apart = 0;
    for (std::size_t k = 0; k < cs.size(); ++k) apart += glm::length(gs[k] - cs[k]) > 0.25f * kSpacing ? 1 : 0;
    std::printf("capped grid: %zu particles, %d apart from the CPU's, %llu neighbour overflows\n", cs.size(), apart,
                static_cast<unsigned long long>(overflows));
    EXPECT_GT(cs.size(), 200u);
    EXPECT_EQ(apart, 0);
}

TEST_F(DeviceFluidTest, AStepMovesAFewHundredBytesASubstepNotTheParticles) {
    // The premise of a device fluid (issue 16): its particles stay on the
    // device. A step reads back one report a substep (FluidSubstepReport,
    // 336 bytes) and uploads nothing; reading the fluid (readFluid, the
    // renderer) brings the particles back once, whatever the steps before.
    // Bounds: at most 400 bytes down a substep and none up over 30 steps of a
    // 400-particle tank (whose particles alone are 10 KB); one readFluid then
    // brings at least the positions back.
    OwnedWorld w(Backend::Vulkan);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(1.0f, 0.5f, 0.0f), 2);
    FluidDef def = waterDef(2, 0.025f, glm::vec3(1.0f, 0.25f, 0.0f));
    def.backend = FluidBackend::Gpu;
    const FluidId f = createFluid(w.id, def);
    stepWorld(w.id, kDt);  // the first step makes the passes' buffers
    const TransferStats before = transferStats(w.id);
    std::uint64_t substeps = 0;
    for (int i = 0; i < 30; ++i) substeps += stepWorld(w.id, kDt).fluids.at(0).substeps;
    const TransferStats after = transferStats(w.id);
    const std::uint64_t down = after.bytesDownloaded - before.bytesDownloaded;
    std::printf("30 steps, %llu substeps: %llu bytes down, %llu up\n", static_cast<unsigned long long>(substeps),
                static_cast<unsigned long long>(down),
                static_cast<unsigned long long>(after.bytesUploaded - before.bytesUploaded));
    EXPECT_LE(down, 400u * substeps);
    EXPECT_EQ(after.bytesUploaded, before.bytesUploaded);
    const FluidSnapshot s = readFluid(w.id, f);
    EXPECT_EQ(s.count(), 400u);
    EXPECT_GE(transferStats(w.id).bytesDownloaded - after.bytesDownloaded, 400u * 8u);
}

TEST_F(DeviceFluidTest, AJetsBirthsGoUpAndNothingComesBack) {
    // A jet's births are emitted on the host from the jets' own state and
    // uploaded; the device's particles are not read for it. A 2D jet (600
    // particles/s, open 0.4 s) into a closed box on the device, 30 steps:
    // exactly the births' bytes go up (36 a birth in 2D: position,
    // velocity and anchor 8 each, pressure, time still and serial 4 each)
    // and at most a report a substep (400 bytes) comes down; the particles
    // then read once are exactly the births (the jet's count, 600 x 0.4,
    // less the first step's, which the world steps before measuring).
    OwnedWorld w(Backend::Vulkan);
    test::closedBox(w.id, glm::vec3(0.0f), glm::vec3(0.8f, 0.6f, 0.0f), 2);
    FluidDef def;
    def.name = "water";
    def.dimension = 2;
    def.spacing = 0.02f;
    def.backend = FluidBackend::Gpu;
    FluidJetDef jet;
    jet.position = glm::vec3(0.1f, 0.45f, 0.0f);
    jet.direction = glm::vec3(1.0f, 0.2f, 0.0f);
    jet.speed = 3.0f;
    jet.rate = 600.0f;
    jet.radius = 0.04f;
    jet.duration = 0.4f;
    def.jets.push_back(jet);
    const FluidId f = createFluid(w.id, def);
    const std::uint64_t first = stepWorld(w.id, kDt).fluids.at(0).born;  // the passes' buffers made
    const TransferStats before = transferStats(w.id);
    std::uint64_t substeps = 0, born = 0;
    for (int i = 0; i < 30; ++i) {
        const FluidStepStats s = stepWorld(w.id, kDt).fluids.at(0);
        ASSERT_TRUE(s.device);
        substeps += s.substeps;
        born += s.born;
    }
    const TransferStats after = transferStats(w.id);
    std::printf("a jet on the device, 30 steps: %llu births, %llu bytes up, %llu down over %llu substeps\n",
                static_cast<unsigned long long>(born),
                static_cast<unsigned long long>(after.bytesUploaded - before.bytesUploaded),
                static_cast<unsigned long long>(after.bytesDownloaded - before.bytesDownloaded),
                static_cast<unsigned long long>(substeps));
    EXPECT_EQ(first + born, 240u);
    EXPECT_EQ(after.bytesUploaded - before.bytesUploaded, 36u * born);
    EXPECT_LE(after.bytesDownloaded - before.bytesDownloaded, 400u * substeps);
    EXPECT_EQ(readFluid(w.id, f).count(), first + born);
}

TEST_F(DeviceFluidTest, BodiesAreGatheredFromTheReportedBoxWithoutReadingParticles) {
    // Which bodies are near a 2D fluid on the device is asked of the box and
    // largest speed its last substep reported, by the CPU gather's own query
    // (its margin: h, a spacing and a step's travel, against Box2D's
    // fattened boxes). A slab falls from 0.75 m (sent down at 0.5 m/s) onto
    // a resting 0.25 m tank whose fluid is on the device, and the same over
    // a CPU twin whose gather is asked before every step; the slab falls
    // alike in both worlds until the fluid meets it. The device's first
    // step with bodies is the first that uploads anything (their shapes).
    // Bounds:
    // - until then no particle comes back (at most a report a substep, 400
    //   bytes) and nothing goes up;
    // - the device gathers the slab within a step of the step at which the
    //   CPU's gather first finds it (the two tanks agree within a quarter
    //   spacing), and not in the first 10 steps, as asking of every body in
    //   the world would (the slab starts 0.49 m above the water).
    OwnedWorld gpuWorld(Backend::Vulkan), cpuWorld(Backend::Cpu);
    FluidDef def = waterDef(2, 0.025f, glm::vec3(1.0f, 0.25f, 0.0f));
    BodyDef slab;
    slab.position = glm::vec2(0.5f, 0.75f);
    slab.linearVelocity = glm::vec2(0.0f, -0.5f);
    slab.density = 500.0f;
    slab.shapes = {boxShape(glm::vec2(0.1f, 0.02f))};
    for (WorldId w : {gpuWorld.id, cpuWorld.id}) {
        test::closedBox(w, glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 0.0f), 2);
        def.backend = w.index == gpuWorld.id.index ? FluidBackend::Gpu : FluidBackend::Cpu;
        createFluid(w, def);
        createBody(w, slab);
    }
    // The CPU's answer: the first step whose gather finds the slab.
    int cpuNear = -1;
    for (int step = 0; step < 120 && cpuNear < 0; ++step) {
        World& c = worldFromId(cpuWorld.id);
        coupling::FluidLink link(c.bodies.get());
        if (link.gather(*c.fluids.at(0), kDt) != nullptr) cpuNear = step;
        stepWorld(cpuWorld.id, kDt);
    }
    stepWorld(gpuWorld.id, kDt);  // the first step makes the passes' buffers (the CPU's loop counts it as step 0)
    const TransferStats before = transferStats(gpuWorld.id);
    TransferStats last = before;
    std::uint64_t substeps = 0;
    int deviceNear = -1;
    for (int step = 1; step < 120 && deviceNear < 0; ++step) {
        const FluidStepStats s = stepWorld(gpuWorld.id, kDt).fluids.at(0);
        ASSERT_TRUE(s.device);
        const TransferStats now = transferStats(gpuWorld.id);
        if (now.bytesUploaded > last.bytesUploaded) {
            deviceNear = step;
        } else {
            substeps += s.substeps;
            last = now;
        }
    }
    std::printf("the slab gathered at step %d on the device, %d by the CPU's gather; before it %llu bytes down over "
                "%llu substeps\n",
                deviceNear, cpuNear, static_cast<unsigned long long>(last.bytesDownloaded - before.bytesDownloaded),
                static_cast<unsigned long long>(substeps));
    ASSERT_GE(deviceNear, 0) << "the slab reached the water and the device never gathered it";
    EXPECT_EQ(last.bytesUploaded, before.bytesUploaded);
    EXPECT_LE(last.bytesDownloaded - before.bytesDownloaded, 400u * substeps);
    EXPECT_NEAR(deviceNear, cpuNear, 1);
    EXPECT_GT(deviceNear, 10);
}

TEST_F(DeviceFluidTest, AFloatingBoxSettlesAsOnTheCpu) {
    // A box of half the water's density (0.2 x 0.1 m, 500 kg/m^2) dropped
    // from 0.45 m into a 1 x 0.25 m tank at 2.5 cm (400 particles), 3 s, on
    // the CPU and on the device: the device solves the contacts with the
    // box in the CPU's order, one invocation, changing the box's velocity as
    // it goes, and hands its impulses to Box2D; the particles a body moved
    // are carried after Box2D's step. Tolerances:
    // - the box's height over the first 0.5 s (the drop and the splash)
    //   within 5 mm of the CPU's at every step (the same impulses up to the
    //   setup's rounding; Box2D integrates both alike);
    // - its height over the last second, averaged, within 5 mm of the
    //   CPU's (a floating body's depth is set by the water around it, which
    //   two runs a rounding apart slosh differently), and its vertical
    //   speed's mean magnitude over that second below 0.05 m/s on both (it
    //   floats, settling);
    // - the fluid stays on the device with the same particle count, and no
    //   particle ends inside the box (beyond 2 mm) on the device;
    // - over the last second the device's steps read back no particle: at
    //   most 500 bytes a substep (the lists' entries after the solve, 16;
    //   the report after the integration, 336; the bodies' report, 16; the
    //   box's velocities and impulses, 48; the carry's box, 24 a step),
    //   where the particles alone are 20 KB.
    constexpr float kSpacing = 0.025f;
    OwnedWorld cpu(Backend::Cpu), vulkan(Backend::Vulkan);
    FluidDef def = waterDef(2, kSpacing, glm::vec3(1.0f, 0.25f, 0.0f));
    BodyDef box;
    box.position = glm::vec2(0.5f, 0.45f);
    box.density = 500.0f;
    box.shapes = {boxShape(glm::vec2(0.1f, 0.05f))};
    for (WorldId w : {cpu.id, vulkan.id}) {
        test::closedBox(w, glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 0.0f), 2);
        def.backend = w.index == vulkan.id.index ? FluidBackend::Gpu : FluidBackend::Cpu;
        createFluid(w, def);
        createBody(w, box);
    }
    float earlyGap = 0.0f;
    double cpuLate = 0.0, deviceLate = 0.0, cpuBob = 0.0, deviceBob = 0.0;
    std::uint64_t lateSubsteps = 0, lateDown = 0;
    for (int i = 0; i < 180; ++i) {
        const TransferStats before = transferStats(vulkan.id);
        const StepStats c = stepWorld(cpu.id, kDt), g = stepWorld(vulkan.id, kDt);
        if (i >= 120) {
            lateSubsteps += g.fluids.at(0).substeps;
            lateDown += transferStats(vulkan.id).bytesDownloaded - before.bytesDownloaded;
        }
        ASSERT_TRUE(g.fluids.at(0).device) << "step " << i;
        ASSERT_EQ(g.fluids.at(0).particles, c.fluids.at(0).particles);
        const BodySnapshot cb = readBodies(cpu.id).at(0), gb = readBodies(vulkan.id).at(0);
        if (i < 30) earlyGap = std::max(earlyGap, std::abs(gb.position.y - cb.position.y));
        if (i >= 120) {
            cpuLate += cb.position.y / 60.0;
            deviceLate += gb.position.y / 60.0;
            cpuBob += std::abs(cb.linearVelocity.y) / 60.0;
            deviceBob += std::abs(gb.linearVelocity.y) / 60.0;
        }
    }
    const BodySnapshot gb = readBodies(vulkan.id).at(0);
    float deepest = 0.0f;
    for (const glm::vec3& x : readFluid(vulkan.id, FluidId{1}).position) {
        const glm::vec2 local = glm::vec2(x) - gb.position;
        const float c = std::cos(-gb.angle), s = std::sin(-gb.angle);
        const glm::vec2 r(c * local.x - s * local.y, s * local.x + c * local.y);
        deepest = std::max(deepest, std::min(0.1f - std::abs(r.x), 0.05f - std::abs(r.y)));
    }
    std::printf("a floating box, CPU / device: height apart by at most %.4f m over 0.5 s; over the last second mean "
                "height %.4f / %.4f m, mean |vertical speed| %.4f / %.4f m/s, %llu bytes down over %llu substeps; "
                "deepest particle inside the box on the device %.4f m\n",
                earlyGap, cpuLate, deviceLate, cpuBob, deviceBob, static_cast<unsigned long long>(lateDown),
                static_cast<unsigned long long>(lateSubsteps), deepest);
    EXPECT_LE(lateDown, 500u * lateSubsteps);
    EXPECT_LT(earlyGap, 0.005f);
    EXPECT_NEAR(deviceLate, cpuLate, 0.005);
    EXPECT_LT(cpuBob, 0.05);
    EXPECT_LT(deviceBob, 0.05);
    EXPECT_LT(deepest, 0.002f);
}

TEST_F(DeviceFluidTest, TheContactsWithMovedBodiesAreListedInTheCpusOrder) {
    // The contacts with bodies the fluid moves are solved one after another,
    // in the CPU's order: particles in grid order, each one's contacts in
    // slot order. The device lists them by a prefix sum of each particle's
    // count (within workgroups of 64, then over the workgroups); here the
    // list after each step is checked, entry for entry, against that order
    // computed on the host from the same contacts. A plank (1.6 x 0.06 m,
    // density 500) dropped onto a 2 m wide pool (1,600 particles, 25
    // workgroups): its contacts come from particles of many workgroups. The
    // world tests above (floating box, crate, showcase) compare outcomes
    // within tolerances, which a listing in another order stays inside.
    constexpr float kSpacing = 0.025f;
    OwnedWorld vulkan(Backend::Vulkan);
    FluidDef def = waterDef(2, kSpacing, glm::vec3(2.0f, 0.5f, 0.0f));
    def.backend = FluidBackend::Gpu;
    test::closedBox(vulkan.id, glm::vec3(0.0f), glm::vec3(2.0f, 1.5f, 0.0f), 2);
    createFluid(vulkan.id, def);
    BodyDef plank;
    plank.position = glm::vec2(1.0f, 0.56f);
    plank.density = 500.0f;
    plank.shapes = {boxShape(glm::vec2(0.8f, 0.03f))};
    createBody(vulkan.id, plank);
    std::size_t listedSteps = 0, mostWorkgroups = 0;
    for (int step = 0; step < 20; ++step) {
        stepWorld(vulkan.id, kDt);
        World& w = worldFromId(vulkan.id);
        ASSERT_TRUE(w.deviceFluids.at(0));
        const gpu::FluidDynamicListing l = gpu::readFluidDynamicListing(deviceFluidContacts(*w.deviceFluids[0]));
        std::vector<std::uint32_t> expected;
        std::vector<bool> workgroups(l.counts.size() / 64 + 1, false);
        for (std::uint32_t i = 0; i < l.counts.size(); ++i) {
            for (std::uint32_t j = 0; j < std::min(l.counts[i], l.slots); ++j) {
                const std::uint32_t at = i * l.slots + j;
                if (l.bodies.at(l.contacts[at].body).invMass > 0.0f) {
                    expected.push_back(at);
                    workgroups[i / 64] = true;
                }
            }
        }
        ASSERT_EQ(l.list, expected) << "step " << step;
        if (!expected.empty()) listedSteps += 1;
        mostWorkgroups = std::max<std::size_t>(mostWorkgroups, std::count(workgroups.begin(), workgroups.end(), true));
    }
    // The check had something to check: the plank touched the water from its
    // fourth step on, through particles of several workgroups.
    EXPECT_GE(listedSteps, 15u);
    EXPECT_GE(mostWorkgroups, 4u);
}

TEST_F(DeviceFluidTest, AJetPushesACrateAsOnTheCpu) {
    // The water cannon of the game use case: a jet (8 m/s, 400 particles a
    // second of 0.9 kg each, 0.6 s: a stream of about 2,900 N) strikes a
    // crate (0.2 m, 4000 kg/m^2: 160 kg) resting on a static ground edge,
    // 1.5 s, on the CPU and on the device (whose jets' births are the
    // host's, and whose contacts with the crate are solved in the CPU's
    // order and handed to Box2D). The crate slides where the stream's push
    // beats its friction, so its path amplifies small differences; how
    // much is measured here too, by a second CPU run whose gravity is 2
    // units in the last place stronger (a rounding-sized change).
    // Tolerances:
    // - the device's crate within 3 times that run's distance from the CPU's
    //   crate (at most over the run), plus 1 cm: a device that differs from
    //   the CPU only by rounding stays in the envelope rounding makes; one
    //   that loses or doubles a share of the stream's momentum does not;
    // - the crate pushed at least 20 cm on both;
    // - the strikes on the crate (collision events) within 15 % of the CPU's.
    //   A count of discrete events moves with rounding as the path does:
    //   thirteen CPU runs whose gravity was -6 to +6 units in the last place
    //   off counted 120 to 137 strikes around this run's 125 (up to 10 %;
    //   third session of 2026-12-07, after the setup's sums became a tree
    //   and the solve's four chains), and the device's sums are a rounding
    //   away from the CPU's (fluid_setup.comp adds in list order). 5 % held
    //   only while both sides happened to land close.
    OwnedWorld cpu(Backend::Cpu), vulkan(Backend::Vulkan), rounded(Backend::Cpu);
    FluidDef def;
    def.name = "water";
    def.dimension = 2;
    def.spacing = 0.03f;
    def.capacity = 1000;
    FluidJetDef jet;
    jet.position = glm::vec3(0.2f, 0.3f, 0.0f);
    jet.direction = glm::vec3(1.0f, 0.0f, 0.0f);
    jet.speed = 8.0f;
    jet.rate = 400.0f;
    jet.radius = 0.04f;
    jet.duration = 0.6f;
    def.jets.push_back(jet);
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.shapes = {edgeShape(glm::vec2(-1.0f, 0.0f), glm::vec2(4.0f, 0.0f))};
    BodyDef crate;
    crate.position = glm::vec2(1.2f, 0.1f);
    crate.density = 4000.0f;
    crate.shapes = {boxShape(glm::vec2(0.1f, 0.1f))};
    for (WorldId w : {cpu.id, vulkan.id, rounded.id}) {
        def.backend = w.index == vulkan.id.index ? FluidBackend::Gpu : FluidBackend::Cpu;
        def.gravity = glm::vec3(0.0f, -9.81f, 0.0f);
        if (w.index == rounded.id.index) {
            def.gravity.y = std::nextafter(std::nextafter(def.gravity.y, -1.0e9f), -1.0e9f);
        }
        createBody(w, ground);
        createBody(w, crate);
        createFluid(w, def);
    }
    float gap = 0.0f, spread = 0.0f;
    std::uint64_t cpuStrikes = 0, deviceStrikes = 0, roundedStrikes = 0;
    for (int i = 0; i < 90; ++i) {
        const StepStats c = stepWorld(cpu.id, kDt), g = stepWorld(vulkan.id, kDt);
        stepWorld(rounded.id, kDt);
        ASSERT_TRUE(g.fluids.at(0).device) << "step " << i;
        ASSERT_EQ(g.fluids.at(0).particles, c.fluids.at(0).particles);
        const glm::vec2 at = readBodies(cpu.id).at(1).position;
        gap = std::max(gap, glm::distance(at, readBodies(vulkan.id).at(1).position));
        spread = std::max(spread, glm::distance(at, readBodies(rounded.id).at(1).position));
        for (const ParticleEvent& e : takeEvents(cpu.id).events) cpuStrikes += e.body.index == 2 ? 1u : 0u;
        for (const ParticleEvent& e : takeEvents(vulkan.id).events) deviceStrikes += e.body.index == 2 ? 1u : 0u;
        for (const ParticleEvent& e : takeEvents(rounded.id).events) roundedStrikes += e.body.index == 2 ? 1u : 0u;
    }
    const float cpuPush = readBodies(cpu.id).at(1).position.x - 1.2f;
    const float devicePush = readBodies(vulkan.id).at(1).position.x - 1.2f;
    const float roundedPush = readBodies(rounded.id).at(1).position.x - 1.2f;
    std::printf("a jet pushes a crate, CPU / device / CPU with gravity 2 ulp stronger: pushed %.4f / %.4f / %.4f m; "
                "the device at most %.4f m from the CPU, the rounded run %.4f m; strikes %llu / %llu / %llu\n",
                cpuPush, devicePush, roundedPush, gap, spread, static_cast<unsigned long long>(cpuStrikes),
                static_cast<unsigned long long>(deviceStrikes), static_cast<unsigned long long>(roundedStrikes));
    EXPECT_LT(gap, 3.0f * spread + 0.01f);
    EXPECT_GT(cpuPush, 0.2f);
    EXPECT_GT(devicePush, 0.2f);
    EXPECT_GT(cpuStrikes, 0u);
    EXPECT_NEAR(static_cast<double>(deviceStrikes), static_cast<double>(cpuStrikes), 0.15 * cpuStrikes);
}

TEST_F(DeviceFluidTest, TheCarryAfterBox2DsStepIsTheCpus) {
    // After Box2D's step a particle inside a shape of a body the fluid moves
    // goes with the body, from where the fluid's copy ended (here (0.5,
    // 0.2), unturned) to where Box2D put it ((0.53, 0.21), turned by 0.2
    // rad), then out through the nearest surface; neither move may cross a
    // still edge (a static body's segment at x = 0.62). The device's carry
    // (fluid_carry.comp) and the CPU's carryOutOfMovedBodies on copies of
    // the same 600 particles: equal bit for bit (the same operations on the
    // same numbers, the turn's cosine and sine computed on the host for
    // both), and the rule acts: some particles move, and some are held by
    // the still edge (inside the crate's new pose past x = 0.62 on the CPU's
    // side of it: the crate straddles the edge).
    test::FluidWorld world{1};
    test::closedBox(world.id, glm::vec3(0.0f), glm::vec3(1.0f, 1.0f, 0.0f), 2);
    createFluid(world.id, waterDef(2, 0.02f, glm::vec3(0.6f, 0.4f, 0.0f)));
    World& w = worldFromId(world.id);
    fluid::FluidState& cpu = *w.fluids.at(0);
    fluid::FluidState device = cpu;
    DeviceFluidPtr g = createDeviceFluid(*shared().device, device);
    const fluid::LocalShape crate{kernels::SD_BODY_SHAPE_POLYGON,
                                  {glm::vec2(-0.1f, -0.1f), glm::vec2(0.1f, -0.1f), glm::vec2(0.1f, 0.1f),
                                   glm::vec2(-0.1f, 0.1f)},
                                  0.0f};
    const fluid::LocalShape edge{kernels::SD_BODY_SHAPE_SEGMENT, {glm::vec2(0.62f, 0.0f), glm::vec2(0.62f, 0.5f)},
                                 0.0f};
    fluid::FluidBodyStep moved;
    fluid::StepBody box;
    box.slot = 0;
    box.centre = glm::vec2(0.53f, 0.21f);
    box.angle = 0.2f;
    box.invMass = 1.0f / 40.0f;
    box.invInertia = 1.0f / 0.27f;
    fluid::StepBody ground;
    ground.slot = 1;
    moved.bodies = {box, ground};
    moved.shapeBody = {0, 1};
    moved.shapeSource = {&crate, &edge};
    cpu.bodiesAtEnd = {{0, glm::vec2(0.5f, 0.2f), 0.0f}, {1, glm::vec2(0.0f), 0.0f}};
    device.bodiesAtEnd = cpu.bodiesAtEnd;
    const std::vector<glm::vec2> before = cpu.p2.position;
    fluid::FluidBodyStep onDevice = moved;
    const std::uint64_t carried = fluid::carryOutOfMovedBodies(w.pool, cpu, moved, w.colliders);
    carryDeviceFluid(*g, device, onDevice);
    readDeviceFluid(*g, device);
    ASSERT_EQ(device.p2.position.size(), cpu.p2.position.size());
    std::size_t held = 0;
    for (std::size_t i = 0; i < before.size(); ++i) {
        const glm::vec2 x = before[i];
        const glm::vec2 d = x - glm::vec2(0.5f, 0.2f);
        const glm::vec2 to = glm::vec2(0.53f, 0.21f) + glm::vec2(std::cos(0.2f) * d.x - std::sin(0.2f) * d.y,
                                                                  std::sin(0.2f) * d.x + std::cos(0.2f) * d.y);
        const bool inside = std::abs(d.x) < 0.1f && std::abs(d.y) < 0.1f;
        held += inside && to.x > 0.62f && cpu.p2.position[i] == x ? 1u : 0u;
    }
    const bool same = std::memcmp(device.p2.position.data(), cpu.p2.position.data(),
                                  cpu.p2.position.size() * sizeof(glm::vec2)) == 0;
    std::printf("the carry after Box2D's step: %llu of %zu particles carried on the CPU, %zu held by the still "
                "edge; the device's %s\n",
                static_cast<unsigned long long>(carried), before.size(), held, same ? "bit for bit the same" : "DIFFERENT");
    EXPECT_TRUE(same);
    EXPECT_GT(carried, 0u);
    EXPECT_GT(held, 0u);
}

TEST_F(DeviceFluidTest, TheShowcasesBodiesFollowTheCpusWhileTheStreamFlies) {
    // The showcase level (scenes/showcase.toml) in two Vulkan worlds, its
    // fluid on the CPU in one and on the device in the other, over its
    // first 1.5 s: the truck drives, the cannon on it opens at 0.3 s and its
    // stream flies over the log pile to the ledge, striking the ground and
    // the logs (static bodies, joints holding the truck's wheels, a jet on a
    // dynamic body, strikes). Every body within 1 mm of the CPU run's at
    // every step and the same particle count; and through the first second
    // (the stream's flight and first strikes on the ground) the median
    // particle, by serial, within a quarter spacing (7.5 mm) of the CPU's
    // (a single splash drop may part further). Later the splash is chaotic (a CPU run
    // with gravity 1 ulp stronger parts from the CPU run as fast as the
    // device does, and the crates it pushes end metres apart in either:
    // docs/fluid.md, "Whole steps"), so the bodies are compared while the
    // water has not yet reached the crates. The level's effects and fires
    // (flames, smoke, steam: drawing only, nothing of them moves a body or
    // the water) are left out, so the test times the fluid.
    SceneDef scene = loadScene(std::string(SPINDRIFT_SOURCE_DIR) + "/scenes/showcase.toml");
    scene.fires.clear();
    scene.emitters.clear();
    scene.world.backend = Backend::Cpu;
    const WorldId onCpu = buildWorld(scene);
    scene.world.backend = Backend::Vulkan;
    scene.fluids.at(0).backend = FluidBackend::Gpu;
    const WorldId onDevice = buildWorld(scene);
    float apart = 0.0f, median = 0.0f;
    std::string farthest;
    std::uint32_t particles = 0;
    for (int i = 0; i < 90; ++i) {
        const StepStats c = stepWorld(onCpu, scene.run.dt), g = stepWorld(onDevice, scene.run.dt);
        takeEvents(onCpu);
        takeEvents(onDevice);
        ASSERT_TRUE(g.fluids.at(0).device);
        ASSERT_EQ(g.fluids.at(0).particles, c.fluids.at(0).particles) << "step " << i;
        particles = c.fluids.at(0).particles;
        if (i % 10 == 9 && i < 60) {
            const FluidSnapshot cs = readFluid(onCpu, FluidId{1}), gs = readFluid(onDevice, FluidId{1});
            std::vector<glm::vec3> bySerial(cs.count());
            for (std::size_t k = 0; k < cs.count(); ++k) bySerial.at(cs.id[k]) = cs.position[k];
            std::vector<float> d;
            for (std::size_t k = 0; k < gs.count(); ++k) d.push_back(glm::distance(gs.position[k], bySerial.at(gs.id[k])));
            std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
            if (!d.empty()) median = std::max(median, d[d.size() / 2]);
        }
        const std::vector<BodySnapshot> cb = readBodies(onCpu), gb = readBodies(onDevice);
        ASSERT_EQ(cb.size(), gb.size());
        for (std::size_t b = 0; b < cb.size(); ++b) {
            const float d = glm::distance(cb[b].position, gb[b].position);
            if (d > apart) {
                apart = d;
                farthest = cb[b].name;
            }
        }
    }
    std::printf("the showcase's first 1.5 s, fluid on the CPU / device: %u particles on both, bodies at most %.6f m "
                "apart (%s), the median particle in the first second at most %.5f m\n",
                particles, apart, farthest.empty() ? "none" : farthest.c_str(), median);
    EXPECT_GT(particles, 500u);
    EXPECT_LT(apart, 0.001f);
    EXPECT_LT(median, 0.0075f);
    destroyWorld(onCpu);
    destroyWorld(onDevice);
}

/// The static body of a tank's floor and walls (thick boxes) around [0, w]
/// x [0, h] (m).
BodyDef tankOfBodies(float w, float h) {
    BodyDef tank;
    tank.type = BodyType::Static;
    tank.shapes = {boxShape(glm::vec2(0.5f * w + 0.1f, 0.05f), glm::vec2(0.5f * w, -0.05f)),
                   boxShape(glm::vec2(0.05f, 0.5f * h + 0.1f), glm::vec2(-0.05f, 0.5f * h)),
                   boxShape(glm::vec2(0.05f, 0.5f * h + 0.1f), glm::vec2(w + 0.05f, 0.5f * h))};
    return tank;
}

TEST_F(DeviceFluidTest, AStaticTankOfBodiesHoldsADamBreakAsTheCpus) {
    // The usual Box2D level: the tank is a static body (floor and walls as
    // boxes), no world collider. A 0.3 x 0.4 m column at 2 cm (300
    // particles) breaks in a 1 x 0.6 m tank of bodies, 1 s, on the CPU and on
    // the device (backend gpu: the device meets the static body itself).
    // Tolerances:
    // - the device fluid stays on the device, with the same particle count;
    // - the front (the largest x) within half a spacing of the CPU's at every
    //   step of the first 0.5 s (the same flow; rounding changes which
    //   particle leads), as the dam breaks against world colliders;
    // - the body contacts over the run within 2 % of the CPU's (the same
    //   shapes, cells and tests; a threshold that rounding tips is rare);
    // - no particle through the walls (every one inside the tank, up to a
    //   particle radius, at every sampled step) on the device;
    // - a step reads back the report (336 bytes), the bodies' report (16)
    //   and their impacts (32 bytes each; the front strikes the far wall at
    //   about 2.5 m/s): at most 400 bytes a substep here, where one read of
    //   the particles is 10.8 KB; and uploads exactly the shapes at both
    //   poses, their cells and the body (2 x 304 + 16 bytes a shape, 48 a
    //   body) a substep: no particle.
    constexpr float kSpacing = 0.02f;
    OwnedWorld cpu(Backend::Cpu), vulkan(Backend::Vulkan);
    FluidDef def = waterDef(2, kSpacing, glm::vec3(0.3f, 0.4f, 0.0f));
    for (WorldId w : {cpu.id, vulkan.id}) {
        createBody(w, tankOfBodies(1.0f, 0.6f));
        def.backend = w.index == vulkan.id.index ? FluidBackend::Gpu : FluidBackend::Cpu;
        createFluid(w, def);
    }
    float frontGap = 0.0f, outside = 0.0f;
    std::uint64_t cpuContacts = 0, deviceContacts = 0, substeps = 0, strikes = 0;
    TransferStats before{};
    for (int i = 0; i < 60; ++i) {
        if (i == 1) before = transferStats(vulkan.id);
        const StepStats c = stepWorld(cpu.id, kDt), g = stepWorld(vulkan.id, kDt);
        ASSERT_TRUE(g.fluids.at(0).device) << "step " << i;
        ASSERT_EQ(g.fluids.at(0).particles, c.fluids.at(0).particles);
        cpuContacts += c.fluids.at(0).bodyContacts;
        deviceContacts += g.fluids.at(0).bodyContacts;
        if (i >= 1) substeps += g.fluids.at(0).substeps;
        strikes += takeEvents(vulkan.id).events.size();
        if (i < 30 || i % 10 == 9) {
            const TransferStats pause = transferStats(vulkan.id);  // the reads below are not the step's
            const FluidSnapshot cs = readFluid(cpu.id, FluidId{1}), gs = readFluid(vulkan.id, FluidId{1});
            if (i < 30) frontGap = std::max(frontGap, std::abs(front(gs.position) - front(cs.position)));
            for (const glm::vec3& x : gs.position) {
                outside = std::max({outside, -x.x, x.x - 1.0f, -x.y});
            }
            const TransferStats resumed = transferStats(vulkan.id);
            before.bytesDownloaded += resumed.bytesDownloaded - pause.bytesDownloaded;
            before.bytesUploaded += resumed.bytesUploaded - pause.bytesUploaded;
        }
    }
    takeEvents(cpu.id);
    const TransferStats after = transferStats(vulkan.id);
    const std::uint64_t down = after.bytesDownloaded - before.bytesDownloaded;
    const std::uint64_t up = after.bytesUploaded - before.bytesUploaded;
    std::printf("a dam break in a static tank of bodies, CPU / device: front apart by at most %.5f m, body contacts "
                "%llu / %llu, farthest outside the tank %.5f m; %llu strikes; over %llu substeps %llu bytes down, "
                "%llu up\n",
                frontGap, static_cast<unsigned long long>(cpuContacts), static_cast<unsigned long long>(deviceContacts),
                outside, static_cast<unsigned long long>(strikes), static_cast<unsigned long long>(substeps),
                static_cast<unsigned long long>(down), static_cast<unsigned long long>(up));
    EXPECT_LT(frontGap, 0.5f * kSpacing);
    EXPECT_GT(cpuContacts, 0u);
    EXPECT_NEAR(static_cast<double>(deviceContacts), static_cast<double>(cpuContacts), 0.02 * cpuContacts);
    EXPECT_LT(outside, 0.5f * kSpacing);
    EXPECT_LE(down, 400u * substeps);
    EXPECT_EQ(up, (3u * (2u * 304u + 16u) + 48u) * substeps);
}

TEST_F(DeviceFluidTest, AKinematicPaddleStrikesTheWaterAsTheCpus) {
    // A kinematic paddle (0.04 x 0.2 m) sweeps at 1 m/s along a resting tank
    // (1 x 0.5 m box of world colliders, 0.2 m of water at 2 cm: 500
    // particles), 0.5 s, on the CPU and on the device. Its strikes (a
    // particle reaching it faster than kFluidImpactSpeed) are collision
    // events naming the paddle. Tolerances:
    // - in the first step of contact the same particles strike on both (the
    //   same serials: the same positions up to rounding, against a paddle
    //   whose pose the host computes for both);
    // - the strikes over the run within 5 % of the CPU's, and the water's
    //   horizontal momentum at the end within 5 % (the paddle pushes the
    //   same water; rounding parts single particles near the threshold);
    // - the fluid stays on the device, with the same count.
    constexpr float kSpacing = 0.02f;
    OwnedWorld cpu(Backend::Cpu), vulkan(Backend::Vulkan);
    FluidDef def = waterDef(2, kSpacing, glm::vec3(1.0f, 0.2f, 0.0f));
    BodyDef paddle;
    paddle.type = BodyType::Kinematic;
    paddle.position = glm::vec2(0.1f, 0.25f);
    paddle.linearVelocity = glm::vec2(1.0f, 0.0f);
    paddle.shapes = {boxShape(glm::vec2(0.02f, 0.1f))};
    for (WorldId w : {cpu.id, vulkan.id}) {
        test::closedBox(w, glm::vec3(0.0f), glm::vec3(1.0f, 0.5f, 0.0f), 2);
        def.backend = w.index == vulkan.id.index ? FluidBackend::Gpu : FluidBackend::Cpu;
        createFluid(w, def);
        createBody(w, paddle);
    }
    std::uint64_t cpuStrikes = 0, deviceStrikes = 0;
    bool firstCompared = false, firstSame = false;
    for (int i = 0; i < 30; ++i) {
        const StepStats c = stepWorld(cpu.id, kDt), g = stepWorld(vulkan.id, kDt);
        ASSERT_TRUE(g.fluids.at(0).device) << "step " << i;
        ASSERT_EQ(g.fluids.at(0).particles, c.fluids.at(0).particles);
        std::vector<std::uint32_t> cs, gs;
        for (const ParticleEvent& e : takeEvents(cpu.id).events) {
            if (e.fluid.index == 1 && e.body.index == 1) cs.push_back(e.birth);
        }
        for (const ParticleEvent& e : takeEvents(vulkan.id).events) {
            if (e.fluid.index == 1 && e.body.index == 1) gs.push_back(e.birth);
        }
        if (!firstCompared && !cs.empty()) {
            firstCompared = true;
            std::sort(cs.begin(), cs.end());
            std::sort(gs.begin(), gs.end());
            firstSame = cs == gs;
        }
        cpuStrikes += cs.size();
        deviceStrikes += gs.size();
    }
    float cpuMomentum = 0.0f, deviceMomentum = 0.0f;
    for (const glm::vec3& v : readFluid(cpu.id, FluidId{1}).velocity) cpuMomentum += v.x;
    for (const glm::vec3& v : readFluid(vulkan.id, FluidId{1}).velocity) deviceMomentum += v.x;
    std::printf("a kinematic paddle, CPU / device: strikes %llu / %llu (the first step's the same particles: %s), "
                "horizontal momentum %.4f / %.4f (particle m/s)\n",
                static_cast<unsigned long long>(cpuStrikes), static_cast<unsigned long long>(deviceStrikes),
                firstSame ? "yes" : "NO", cpuMomentum, deviceMomentum);
    EXPECT_TRUE(firstCompared);
    EXPECT_TRUE(firstSame);
    EXPECT_GT(cpuStrikes, 0u);
    EXPECT_NEAR(static_cast<double>(deviceStrikes), static_cast<double>(cpuStrikes), 0.05 * cpuStrikes);
    EXPECT_GT(cpuMomentum, 0.0f);
    EXPECT_NEAR(deviceMomentum, cpuMomentum, 0.05f * cpuMomentum);
}

TEST_F(DeviceFluidTest, TheBackendIsChosenAsDocumented) {
    FluidDef def = waterDef(2, 0.05f, glm::vec3(0.5f, 0.25f, 0.0f));
    // Auto: the device only in a Vulkan world on a hardware GPU.
    {
        OwnedWorld w(Backend::Vulkan);
        createFluid(w.id, def);
        EXPECT_EQ(stepWorld(w.id, kDt).fluids.at(0).device, gpu::hardwareGpuAvailable());
    }
    {
        OwnedWorld w(Backend::Cpu);
        createFluid(w.id, def);
        EXPECT_FALSE(stepWorld(w.id, kDt).fluids.at(0).device);
    }
    // Gpu needs a Vulkan world, and says so when it gets none.
    def.backend = FluidBackend::Gpu;
    {
        OwnedWorld w(Backend::Cpu);
        try {
            createFluid(w.id, def);
            ADD_FAILURE() << "a gpu fluid was made in a CPU world";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("backend gpu needs a Vulkan world"), std::string::npos) << e.what();
        }
    }
    // A gpu fluid with a body near it stays on the device and meets it.
    {
        OwnedWorld w(Backend::Vulkan);
        createFluid(w.id, def);
        BodyDef slab;
        slab.type = BodyType::Dynamic;
        slab.position = glm::vec2(0.25f, 0.3f);
        slab.shapes = {boxShape(glm::vec2(0.1f, 0.02f))};
        createBody(w.id, slab);
        const FluidStepStats s = stepWorld(w.id, kDt).fluids.at(0);
        EXPECT_TRUE(s.device);
        EXPECT_GT(s.bodyContacts, 0u);
    }
}

}  // namespace
}  // namespace spindrift
