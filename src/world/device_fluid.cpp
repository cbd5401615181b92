// The device fluid's step driver (device_fluid.h): particle buffers kept on
// the device, the substeps recorded from the passes of src/gpu, and the few
// numbers read back that the host's substep rule and grid placement need.
#include "world/device_fluid.h"

#include "fluid/body_contacts.h"
#include "fluid/fluid_state.h"
#include "gpu/gpu_fluid_carry.h"
#include "gpu/gpu_fluid_contacts.h"
#include "gpu/gpu_fluid_grid.h"
#include "gpu/gpu_fluid_integrate.h"
#include "gpu/gpu_fluid_setup.h"
#include "gpu/gpu_fluid_solve.h"
#include "gpu/vulkan_buffer.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/layout.glsl"

#include <spindrift/errors.h>
#include <spindrift/world.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

namespace spindrift {

struct DeviceFluid {
    gpu::Device* device = nullptr;
    std::unique_ptr<gpu::GpuFluidGrid> grid;
    std::unique_ptr<gpu::GpuFluidSetup> setup;
    std::unique_ptr<gpu::GpuFluidSolve> solve;
    std::unique_ptr<gpu::GpuFluidContacts> contacts;
    std::unique_ptr<gpu::GpuFluidIntegrate> integrate;
    std::unique_ptr<gpu::GpuFluidCarry> carry;
    // The particles in particle order (the last grid order), tightly packed
    // as the CPU's arrays: positions and anchors dimension floats each,
    // velocities too, pressures, times still and serials one each.
    gpu::Buffer x, v, p, anchors, stills, ids;
    gpu::Buffer wall;  // the contacts' find writes it, the setup reads it (grid order)
    std::uint32_t count = 0;
    std::uint32_t dimension = 2;
    glm::vec3 boxLow{0.0f}, boxHigh{0.0f};  // of the particles now (m): places the next grid
    float fastest = 0.0f;                   // m/s, the largest speed now (bodies near, DeviceFluidExtent)
    bool setUp = false;                     // a setup ran: its constraints hold the densities
    bool onHost = true;                     // the fluid state's arrays hold the particles (deviceFluidOnHost)
    std::vector<kernels::ColliderParams> surfaces;  // the fluid colliders last uploaded
    bool surfacesSet = false;

    ~DeviceFluid() {
        if (device == nullptr) return;
        for (gpu::Buffer* b : {&x, &v, &p, &anchors, &stills, &ids, &wall}) gpu::destroyBuffer(*device, *b);
    }
};

void DeviceFluidDeleter::operator()(DeviceFluid* g) const { delete g; }

gpu::GpuFluidContacts& deviceFluidContacts(DeviceFluid& g) { return *g.contacts; }

namespace {

template <int D>
glm::vec3 to3(fluid::Vec<D> x) {
    if constexpr (D == 2) return glm::vec3(x, 0.0f); else return x;
}

/// A particle buffer and its bytes a particle.
struct ParticleArray {
    gpu::Buffer* buffer;
    VkDeviceSize each;
};
std::array<ParticleArray, 6> particleArrays(DeviceFluid& g) {
    const VkDeviceSize vector = VkDeviceSize{g.dimension} * 4;
    return {{{&g.x, vector}, {&g.v, vector}, {&g.anchors, vector}, {&g.p, 4}, {&g.stills, 4}, {&g.ids, 4}}};
}

/// Room for `n` particles in every particle buffer and the wall; a buffer
/// too small is made anew (its contents lost: the caller uploads them all).
void reserveParticles(DeviceFluid& g, std::uint32_t n) {
    const VkDeviceSize room = std::max<VkDeviceSize>(n, 1);
    for (const ParticleArray& a : particleArrays(g)) {
        if (a.buffer->buffer == VK_NULL_HANDLE || a.buffer->size < room * a.each) {
            gpu::recreateStorageBuffer(*g.device, *a.buffer, room * a.each);
        }
    }
    if (g.wall.buffer == VK_NULL_HANDLE || g.wall.size < room * sizeof(glm::vec4)) {
        gpu::recreateStorageBuffer(*g.device, g.wall, room * sizeof(glm::vec4));
    }
}

/// `p`'s particles onto the device, and their box.
template <int D>
void uploadParticles(DeviceFluid& g, const fluid::Particles<D>& p) {
    static_assert(sizeof(fluid::Vec<D>) == D * sizeof(float));  // tightly packed, as the passes read them
    g.count = static_cast<std::uint32_t>(p.size());
    reserveParticles(g, g.count);
    g.boxLow = glm::vec3(0.0f);
    g.boxHigh = glm::vec3(0.0f);
    g.fastest = 0.0f;
    if (g.count == 0) return;
    g.boxLow = glm::vec3(3.0e38f);
    g.boxHigh = glm::vec3(-3.0e38f);
    for (std::size_t i = 0; i < p.size(); ++i) {
        g.boxLow = glm::min(g.boxLow, to3<D>(p.position[i]));
        g.boxHigh = glm::max(g.boxHigh, to3<D>(p.position[i]));
        g.fastest = std::max(g.fastest, glm::length(p.velocity[i]));
    }
    const auto host = [](const auto& array) { return const_cast<void*>(static_cast<const void*>(array.data())); };
    const std::vector<gpu::Transfer> up{{&g.x, host(p.position), p.position.size() * sizeof(p.position[0])},
                                        {&g.v, host(p.velocity), p.velocity.size() * sizeof(p.velocity[0])},
                                        {&g.p, host(p.pressure), p.pressure.size() * 4},
                                        {&g.anchors, host(p.anchor), p.anchor.size() * sizeof(p.anchor[0])},
                                        {&g.stills, host(p.still), p.still.size() * 4},
                                        {&g.ids, host(p.id), p.id.size() * 4}};  // upload only reads them
    gpu::upload(*g.device, up);
}

/// Room for `n` particles in every particle buffer, the particles there
/// kept (a buffer that grows is copied into its successor on the device).
void growKeeping(DeviceFluid& g, std::uint32_t n) {
    std::vector<std::pair<ParticleArray, gpu::Buffer>> growing;  // the array, its successor
    for (const ParticleArray& a : particleArrays(g)) {
        if (a.buffer->size < n * a.each) {
            growing.emplace_back(a, gpu::createStorageBuffer(*g.device, std::max(n * a.each, 2 * a.buffer->size)));
        }
    }
    if (g.count > 0 && !growing.empty()) {
        gpu::submitOnce(*g.device, [&](VkCommandBuffer cmd) {  // every copy in one submission
            for (const auto& [a, grown] : growing) {
                const VkBufferCopy region{0, 0, g.count * a.each};
                vkCmdCopyBuffer(cmd, a.buffer->buffer, grown.buffer, 1, &region);
            }
        });
    }
    for (auto& [a, grown] : growing) {
        gpu::destroyBuffer(*g.device, *a.buffer);
        *a.buffer = grown;
    }
    reserveParticles(g, n);  // the wall, which holds nothing between substeps
}

/// `births` appended to the device's particles (after the last), and to
/// the box the next grid covers: the bytes of a birth, nothing read back.
template <int D>
void appendParticles(DeviceFluid& g, const fluid::Births& births) {
    if (births.size() == 0) return;
    fluid::Particles<D> p;  // the births as the device's arrays hold them
    for (std::size_t i = 0; i < births.size(); ++i) {
        p.push(fluid::Vec<D>(births.position[i]), fluid::Vec<D>(births.velocity[i]), births.id[i]);
    }
    const std::uint32_t from = g.count;
    const auto n = static_cast<std::uint32_t>(from + p.size());
    growKeeping(g, n);
    const auto host = [](const auto& array) {
        return const_cast<void*>(static_cast<const void*>(array.data()));  // upload only reads it
    };
    const VkDeviceSize vector = sizeof(fluid::Vec<D>), added = p.size();
    const std::vector<gpu::Transfer> up{{&g.x, host(p.position), added * vector, from * vector},
                                        {&g.v, host(p.velocity), added * vector, from * vector},
                                        {&g.p, host(p.pressure), added * 4, from * 4},
                                        {&g.anchors, host(p.anchor), added * vector, from * vector},
                                        {&g.stills, host(p.still), added * 4, from * 4},
                                        {&g.ids, host(p.id), added * 4, from * 4}};
    gpu::upload(*g.device, up);
    if (g.count == 0) {
        g.boxLow = glm::vec3(3.0e38f);
        g.boxHigh = glm::vec3(-3.0e38f);
        g.fastest = 0.0f;
    }
    for (std::size_t i = 0; i < p.size(); ++i) {
        g.boxLow = glm::min(g.boxLow, to3<D>(p.position[i]));
        g.boxHigh = glm::max(g.boxHigh, to3<D>(p.position[i]));
        g.fastest = std::max(g.fastest, glm::length(p.velocity[i]));
    }
    g.count = n;
    g.setUp = false;  // the last setup's densities are of fewer particles
    g.onHost = false;  // the host's arrays lack the births
}

/// The device's particles into `p` (resized).
template <int D>
void downloadParticles(DeviceFluid& g, fluid::Particles<D>& p) {
    const std::size_t n = g.count;
    p.position.resize(n);
    p.velocity.resize(n);
    p.pressure.resize(n);
    p.density.resize(n, 1.0f);
    p.id.resize(n);
    p.anchor.resize(n);
    p.still.resize(n);
    p.motion.resize(n);
    if (n == 0) return;
    std::vector<glm::vec4> constraints(g.setUp ? n : 0);
    std::vector<gpu::Transfer> down{{&g.x, p.position.data(), n * sizeof(p.position[0])},
                                    {&g.v, p.velocity.data(), n * sizeof(p.velocity[0])},
                                    {&g.p, p.pressure.data(), n * 4},
                                    {&g.anchors, p.anchor.data(), n * sizeof(p.anchor[0])},
                                    {&g.stills, p.still.data(), n * 4},
                                    {&g.ids, p.id.data(), n * 4}};
    // The last setup's densities, in the order the particles are now (the
    // setup's grid order, which the carry kept), in the same transfer.
    if (g.setUp) down.push_back({&g.setup->constraints, constraints.data(), n * sizeof(glm::vec4)});
    gpu::download(*g.device, down);
    for (std::size_t i = 0; i < constraints.size(); ++i) p.density[i] = constraints[i].z;
}

/// The fluid colliders (planes, spheres, boxes) and polygons for the
/// contacts, uploaded when they changed.
void setSurfaces(DeviceFluid& g, const fluid::FluidState& f, std::span<const kernels::ColliderParams> colliders) {
    std::vector<kernels::ColliderParams> fluidColliders;
    for (const kernels::ColliderParams& c : colliders) {
        if (fluid::isFluidCollider(c)) fluidColliders.push_back(c);
    }
    if (g.surfacesSet && fluidColliders.size() == g.surfaces.size() &&
        (fluidColliders.empty() || std::memcmp(fluidColliders.data(), g.surfaces.data(),
                                               fluidColliders.size() * sizeof(fluidColliders[0])) == 0)) {
        return;
    }
    std::vector<glm::vec2> table(fluid::WallTable::kSize);
    for (int e = 0; e < fluid::WallTable::kSize; ++e) {
        table[e] = glm::vec2(f.wallTable.density[e], f.wallTable.push[e]);
    }
    gpu::setFluidSurfaces(*g.contacts, {fluidColliders, f.polygons, table, f.wallTable.start, f.wallTable.step});
    g.surfaces = std::move(fluidColliders);
    g.surfacesSet = true;
}

/// Where the substep's grid lies: the CPU's placeGrid for the particles' box
/// (read back after the last substep). An axis the cell budget caps centres
/// its window on the particles' median, which needs their coordinates: read
/// back then (a fluid spread over more than about 2 x 10^5 cells of 2h a
/// side in 2D; the device's median is a later slice).
template <int D>
gpu::FluidGridParams placeDeviceGrid(DeviceFluid& g, const fluid::FluidState& f, fluid::Grid<D>& grid) {
    fluid::Vec<D> lo, hi;
    for (int a = 0; a < D; ++a) {
        lo[a] = g.boxLow[a];
        hi[a] = g.boxHigh[a];
    }
    const std::uint32_t capped = fluid::placeGridInBox<D>(lo, hi, g.count, f.h, grid);
    if (capped != 0) {
        const std::vector<fluid::Vec<D>> x = gpu::downloadArray<fluid::Vec<D>>(*g.device, g.x, g.count);
        std::vector<float> scratch;
        for (int a = 0; a < D; ++a) {
            if ((capped & (1u << a)) == 0) continue;
            const float width = static_cast<float>(grid.cells[a]) * 2.0f * f.h;
            grid.origin[a] = fluid::cappedWindowOrigin(fluid::medianAlong<D>(x, a, scratch), lo[a], hi[a], width);
        }
    }
    gpu::FluidGridParams params;
    params.dimension = D;
    params.origin = to3<D>(grid.origin);
    params.invH = 1.0f / grid.h;
    params.cells = glm::ivec3(grid.cells[0], grid.cells[1], grid.cells[2]);
    return params;
}

/// The passes' settings of one substep of `dt` s, as the CPU's passes
/// compute them from the fluid's state.
struct SubstepParams {
    fluid::Grid<2> cells2;  // the grid as the CPU's passes hold it (2D: the bodies' bins)
    gpu::FluidGridParams grid;
    gpu::FluidSetupParams setup;
    gpu::FluidContactParams contacts;
    gpu::FluidSolveParams solve;
    gpu::FluidIntegrateParams integrate;
};

template <int D>
SubstepParams substepParams(DeviceFluid& g, const fluid::FluidState& f, float dt, bool first) {
    SubstepParams s;
    if constexpr (D == 2) {
        s.grid = placeDeviceGrid<2>(g, f, s.cells2);
    } else {
        fluid::Grid<3> grid;
        s.grid = placeDeviceGrid<3>(g, f, grid);
    }
    // The warm start's share and cap: as setupConstraints (neighbours.cpp) takes them.
    const fluid::WarmStart warm = fluid::warmStartOf(f, dt);
    const float warmFraction = warm.fraction;
    s.setup = {
        f.subCellReadLimit, f.maxNeighbours, f.h, f.restDensity, f.def.baumgarte, fluid::sweepRelaxation(f.def), dt,
        warmFraction};
    s.setup.warmCap = warm.cap;
    // The step's external force, as stepPasses applies it (fluid_step.cpp).
    s.setup.velocityChange = to3<D>(fluid::Vec<D>(glm::vec3(f.def.gravity) * dt));
    s.setup.countClosing = first;  // the substep rule's closing speeds (setupConstraints)
    s.contacts = {f.radius, f.def.spacing, dt, f.def.friction, f.def.splitImpulse};
    s.solve = {f.def.iterations, f.def.splitImpulse, warmFraction, f.restDensity, f.def.baumgarte, f.h, dt};
    s.integrate = {f.def.gravity, dt, f.def.sleepSpeed, f.def.sleepTime, f.def.spacing, f.def.splitImpulse};
    return s;
}

/// A substep's passes up to the solve's end.
void recordSubstepSolve(VkCommandBuffer cmd, DeviceFluid& g, const SubstepParams& s) {
    gpu::recordFluidGrid(cmd, *g.grid, g.x, g.count, s.grid);
    gpu::recordFluidGather(cmd, *g.setup, *g.grid, {&g.x, &g.v, &g.p, &g.wall, g.count}, s.setup);
    gpu::recordFluidContactsFind(cmd, *g.contacts, *g.setup, g.wall, s.contacts, &gpu::gridOrder(*g.grid), &g.ids,
                                 &g.stills);
    gpu::recordFluidConstraints(cmd, *g.setup, *g.grid, s.setup);
    gpu::recordFluidSolve(cmd, *g.solve, *g.grid, *g.setup, g.wall, s.solve, g.contacts.get());
}

/// A substep's integration.
void recordSubstepIntegrate(VkCommandBuffer cmd, DeviceFluid& g, const SubstepParams& s) {
    gpu::recordFluidIntegrate(cmd, *g.integrate, *g.grid, *g.setup, *g.solve, *g.contacts,
                              {&g.anchors, &g.stills, &g.ids}, s.integrate);
}

/// The substep's results (grid order) become the next one's input: the
/// driver's buffers and the passes' outputs trade places, no copy. The
/// driver's buffer is first made the size of the pass's, so the pass's
/// capacity stays true of what it gets (its old contents are dropped: the
/// pass writes it before reading it).
void carry(DeviceFluid& g) {
    const auto trade = [&](gpu::Buffer& mine, gpu::Buffer& pass) {
        if (mine.size != pass.size) gpu::recreateStorageBuffer(*g.device, mine, pass.size);
        std::swap(mine, pass);
    };
    trade(g.x, g.setup->x);
    trade(g.v, g.setup->v);
    trade(g.p, g.setup->p);
    trade(g.anchors, g.integrate->anchors);
    trade(g.stills, g.integrate->stills);
    trade(g.ids, g.integrate->ids);
}

/// The particles whose numbers stopped being finite (marked with a NaN
/// position by the integration) removed, as the CPU's integratePositions
/// removes them: read back, kept in order, uploaded again. Rare (a blow-up);
/// the device's compaction is a later slice.
template <int D>
std::uint64_t removeNonFinite(DeviceFluid& g) {
    fluid::Particles<D> p;
    downloadParticles<D>(g, p);
    const std::size_t removed =
        p.keepIf([&](std::size_t i) { return kernels::fluidFinite(to3<D>(p.position[i])); });
    uploadParticles<D>(g, p);
    g.setUp = false;  // the setup's densities are of the old order
    return removed;
}

/// The bodies of one substep as the device takes them: the shapes at its
/// start and (for bodies the fluid does not move) end poses, each shape's
/// cells, the bodies and the joints' rows.
struct SubstepBodies {
    std::vector<kernels::FluidBodyShape> start, end;
    std::vector<glm::ivec4> cells;
    std::vector<kernels::FluidBodyMotion> motions;
    std::vector<kernels::FluidJointRow> rows;
    bool moves = false;  // a body the fluid moves is among them: the end poses wait for the solve
};

/// The shapes at the bodies' poses now, pad0 1 where the body does not move
/// (the integration stops paths at those shapes' edges).
std::vector<kernels::FluidBodyShape> shapesNow(const fluid::FluidBodyStep& s) {
    std::vector<kernels::FluidBodyShape> shapes = s.shapes;
    for (kernels::FluidBodyShape& shape : shapes) {
        const fluid::StepBody& b = s.bodies[shape.body];
        shape.pad0 = b.velocity == glm::vec2(0.0f) && b.angularVelocity == 0.0f ? 1u : 0u;
    }
    return shapes;
}

/// The bodies near the fluid at this substep (the CPU's beginSubstep, on
/// the fluid's own copies of them) and, when the fluid moves none of them,
/// at its end (advanceBodies: they end where their velocities take them).
SubstepBodies prepareSubstepBodies(const fluid::FluidState& f, fluid::FluidBodyStep& s, const fluid::Grid<2>& grid,
                                   float dt) {
    fluid::beginSubstep(s, f, grid, dt);
    SubstepBodies b;
    b.start = s.shapes;
    for (std::size_t k = 0; k < s.shapes.size(); ++k) b.cells.push_back(fluid::shapeCells(s, grid, k));
    for (const fluid::StepBody& body : s.bodies) {
        b.motions.push_back(fluid::bodyMotion(body));
        b.moves = b.moves || body.invMass > 0.0f;
    }
    b.rows = s.jointRows;
    if (!b.moves) {
        fluid::advanceBodies(s, dt);
        b.end = shapesNow(s);
    }
    return b;
}

void uploadSubstepBodies(DeviceFluid& g, const fluid::FluidState& f, const fluid::FluidBodyStep& s,
                         const SubstepBodies& b, const gpu::FluidGridParams& params) {
    gpu::FluidBodies up;
    up.shapes = b.start;
    up.shapesAtEnd = b.end;
    up.jointRows = b.rows;
    up.moves = b.moves;
    up.shapeCells = b.cells;
    up.bodies = b.motions;
    up.gridOrigin = glm::vec2(params.origin);
    up.gridInvH = params.invH;
    up.cells = glm::ivec2(params.cells);
    up.particleInvMass = s.particleInvMass;
    up.binnedReach = f.radius + f.def.spacing;  // as integratePositions's (collide.cpp)
    up.impactSpeed = kFluidImpactSpeed;
    gpu::setFluidBodies(*g.contacts, up);
}

/// After a solve that moved bodies: the fluid's copies take the device's
/// velocities and the step's impulses (`motions`, read back), move on by dt
/// (advanceBodies), and the shapes at their end poses go up for the
/// integration.
void advanceMovedBodies(DeviceFluid& g, fluid::FluidBodyStep& s, const std::vector<kernels::FluidBodyMotion>& motions,
                        float dt) {
    for (std::size_t k = 0; k < s.bodies.size() && k < motions.size(); ++k) {
        s.bodies[k].velocity = motions[k].velocity;
        s.bodies[k].angularVelocity = motions[k].angularVelocity;
        s.bodies[k].linearImpulse = motions[k].linearImpulse;
        s.bodies[k].angularImpulse = motions[k].angularImpulse;
    }
    fluid::advanceBodies(s, dt);
    gpu::setFluidBodyShapesAtEnd(*g.contacts, shapesNow(s));
}

/// The substep's strikes on bodies, in the CPU's order: by chunk of
/// particles (grid order), then the particle, then the shape (the CPU's
/// findBodyContacts appends each chunk's impacts of every substep to that
/// chunk's list).
void keepImpacts(const gpu::FluidBodyReadback& r, fluid::FluidBodyStep& s, std::uint32_t count) {
    std::vector<kernels::FluidBodyImpact> impacts = r.impacts;
    std::sort(impacts.begin(), impacts.end(), [](const kernels::FluidBodyImpact& a, const kernels::FluidBodyImpact& b) {
        return a.place != b.place ? a.place < b.place : a.shape < b.shape;
    });
    s.impacts.resize(std::max(s.impacts.size(), WorkerPool::chunkCount(count, fluid::kParticleChunk)));
    for (const kernels::FluidBodyImpact& hit : impacts) {
        s.impacts[hit.place / fluid::kParticleChunk].push_back(
            {hit.id, s.bodies[hit.body].slot, hit.position, hit.approach});
    }
    s.contactCount += r.report.contacts;
}

template <int D>
void substep(DeviceFluid& g, fluid::FluidState& f, float dt, bool first, FluidStepStats& stats) {
    const SubstepParams params = substepParams<D>(g, f, dt, first);
    fluid::FluidBodyStep* bodies = D == 2 ? f.bodies : nullptr;
    SubstepBodies prepared;
    if (bodies != nullptr) {
        prepared = prepareSubstepBodies(f, *bodies, params.cells2, dt);
    } else if (g.contacts->shapeCount > 0 || g.contacts->moves) {
        gpu::setFluidBodies(*g.contacts, {});
    }
    // One submission; two when the solve moves bodies (their end poses,
    // which the integration meets, come from its velocities). The lists and
    // the body contacts hold what the setup and the find found, or the
    // substep runs again with room for them (its inputs, the bodies
    // included, untouched until the carry).
    const bool split = prepared.moves;
    gpu::FluidSubstepReport r;
    gpu::FluidBodyReadback b;
    std::vector<kernels::FluidBodyMotion> motions(split ? bodies->bodies.size() : 0);
    for (;;) {
        if (bodies != nullptr) uploadSubstepBodies(g, f, *bodies, prepared, params.grid);
        gpu::submitOnce(*g.device, [&](VkCommandBuffer cmd) {
            recordSubstepSolve(cmd, g, params);
            if (!split) recordSubstepIntegrate(cmd, g, params);
        });
        // Split, the integration has not run yet: the lists' entries and the
        // bodies after the solve, in the bodies' report's transfer.
        if (split) {
            kernels::FluidSetupHeader header{};
            const std::array<gpu::Transfer, 2> alongside{
                gpu::Transfer{&g.setup->header, &header, sizeof header},
                gpu::Transfer{&g.contacts->bodies, motions.data(), motions.size() * sizeof(motions[0])}};
            b = gpu::readFluidBodyReport(*g.contacts, alongside);
            r.listEntries = header.entries;
        } else {
            r = gpu::readFluidSubstepReport(*g.setup, *g.integrate);
            if (bodies != nullptr) b = gpu::readFluidBodyReport(*g.contacts);
        }
        const bool listsFit = r.listEntries <= g.setup->listCapacity;
        const bool bodiesFit =
            b.report.mostContacts <= g.contacts->bodySlots && b.report.impacts <= g.contacts->impactRoom;
        if (listsFit && bodiesFit) break;
        if (!listsFit) gpu::reserveFluidLists(*g.setup, r.listEntries + r.listEntries / 4);
        if (!bodiesFit) {
            gpu::reserveFluidBodyRoom(*g.contacts, std::max(g.contacts->bodySlots, b.report.mostContacts),
                                      std::max(g.contacts->impactRoom, 2 * b.report.impacts));
        }
    }
    if (split) {
        advanceMovedBodies(g, *bodies, motions, dt);
        gpu::submitOnce(*g.device, [&](VkCommandBuffer cmd) { recordSubstepIntegrate(cmd, g, params); });
        r = gpu::readFluidSubstepReport(*g.setup, *g.integrate);
    }
    if (bodies != nullptr) keepImpacts(b, *bodies, g.count);
    carry(g);
    g.setUp = true;
    f.lastSubstep = dt;  // as solveConstraints records it
    stats.neighbourOverflows += r.neighbourOverflows;

    // The substep's statistics, as the CPU's setup and integration report
    // them (the density ones are the last substep's).
    const double n = std::max<double>(g.count, 1.0);
    stats.meanDensityError = r.densityErrorSum / n;
    stats.maxDensityError = g.count > 0 ? r.maxDensityError : 0.0;
    stats.meanNeighbours = r.neighbours / n;
    stats.maxSpeed = r.maxSpeed;
    // The substep rule's closing speeds: only the step's first substep
    // computes them, as the CPU's setup does (setupConstraints).
    if (first) {
        for (std::size_t b = 0; b < f.approach.size(); ++b) f.approach[b] += r.approach[b];
    }
    f.pressedDepth = r.pressedDepth;
    g.boxLow = r.boxLow;
    g.boxHigh = r.boxHigh;
    g.fastest = r.maxSpeed;
    if (r.nonFinite > 0) stats.nonFinite += removeNonFinite<D>(g);
}

}  // namespace

DeviceFluidPtr createDeviceFluid(gpu::Device& d, const fluid::FluidState& f) {
    if (f.def.solver != FluidSolver::Parallel) {
        throw Error(fmt::format("fluid '{}': the device fluid solves in the Parallel order only", f.def.name));
    }
    DeviceFluidPtr g(new DeviceFluid);
    g->device = &d;
    g->dimension = f.def.dimension;
    g->grid = gpu::createGpuFluidGrid(d);
    g->setup = gpu::createGpuFluidSetup(d);
    g->solve = gpu::createGpuFluidSolve(d);
    g->contacts = gpu::createGpuFluidContacts(d);
    g->integrate = gpu::createGpuFluidIntegrate(d);
    g->carry = gpu::createGpuFluidCarry(d);
    uploadDeviceFluid(*g, f);
    return g;
}

FluidStepStats stepDeviceFluid(DeviceFluid& g, fluid::FluidState& f,
                               std::span<const kernels::ColliderParams> colliders, FluidId id, float dt) {
    FluidStepStats stats;
    stats.fluid = id;
    setSurfaces(g, f, colliders);
    const int substeps = fluid::substepsOfStep(f, dt, stats);
    const float h = dt / static_cast<float>(substeps);
    for (int k = 0; k < substeps && g.count > 0; ++k) {
        if (f.def.dimension == 2) {
            substep<2>(g, f, h, k == 0, stats);
        } else {
            substep<3>(g, f, h, k == 0, stats);
        }
    }
    g.onHost = g.onHost && g.count == 0;  // a step with particles leaves the host copy behind
    f.lastMeanDensityError = static_cast<float>(stats.meanDensityError);
    f.lastSubsteps = substeps;
    stats.substeps = static_cast<std::uint32_t>(substeps);
    stats.particles = g.count;
    stats.device = true;
    f.steps += 1;
    return stats;
}

void carryDeviceFluid(DeviceFluid& g, const fluid::FluidState& f, fluid::FluidBodyStep& moved) {
    if (g.dimension != 2 || g.count == 0) return;
    const std::vector<fluid::BodyEndPose> was = fluid::placeMovedBodies(f, moved);
    std::vector<kernels::FluidBodyCarry> bodies(moved.bodies.size());
    bool any = false;
    for (std::size_t k = 0; k < bodies.size(); ++k) {
        const fluid::StepBody& now = moved.bodies[k];
        // The CPU's turn of x - then.centre by now.angle - then.angle.
        const float turn = now.angle - was[k].angle;
        bodies[k].then = was[k].centre;
        bodies[k].now = now.centre;
        bodies[k].cosTurn = std::cos(turn);
        bodies[k].sinTurn = std::sin(turn);
        bodies[k].moving = now.invMass > 0.0f ? 1u : 0u;
        any = any || bodies[k].moving != 0u;
    }
    if (!any) return;
    const std::vector<kernels::FluidBodyShape> shapes = shapesNow(moved);
    const glm::vec4 box = gpu::carryOnDevice(*g.carry, *g.contacts, g.x, g.count, {shapes, moved.shapeBox, bodies});
    if (box.x <= box.z) {
        g.boxLow = glm::vec3(box.x, box.y, 0.0f);
        g.boxHigh = glm::vec3(box.z, box.w, 0.0f);
    }
    g.onHost = false;
}

void appendDeviceBirths(DeviceFluid& g, const fluid::Births& births) {
    if (g.dimension == 2) {
        appendParticles<2>(g, births);
    } else {
        appendParticles<3>(g, births);
    }
}

std::size_t deviceFluidCount(const DeviceFluid& g) { return g.count; }

DeviceFluidExtent deviceFluidExtent(const DeviceFluid& g) { return {g.count, g.boxLow, g.boxHigh, g.fastest}; }

void uploadDeviceFluid(DeviceFluid& g, const fluid::FluidState& f) {
    if (f.def.dimension == 2) {
        uploadParticles<2>(g, f.p2);
    } else {
        uploadParticles<3>(g, f.p3);
    }
    g.setUp = false;
    g.onHost = true;
}

bool deviceFluidOnHost(const DeviceFluid& g) { return g.onHost; }

DeviceFluidBuffers deviceFluidBuffers(const DeviceFluid& g) {
    DeviceFluidBuffers b;
    b.x = &g.x;
    b.v = &g.v;
    b.ids = &g.ids;
    if (g.setUp) {
        b.constraints = &g.setup->constraints;
        b.counts = &g.setup->counts;
        b.first = &g.setup->first;
        b.list = &g.setup->listIndex;
    }
    b.count = g.count;
    b.dimension = g.dimension;
    return b;
}

void readDeviceFluid(DeviceFluid& g, fluid::FluidState& f) {
    if (f.def.dimension == 2) {
        downloadParticles<2>(g, f.p2);
    } else {
        downloadParticles<3>(g, f.p3);
    }
    g.onHost = true;
}

}  // namespace spindrift
