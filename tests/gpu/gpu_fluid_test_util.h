// What the device fluid's tests share (gpu_fluid_setup_test.cpp,
// gpu_fluid_solve_test.cpp): one device's passes, a fluid's state run through
// the CPU's grid and setup, and the same state uploaded for the device.
#pragma once

#include "fluid/body_link.h"
#include "fluid/fluid_state.h"
#include "fluid/fluid_test_util.h"
#include "gpu/gpu_fluid_contacts.h"
#include "gpu/gpu_fluid_grid.h"
#include "gpu/gpu_fluid_integrate.h"
#include "gpu/gpu_fluid_setup.h"
#include "gpu/gpu_fluid_solve.h"
#include "gpu/vulkan_buffer.h"
#include "particles/event_queue.h"
#include "particles/params.h"

#include <spindrift/fluid.h>
#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

namespace spindrift::test {

inline constexpr float kFluidDt = 1.0f / 60.0f;

/// One device's fluid passes.
struct FluidParts {
    std::unique_ptr<gpu::GpuFluidGrid> grid;
    std::unique_ptr<gpu::GpuFluidSetup> setup;
    std::unique_ptr<gpu::GpuFluidSolve> solve;
    std::unique_ptr<gpu::GpuFluidContacts> contacts;
    std::unique_ptr<gpu::GpuFluidIntegrate> integrate;
};
inline std::unique_ptr<FluidParts> createFluidParts(gpu::Device& d) {
    auto parts = std::make_unique<FluidParts>();
    parts->contacts = gpu::createGpuFluidContacts(d);
    parts->integrate = gpu::createGpuFluidIntegrate(d);
    parts->grid = gpu::createGpuFluidGrid(d);
    parts->setup = gpu::createGpuFluidSetup(d);
    parts->solve = gpu::createGpuFluidSolve(d);
    return parts;
}

/// A fluid's particles in particle order, as a setup takes them.
template <int D>
struct FluidParticles {
    std::vector<fluid::Vec<D>> x, v;
    std::vector<float> pressure;  // m/s
    /// Sleep (integratePositions): the anchor (m) and time still (s); empty:
    /// each particle's own position and 0.
    std::vector<fluid::Vec<D>> anchor;
    std::vector<float> still;
};

/// A colliders' share for every particle in grid order: not the contacts'
/// (they are a later slice), but values of their size, different per
/// particle, so that the setup's and the solve's use of them is compared too.
inline glm::vec4 syntheticWall(std::size_t i, int dimension) {
    if (i % 3 != 0) return glm::vec4(0.0f);
    return {0.4f * static_cast<float>(i % 7) / 7.0f, 0.3f * static_cast<float>(i % 5) / 5.0f - 0.1f,
            0.25f * static_cast<float>(i % 4) / 4.0f, dimension == 3 ? 0.2f * static_cast<float>(i % 3) / 3.0f : 0.0f};
}

/// The CPU's setup of some particles: the state after its grid and
/// setupConstraints, with the colliders' share (`wall`, grid order) an input.
template <int D>
struct CpuSetup {
    fluid::FluidState f;
    FluidStepStats stats;
    std::vector<glm::vec4> wall;  // density, g sum (grid order)
};

/// A step's view of a world with colliders and no bodies (findContacts reads
/// only the colliders).
class NoBodies final : public fluid::BodyLink {
public:
    fluid::JetMount jetMount(BodyId) override { return {}; }
    void applyRecoil(BodyId, const fluid::JetMount&) override {}
    fluid::FluidBodyStep* gather(const fluid::FluidState&, float) override { return nullptr; }
    void exchange(const fluid::FluidBodyStep&) override {}
};

/// The CPU's setup of `in`, the colliders' share from `colliders` (fluid
/// kinds only, in order) and the fluid's polygons (findContacts), or, when
/// there are none, synthetic (syntheticWall).
template <int D>
void runCpuSetup(CpuSetup<D>& c, const FluidDef& def, const FluidParticles<D>& in,
                 std::span<const kernels::ColliderParams> colliders = {}) {
    c.f.def = def;
    fluid::initialiseFluid(c.f);
    fluid::Particles<D>& p = c.f.template particles<D>();
    for (std::size_t i = 0; i < in.x.size(); ++i) {
        p.push(in.x[i], in.v[i], static_cast<std::uint32_t>(i));
        p.pressure[i] = in.pressure[i];
        if (!in.anchor.empty()) p.anchor[i] = in.anchor[i];
        if (!in.still.empty()) p.still[i] = in.still[i];
    }
    // The step's external force, as stepPasses applies it before the grid.
    const fluid::Vec<D> dv = fluid::Vec<D>(glm::vec3(def.gravity) * kFluidDt);
    for (fluid::Vec<D>& v : p.velocity) v += dv;
    WorkerPool pool(2);
    fluid::buildGrid<D>(pool, c.f);
    const std::size_t n = p.size();
    c.wall.resize(n);
    if (colliders.empty() && c.f.polygons.empty()) {
        c.f.constraints.wallDensity.resize(n);
        c.f.constraints.wallGradient.resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            c.wall[i] = syntheticWall(i, D);
            c.f.constraints.wallDensity[i] = c.wall[i].x;
            c.f.constraints.wallGradient[i] = glm::vec3(c.wall[i].y, c.wall[i].z, c.wall[i].w);
        }
    } else {
        EventQueue events;
        NoBodies bodies;
        const fluid::StepContext context{pool, colliders, 0.0, 0, events, bodies};
        fluid::findContacts<D>(pool, c.f, context, kFluidDt);
        for (std::size_t i = 0; i < n; ++i) {
            c.wall[i] = glm::vec4(c.f.constraints.wallDensity[i], c.f.constraints.wallGradient[i]);
        }
    }
    c.f.lastSubstep = 2.0f * kFluidDt;  // a warm start scaled by a half, as after a change of substeps
    fluid::setupConstraints<D>(pool, c.f, kFluidDt, /*countClosing=*/true, c.stats);
}

/// The particles of a CPU setup on the device: the inputs (particle order,
/// the wall in grid order) uploaded, and the grid and setup recorded in the
/// CPU grid's place.
template <int D>
struct DeviceFluid {
    gpu::Device& d;
    std::uint32_t n;
    gpu::FluidGridParams gridParams;
    gpu::FluidSetupParams setupParams;
    std::vector<fluid::Vec<D>> anchors;
    std::vector<float> stills;
    gpu::Buffer x, v, p, wall;
    gpu::Buffer anchor, still;  // particle order

    DeviceFluid(gpu::Device& device, CpuSetup<D>& c, const FluidParticles<D>& in)
        : d(device), n(static_cast<std::uint32_t>(in.x.size())) {
        const fluid::Grid<D>& g = c.f.template grid<D>();
        gridParams.dimension = D;
        for (int a = 0; a < D; ++a) gridParams.origin[a] = g.origin[a];
        gridParams.invH = 1.0f / g.h;
        gridParams.cells = glm::ivec3(g.cells[0], g.cells[1], g.cells[2]);
        setupParams.readLimit = c.f.subCellReadLimit;
        setupParams.cap = c.f.maxNeighbours;
        setupParams.h = c.f.h;
        setupParams.restDensity = c.f.restDensity;
        setupParams.baumgarte = c.f.def.baumgarte;
        setupParams.relaxation = c.f.def.relaxation;
        setupParams.dt = kFluidDt;
        setupParams.warmFraction = c.f.constraints.warmFraction;
        setupParams.warmCap = fluid::warmStartOf(c.f, kFluidDt).cap;
        setupParams.velocityChange = glm::vec3(glm::vec3(c.f.def.gravity) * kFluidDt);
        if (D == 2) setupParams.velocityChange.z = 0.0f;
        static_assert(sizeof(fluid::Vec<D>) == D * sizeof(float));  // tightly packed, as the device reads them
        const auto bytes = [](std::size_t b) { return std::max<VkDeviceSize>(b, 16u); };
        x = gpu::createStorageBuffer(d, bytes(n * sizeof(fluid::Vec<D>)));
        v = gpu::createStorageBuffer(d, bytes(n * sizeof(fluid::Vec<D>)));
        p = gpu::createStorageBuffer(d, bytes(n * sizeof(float)));
        wall = gpu::createStorageBuffer(d, bytes(n * sizeof(glm::vec4)));
        anchor = gpu::createStorageBuffer(d, bytes(n * sizeof(fluid::Vec<D>)));
        still = gpu::createStorageBuffer(d, bytes(n * sizeof(float)));
        anchors = in.anchor.empty() ? in.x : in.anchor;
        stills = in.still.empty() ? std::vector<float>(n, 0.0f) : in.still;
        if (n > 0) {
            std::vector<gpu::Transfer> up{
                {&x, const_cast<fluid::Vec<D>*>(in.x.data()), n * sizeof(fluid::Vec<D>)},
                {&v, const_cast<fluid::Vec<D>*>(in.v.data()), n * sizeof(fluid::Vec<D>)},
                {&p, const_cast<float*>(in.pressure.data()), n * sizeof(float)},
                {&wall, c.wall.data(), n * sizeof(glm::vec4)},
                {&anchor, anchors.data(), n * sizeof(fluid::Vec<D>)},
                {&still, stills.data(), n * sizeof(float)}};
            gpu::upload(d, up);
        }
    }
    DeviceFluid(const DeviceFluid&) = delete;
    DeviceFluid& operator=(const DeviceFluid&) = delete;
    ~DeviceFluid() {
        for (gpu::Buffer* b : {&x, &v, &p, &wall, &anchor, &still}) gpu::destroyBuffer(d, *b);
    }

    void recordSetup(VkCommandBuffer cmd, FluidParts& parts) {
        gpu::recordFluidGrid(cmd, *parts.grid, x, n, gridParams);
        gpu::recordFluidSetup(cmd, *parts.setup, *parts.grid, {&x, &v, &p, &wall, n}, setupParams);
    }
};

/// The CPU's setup of `c` copied over the device setup's results (and, given
/// `wall`, the colliders' share over it), so that a device solve starts from
/// the CPU's bits.
template <int D>
void uploadCpuSetup(gpu::Device& d, CpuSetup<D>& c, gpu::GpuFluidSetup& setup, gpu::Buffer* wall = nullptr) {
    const fluid::Particles<D>& p = c.f.template particles<D>();
    const fluid::Constraints& k = c.f.constraints;
    const std::size_t n = p.size();
    std::vector<std::uint32_t> first(n), counts(n), listIndex;
    std::vector<float> velocity(n * D), pressure(p.pressure);
    std::vector<glm::vec4> constraints(n), warm(n);
    for (std::size_t i = 0; i < n; ++i) {
        first[i] = static_cast<std::uint32_t>(listIndex.size());
        counts[i] = k.count[i];
        const fluid::Neighbour<D>* list = fluid::neighbourList<D>(c.f.template neighbours<D>(), k, i);
        for (std::uint32_t e = 0; e < k.count[i]; ++e) {
            listIndex.push_back(list[e].index);
        }
        constraints[i] = glm::vec4(k.bias[i], k.invMass[i], p.density[i], 0.0f);
        warm[i] = glm::vec4(k.warmVelocity[i], 0.0f);
        for (int a = 0; a < D; ++a) velocity[D * i + a] = p.velocity[i][a];
    }
    ASSERT_LE(listIndex.size(), setup.listCapacity);
    std::uint32_t header[4] = {static_cast<std::uint32_t>(listIndex.size()),
                               static_cast<std::uint32_t>(c.stats.neighbourOverflows), 0u, 0u};
    std::vector<gpu::Transfer> up{{&setup.header, header, sizeof header}};
    if (wall != nullptr && n > 0) up.push_back({wall, c.wall.data(), n * sizeof(glm::vec4)});
    const auto add = [&](gpu::Buffer& b, auto& values) {
        if (!values.empty()) up.push_back({&b, values.data(), values.size() * sizeof(values[0])});
    };
    add(setup.first, first);
    add(setup.counts, counts);
    add(setup.listIndex, listIndex);
    add(setup.constraints, constraints);
    add(setup.warm, warm);
    add(setup.v, velocity);
    add(setup.p, pressure);
    gpu::upload(d, up);
}

/// A dam break's particles after `steps` steps: moving, disordered, under
/// pressure, with the pressures the CPU solver left (the warm start's input).
template <int D>
FluidParticles<D> damBreakParticles(const FluidDef& def, glm::vec3 box, int steps) {
    FluidWorld world;
    closedBox(world.id, glm::vec3(0.0f), box, D);
    const FluidId id = createFluid(world.id, def);
    for (int i = 0; i < steps; ++i) {
        stepWorld(world.id, kFluidDt);
    }
    const FluidSnapshot s = readFluid(world.id, id);
    FluidParticles<D> p;
    for (std::size_t i = 0; i < s.count(); ++i) {
        p.x.push_back(fluid::Vec<D>(s.position[i]));
        p.v.push_back(fluid::Vec<D>(s.velocity[i]));
        p.pressure.push_back(s.pressure[i]);
    }
    return p;
}

/// A column of water in a box's corner, at `spacing` (m).
inline FluidDef damBreakDef(int dimension, float spacing, glm::vec3 column) {
    FluidDef def;
    def.name = "water";
    def.dimension = static_cast<std::uint32_t>(dimension);
    def.spacing = spacing;
    def.blocks.push_back({glm::vec3(0.0f), column, glm::vec3(0.0f)});
    return def;
}

}  // namespace spindrift::test
