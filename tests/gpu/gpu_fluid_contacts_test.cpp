// The fluid's contacts with static colliders and its integration on the
// device (src/gpu/gpu_fluid_contacts.h, gpu_fluid_integrate.h) against the
// CPU's findContacts, solveContacts and integratePositions
// (src/fluid/collide.cpp): a dam break in a closed box of
// planes with a sphere, a turned box and (2D) a polygon inside it.
//
// Why equality: both evaluate the same kernel functions (fluid.glsl's
// surfaces, wall table and contact velocity) on the same numbers, in the
// same order of surfaces, with `precise` arithmetic on the device, so on a
// device that rounds to nearest (lavapipe) the contact sets, the colliders'
// share of the density and the solved velocities are the same bits; the
// solve test (gpu_fluid_solve_test.cpp) says why the sweeps are.
#include "gpu_fluid_test_util.h"
#include "gpu_test_util.h"

#include <spindrift/fluid.h>

#include <cstdint>
#include <string>

namespace spindrift {
namespace {

using test::kFluidDt;

/// The fluid colliders of a 3 x 2 (x 0.6) m box with a sphere and a box turned
/// by 30 degrees inside, both where the particles already are (so paths start
/// inside them), as the world passes them to the fluid.
std::vector<kernels::ColliderParams> boxWithObstacles(int dimension) {
    std::vector<ColliderDef> defs;
    const glm::vec3 hi(3.0f, 2.0f, 0.6f);
    defs.push_back(test::wall(glm::vec3(0.0f), {1, 0, 0}));
    defs.push_back(test::wall(hi, {-1, 0, 0}));
    defs.push_back(test::wall(glm::vec3(0.0f), {0, 1, 0}));
    defs.push_back(test::wall(hi, {0, -1, 0}));
    if (dimension == 3) {
        defs.push_back(test::wall(glm::vec3(0.0f), {0, 0, 1}));
        defs.push_back(test::wall(hi, {0, 0, -1}));
    }
    ColliderDef sphere;
    sphere.kind = ColliderKind::Sphere;
    // Inside the water (2D: in the plane z = 0).
    sphere.position = dimension == 2 ? glm::vec3(0.5f, 0.35f, 0.0f) : glm::vec3(0.2f, 0.15f, 0.2f);
    sphere.radius = 0.12f;
    defs.push_back(sphere);
    ColliderDef box;
    box.kind = ColliderKind::Box;
    box.position = dimension == 2 ? glm::vec3(0.25f, 0.6f, 0.0f) : glm::vec3(0.3f, 0.3f, 0.2f);
    box.halfExtents = {0.1f, 0.06f, 0.1f};
    box.rotationDegrees = {0.0f, 0.0f, 30.0f};
    defs.push_back(box);
    std::vector<kernels::ColliderParams> params;
    for (const ColliderDef& d : defs) params.push_back(makeColliderParams(d, 0));
    return params;
}

/// Particles at every stage of sleep: still for 0 to 0.6 of sleepTime's
/// 0.5 s (some asleep already), anchored 0 to 1.5 of the sleep circle's
/// radius away (some outside it).
template <int D>
void withSleep(test::FluidParticles<D>& p, const FluidDef& def) {
    const float drift = kernels::fluidSleepDrift(def.sleepSpeed, def.sleepTime, def.spacing);
    for (std::size_t i = 0; i < p.x.size(); ++i) {
        fluid::Vec<D> offset(0.0f);
        offset[0] = drift * 0.5f * static_cast<float>(i % 4);
        p.anchor.push_back(p.x[i] + offset);
        p.still.push_back(def.sleepTime * 0.3f * static_cast<float>(i % 5));
    }
}

class GpuFluidContactsTest : public test::GpuSuiteWith<test::FluidParts, &test::createFluidParts> {
protected:
    template <int D>
    static void expectSameContacts(FluidDef def, const test::FluidParticles<D>& in, const std::string& what) {
        Shared& s = shared();
        test::FluidParts& parts = *s.part;
        const std::vector<kernels::ColliderParams> colliders = boxWithObstacles(D);
        test::CpuSetup<D> c;
        test::runCpuSetup<D>(c, def, in, colliders);
        const fluid::Particles<D>& p = c.f.template particles<D>();
        const std::size_t n = p.size();

        // The device: gather, find (into the wall buffer), constraints.
        test::DeviceFluid<D> device(*s.device, c, in);
        std::vector<glm::vec2> table(fluid::WallTable::kSize);
        for (int e = 0; e < fluid::WallTable::kSize; ++e) {
            table[e] = glm::vec2(c.f.wallTable.density[e], c.f.wallTable.push[e]);
        }
        gpu::setFluidSurfaces(*parts.contacts,
                              {colliders, c.f.polygons, table, c.f.wallTable.start, c.f.wallTable.step});
        const gpu::FluidContactParams contactParams{c.f.radius, def.spacing, kFluidDt, def.friction, def.splitImpulse};
        gpu::submitOnce(*s.device, [&](VkCommandBuffer cmd) {
            gpu::recordFluidGrid(cmd, *parts.grid, device.x, device.n, device.gridParams);
            gpu::recordFluidGather(cmd, *parts.setup, *parts.grid,
                                   {&device.x, &device.v, &device.p, &device.wall, device.n}, device.setupParams);
            gpu::recordFluidContactsFind(cmd, *parts.contacts, *parts.setup, device.wall, contactParams);
            gpu::recordFluidConstraints(cmd, *parts.setup, *parts.grid, device.setupParams);
        });
        const std::vector<glm::vec4> wall = gpu::downloadArray<glm::vec4>(*s.device, device.wall, n);
        const std::vector<std::uint32_t> masks = gpu::downloadArray<std::uint32_t>(*s.device, parts.contacts->masks, n);

        // The contact sets and the colliders' share, particle by particle.
        std::vector<std::uint32_t> cpuMasks(n, 0u);
        std::size_t contacts = 0;
        for (const std::vector<fluid::Contact>& chunk : c.f.contacts) {
            for (const fluid::Contact& contact : chunk) {
                // The surface's index: the first whose surface at the particle is this one.
                glm::vec3 x(0.0f);
                for (int a = 0; a < D; ++a) x[a] = p.position[contact.particle][a];
                for (std::uint32_t k = 0; k < colliders.size() + c.f.polygons.size(); ++k) {
                    kernels::FluidSurface surface =
                        k < colliders.size() ? kernels::fluidColliderSurface(colliders[k], x)
                                             : kernels::fluidPolygonSurface(c.f.polygons[k - colliders.size()], x);
                    if (D == 2 && k < colliders.size()) surface = kernels::fluidFlatSurface(surface);
                    if (surface.distance == contact.surface.distance && surface.normal == contact.surface.normal &&
                        !(cpuMasks[contact.particle] & (1u << k))) {
                        cpuMasks[contact.particle] |= 1u << k;
                        break;
                    }
                }
                ++contacts;
            }
        }
        ASSERT_GT(contacts, 100u) << what << ": a test of contacts needs contacts";
        std::size_t maskDiffs = 0, wallDiffs = 0;
        for (std::size_t i = 0; i < n; ++i) {
            maskDiffs += masks[i] != cpuMasks[i];
            wallDiffs += wall[i] != c.wall[i];
        }
        EXPECT_EQ(maskDiffs, 0u) << what;
        EXPECT_EQ(wallDiffs, 0u) << what;

        // The solve with the contacts between its sweeps, from the CPU's setup.
        test::uploadCpuSetup<D>(*s.device, c, *parts.setup, &device.wall);
        gpu::FluidSolveParams params{def.iterations, def.splitImpulse, c.f.constraints.warmFraction, c.f.restDensity,
                                     def.baumgarte, c.f.h, kFluidDt};
        gpu::submitOnce(*s.device, [&](VkCommandBuffer cmd) {
            gpu::recordFluidSolve(cmd, *parts.solve, *parts.grid, *parts.setup, device.wall, params, parts.contacts.get());
        });
        const gpu::FluidSolveReadback r = gpu::readFluidSolve(*parts.solve, *parts.setup);
        WorkerPool pool(2);
        fluid::solveConstraints<D>(pool, c.f, kFluidDt);
        std::size_t velocityDiffs = 0, pseudoDiffs = 0;
        for (std::size_t i = 0; i < n; ++i) {
            for (int a = 0; a < D; ++a) {
                velocityDiffs += r.velocity[D * i + a] != p.velocity[i][a];
                pseudoDiffs += r.motion[2 * D * i + D + a] != p.motion[i].pseudo[a];
            }
        }
        EXPECT_EQ(velocityDiffs, 0u) << what;
        EXPECT_EQ(pseudoDiffs, 0u) << what;

        // The integration: sleep, moves, path tests, statistics.
        const gpu::FluidIntegrateParams integrateParams{def.gravity, kFluidDt, def.sleepSpeed, def.sleepTime, def.spacing,
                                                        def.splitImpulse};
        gpu::submitOnce(*s.device, [&](VkCommandBuffer cmd) {
            gpu::recordFluidIntegrate(cmd, *parts.integrate, *parts.grid, *parts.setup, *parts.solve, *parts.contacts,
                                      {&device.anchor, &device.still}, integrateParams);
        });
        const gpu::FluidSetupReadback moved = gpu::readFluidSetup(*parts.setup);
        const gpu::FluidIntegrateReadback ir = gpu::readFluidIntegrate(*parts.setup, *parts.integrate);
        EventQueue events;
        test::NoBodies bodies;
        const fluid::StepContext context{pool, colliders, 0.0, 0, events, bodies};
        FluidStepStats stats;
        fluid::integratePositions<D>(pool, c.f, context, kFluidDt, stats);
        ASSERT_EQ(p.size(), n) << what << ": a particle removed (its numbers not finite)";
        std::size_t positionDiffs = 0, movedVelocityDiffs = 0, sleepDiffs = 0, asleep = 0;
        for (std::size_t i = 0; i < n; ++i) {
            for (int a = 0; a < D; ++a) {
                positionDiffs += moved.x[D * i + a] != p.position[i][a];
                movedVelocityDiffs += moved.v[D * i + a] != p.velocity[i][a];
                sleepDiffs += ir.anchors[D * i + a] != p.anchor[i][a];
            }
            sleepDiffs += ir.stills[i] != p.still[i];
            // Asleep now, or woken by the solve this substep.
            asleep += p.still[i] >= def.sleepTime || (in.still[p.id[i]] >= def.sleepTime && p.still[i] == 0.0f);
        }
        {
            // Particles the path tests put back: on a collider's skin.
            std::size_t onSkin = 0;
            for (std::size_t i = 0; i < n; ++i) {
                glm::vec3 x(0.0f);
                for (int a = 0; a < D; ++a) x[a] = p.position[i][a];
                for (const kernels::ColliderParams& col : colliders) {
                    const float dist = kernels::fluidColliderSurface(col, x).distance;
                    onSkin += dist >= 0.0f && dist < 2e-5f;
                }
            }
            EXPECT_GT(onSkin, 20u) << what << ": the path tests should put particles back";
        }
        EXPECT_EQ(positionDiffs, 0u) << what;
        EXPECT_EQ(movedVelocityDiffs, 0u) << what;
        EXPECT_EQ(sleepDiffs, 0u) << what;
        EXPECT_GT(asleep, 0u) << what << ": the test should put particles to sleep or wake them";
        EXPECT_EQ(ir.maxSpeed, stats.maxSpeed) << what;
        EXPECT_EQ(ir.pressedDepth, c.f.pressedDepth) << what;
        EXPECT_EQ(ir.nonFinite, 0u) << what;
    }
};

TEST_F(GpuFluidContactsTest, DamBreak2DWithObstaclesMatchesTheCpuBitForBit) {
    FluidDef def = test::damBreakDef(2, 0.02f, {1.0f, 1.2f, 0.0f});
    def.friction = 0.3f;
    def.polygons.push_back({{{1.7f, 0.0f}, {2.0f, 0.0f}, {1.85f, 0.25f}}});
    test::FluidParticles<2> p = test::damBreakParticles<2>(test::damBreakDef(2, 0.02f, {1.0f, 1.2f, 0.0f}),
                                                           {3.0f, 2.0f, 0.0f}, 30);
    withSleep<2>(p, def);
    expectSameContacts<2>(def, p, "2D dam break, split impulses");
    def.splitImpulse = false;
    expectSameContacts<2>(def, p, "2D dam break, the slides' contact");
}

TEST_F(GpuFluidContactsTest, DamBreak3DWithObstaclesMatchesTheCpuBitForBit) {
    FluidDef def = test::damBreakDef(3, 0.04f, {0.4f, 0.5f, 0.4f});
    def.friction = 0.3f;
    test::FluidParticles<3> p = test::damBreakParticles<3>(def, {1.2f, 0.8f, 0.6f}, 20);
    withSleep<3>(p, def);
    expectSameContacts<3>(def, p, "3D dam break");
}

}  // namespace
}  // namespace spindrift
