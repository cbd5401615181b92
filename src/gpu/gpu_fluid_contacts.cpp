// The constraint fluid's contacts with static colliders on the device:
// pipelines, surfaces and the recorded passes of fluid_contacts.comp.
#include "gpu/gpu_fluid_contacts.h"

#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/layout.glsl"

#include <spindrift/errors.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <utility>

namespace spindrift::gpu {
namespace {

// Bindings, passes and push constants of fluid_contacts.comp: src/kernels/layout.glsl.
constexpr std::uint32_t kBindings = kernels::SD_FLUID_CONTACTS_BINDINGS;
constexpr std::uint32_t kWorkgroup = kernels::SD_FLUID_CONTACTS_WORKGROUP;
using kernels::FluidContactsPush;
static_assert(sizeof(kernels::FluidBodyShape) == 304);
static_assert(sizeof(kernels::FluidBodyMotion) == 48);
static_assert(sizeof(kernels::FluidJointRow) == 48);
static_assert(sizeof(kernels::FluidBodyContact) == 48);
static_assert(sizeof(glm::ivec4) == 16);

void writeSet(GpuFluidContacts& c, VkDescriptorSet set, const Buffer& x, const Buffer& v, const Buffer& wall,
              const Buffer& motion) {
    std::array<const Buffer*, kBindings> buffers{};
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_X] = &x;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_V] = &v;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_COLLIDERS] = &c.colliders;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_POLYGONS] = &c.polygons;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_WALL_TABLE] = &c.wallTable;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_WALL] = &wall;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_MASK] = &c.masks;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_MOTION] = &motion;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_SHAPES] = &c.shapes;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_SHAPE_CELLS] = &c.shapeCells;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_BODIES] = &c.bodies;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_BODY_CONTACTS] = &c.bodyContacts;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_BODY_COUNTS] = &c.bodyCounts;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_BODY_REPORT] = &c.bodyReport;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_ORDER] = c.boundOrder;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_IDS] = c.boundIds;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_DYNAMIC] = &c.dynamicList;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_JOINT_ROWS] = &c.jointRows;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_STILLS] = c.boundStills;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_DYNAMIC_STARTS] = &c.dynamicStarts;
    buffers[kernels::SD_FLUID_CONTACTS_BINDING_GROUP_STARTS] = &c.groupStarts;
    writeStorageSet(*c.device, set, buffers);
}

FluidContactsPush pushOf(const GpuFluidContacts& c) {
    FluidContactsPush push{};
    push.count = c.count;
    push.dimension = c.dimension;
    push.colliders = c.colliderCount;
    push.polygons = c.polygonCount;
    push.radius = c.params.radius;
    push.spacing = c.params.spacing;
    push.dt = c.params.dt;
    push.friction = c.params.friction;
    push.tableStart = c.tableStart;
    push.tableStep = c.tableStep;
    push.tableSize = c.tableSize;
    push.split = c.params.split ? 1u : 0u;
    push.grid = c.grid;
    push.cells = glm::ivec4(c.cells, static_cast<int>(c.shapeCount), static_cast<int>(c.bodySlots));
    push.impactSpeed = c.impactSpeed;
    push.impactRoom = c.impactRoom;
    push.jointRows = c.jointRowCount;
    return push;
}

}  // namespace

GpuFluidContacts::~GpuFluidContacts() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    for (Buffer* b : {&colliders, &polygons, &wallTable, &masks, &shapes, &shapesAtEnd, &shapeCells, &bodies,
                      &bodyContacts, &bodyCounts, &bodyReport, &dynamicList, &dynamicStarts, &groupStarts,
                      &jointRows}) {
        destroyBuffer(*device, *b);
    }
    destroyComputePasses(*device, passes);
}

std::unique_ptr<GpuFluidContacts> createGpuFluidContacts(Device& d) {
    auto c = std::make_unique<GpuFluidContacts>();  // destroys what was made if a step throws
    c->device = &d;
    createComputePasses(d, kBindings, sizeof(FluidContactsPush), 2,
                        std::span(shaders::kFluidContacts, shaders::kFluidContactsWords), kernels::SD_FLUID_CONTACTS_PASSES,
                        "fluid_contacts",
                        c->passes);
    const glm::vec2 empty[2] = {glm::vec2(0.0f), glm::vec2(0.0f)};
    setFluidSurfaces(*c, {{}, {}, empty, 0.0f, 1.0f});
    setFluidBodies(*c, {});
    reserveFluidBodyRoom(*c, c->bodySlots, c->impactRoom);
    return c;
}

void setFluidSurfaces(GpuFluidContacts& c, const FluidSurfaces& surfaces) {
    const std::size_t count = surfaces.colliders.size() + surfaces.polygons.size();
    if (count > kernels::SD_FLUID_MAX_SURFACES) {
        throw Error(fmt::format("gpu fluid contacts: {} colliders and polygons; the device fluid tells at most {} apart",
                                count, kernels::SD_FLUID_MAX_SURFACES));
    }
    if (surfaces.wallTable.size() < 2) {
        throw Error(fmt::format("gpu fluid contacts: a wall table of {} entries (2 at least)", surfaces.wallTable.size()));
    }
    Device& d = *c.device;
    uploadGrowing(d, c.colliders, surfaces.colliders.data(), surfaces.colliders.size_bytes());
    uploadGrowing(d, c.polygons, surfaces.polygons.data(), surfaces.polygons.size_bytes());
    uploadGrowing(d, c.wallTable, surfaces.wallTable.data(), surfaces.wallTable.size_bytes());
    c.colliderCount = static_cast<std::uint32_t>(surfaces.colliders.size());
    c.polygonCount = static_cast<std::uint32_t>(surfaces.polygons.size());
    c.tableSize = static_cast<std::uint32_t>(surfaces.wallTable.size());
    c.tableStart = surfaces.tableStart;
    c.tableStep = surfaces.tableStep;
}

void setFluidBodies(GpuFluidContacts& c, const FluidBodies& bodies) {
    Device& d = *c.device;
    uploadGrowing(d, c.shapes, bodies.shapes.data(), bodies.shapes.size_bytes());
    uploadGrowing(d, c.shapesAtEnd, bodies.shapesAtEnd.data(), bodies.shapesAtEnd.size_bytes());
    uploadGrowing(d, c.shapeCells, bodies.shapeCells.data(), bodies.shapeCells.size_bytes());
    uploadGrowing(d, c.bodies, bodies.bodies.data(), bodies.bodies.size_bytes());
    uploadGrowing(d, c.jointRows, bodies.jointRows.data(), bodies.jointRows.size_bytes());
    c.shapeCount = static_cast<std::uint32_t>(bodies.shapes.size());
    c.jointRowCount = static_cast<std::uint32_t>(bodies.jointRows.size());
    c.bodyCount = static_cast<std::uint32_t>(bodies.bodies.size());
    c.moves = bodies.moves;
    c.grid = glm::vec4(bodies.gridOrigin, bodies.gridInvH, bodies.particleInvMass);
    c.cells = bodies.cells;
    c.binnedReach = bodies.binnedReach;
    c.impactSpeed = bodies.impactSpeed;
}

void reserveFluidBodyRoom(GpuFluidContacts& c, std::uint32_t slots, std::uint32_t impacts) {
    c.bodySlots = std::max(slots, 1u);
    c.impactRoom = std::max(impacts, 1u);
    recreateStorageBuffer(*c.device, c.bodyReport,
                          sizeof(kernels::FluidBodyReport) + VkDeviceSize{c.impactRoom} * sizeof(kernels::FluidBodyImpact));
    c.bodyCapacity = 0;  // the contacts are made anew at the next find with bodies
}

/// Room for the body contacts of `n` particles (a few bytes while there
/// are no bodies: the bindings still need buffers).
void reserveBodyContacts(GpuFluidContacts& c, std::uint32_t n) {
    const std::uint32_t want = c.shapeCount > 0 ? n : 0;
    if (c.bodyContacts.buffer != VK_NULL_HANDLE && want <= c.bodyCapacity) return;
    const std::uint32_t room = std::max(want, 2 * c.bodyCapacity);
    recreateStorageBuffer(*c.device, c.bodyContacts,
                          std::max<VkDeviceSize>(VkDeviceSize{room} * c.bodySlots * sizeof(kernels::FluidBodyContact), 16));
    recreateStorageBuffer(*c.device, c.bodyCounts, std::max<VkDeviceSize>(VkDeviceSize{room} * 4, 16));
    recreateStorageBuffer(*c.device, c.dynamicList, std::max<VkDeviceSize>(VkDeviceSize{room} * c.bodySlots * 4, 16));
    recreateStorageBuffer(*c.device, c.dynamicStarts, std::max<VkDeviceSize>(VkDeviceSize{room} * 4, 16));
    const VkDeviceSize groups = (VkDeviceSize{room} + kWorkgroup - 1) / kWorkgroup;
    recreateStorageBuffer(*c.device, c.groupStarts, std::max<VkDeviceSize>(groups * 4, 16));
    c.bodyCapacity = room;
}

void setFluidBodyShapesAtEnd(GpuFluidContacts& c, std::span<const kernels::FluidBodyShape> shapes) {
    uploadGrowing(*c.device, c.shapesAtEnd, shapes.data(), shapes.size_bytes());
}


void recordFluidContactsFind(VkCommandBuffer cmd, GpuFluidContacts& c, const GpuFluidSetup& setup, Buffer& wall,
                             const FluidContactParams& params, const Buffer* order, const Buffer* ids,
                             Buffer* stills) {
    const std::uint32_t n = setup.count;
    requireBufferBytes(&wall, VkDeviceSize{n} * 16, "gpu fluid contacts", "wall");
    const std::uint32_t groups = workgroupsFor(*c.device, n, kWorkgroup, "gpu fluid contacts", "particles");
    if (n > c.capacity) {
        const std::uint32_t room = std::max(n, 2 * c.capacity);
        recreateStorageBuffer(*c.device, c.masks, VkDeviceSize{room} * 4);
        c.capacity = room;
    }
    c.count = n;
    c.dimension = setup.dimension;
    c.params = params;
    c.boundX = &setup.x;
    c.boundV = &setup.v;
    c.boundWall = &wall;
    if (c.shapeCount > 0 && (order == nullptr || ids == nullptr || stills == nullptr)) {
        throw Error("gpu fluid contacts: bodies need the grid order, the particles' serials and times still");
    }
    reserveBodyContacts(c, n);
    // Placeholders where there are no bodies (not read).
    c.boundOrder = order != nullptr ? order : &c.masks;
    c.boundIds = ids != nullptr ? ids : &c.masks;
    c.boundStills = stills != nullptr ? stills : &c.masks;
    // The solve pass's set names the masks too; it is written when a solve
    // is recorded. Here the motion binding is a placeholder (not read).
    writeSet(c, c.passes.sets[0], setup.x, setup.v, wall, c.masks);
    const FluidContactsPush push = pushOf(c);
    // The body report starts empty.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                  VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, c.bodyReport.buffer, 0, sizeof(kernels::FluidBodyReport), 0u);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    computeToCompute(cmd);  // the gather
    if (n > 0) {
        dispatchCompute(cmd, c.passes.pipelines[kernels::SD_FLUID_CONTACTS_PASS_FIND], c.passes.pipelineLayout,
                        c.passes.sets[0], &push, sizeof(push), groups);
        if (c.moves && c.shapeCount > 0) {
            // The list of contacts with bodies the fluid moves, by a prefix
            // sum of their counts: within workgroups, over them, then written.
            // Without shapes there are none (the report starts at 0), and the
            // lists' buffers have no room for the particles.
            for (const auto& [pass, dispatched] : {std::pair{kernels::SD_FLUID_CONTACTS_PASS_COUNT, groups},
                                                   std::pair{kernels::SD_FLUID_CONTACTS_PASS_GROUPS, 1u},
                                                   std::pair{kernels::SD_FLUID_CONTACTS_PASS_ORDER, groups}}) {
                computeToCompute(cmd);
                dispatchCompute(cmd, c.passes.pipelines[pass], c.passes.pipelineLayout, c.passes.sets[0], &push,
                                sizeof(push), dispatched);
            }
        }
    }
    computeToCompute(cmd);
}

void recordFluidContactsSolve(VkCommandBuffer cmd, GpuFluidContacts& c, const Buffer& motion, bool firstAfterFind) {
    if (c.count == 0 || c.colliderCount + c.polygonCount + c.shapeCount == 0) {
        return;
    }
    if (firstAfterFind) {
        writeSet(c, c.passes.sets[1], *c.boundX, *c.boundV, *c.boundWall, motion);
    }
    const FluidContactsPush push = pushOf(c);
    const std::uint32_t groups = workgroupsFor(*c.device, c.count, kWorkgroup, "gpu fluid contacts", "particles");
    dispatchCompute(cmd, c.passes.pipelines[kernels::SD_FLUID_CONTACTS_PASS_SOLVE], c.passes.pipelineLayout,
                    c.passes.sets[1], &push, sizeof(push), groups);
    computeToCompute(cmd);
    if (c.moves) {
        // After every particle's colliders and still bodies: the CPU's order.
        dispatchCompute(cmd, c.passes.pipelines[kernels::SD_FLUID_CONTACTS_PASS_DYNAMIC], c.passes.pipelineLayout,
                        c.passes.sets[1], &push, sizeof(push), 1);
        computeToCompute(cmd);
    }
}

FluidBodyReadback readFluidBodyReport(GpuFluidContacts& c, std::span<const Transfer> alongside) {
    FluidBodyReadback r;
    std::vector<Transfer> down{{&c.bodyReport, &r.report, sizeof r.report}};
    down.insert(down.end(), alongside.begin(), alongside.end());
    download(*c.device, down);
    const std::uint32_t impacts = std::min(r.report.impacts, c.impactRoom);
    if (impacts > 0) {
        r.impacts.resize(impacts);
        const Transfer records{&c.bodyReport, r.impacts.data(), impacts * sizeof(kernels::FluidBodyImpact),
                               sizeof(kernels::FluidBodyReport)};
        download(*c.device, std::span(&records, 1));
    }
    return r;
}

FluidDynamicListing readFluidDynamicListing(GpuFluidContacts& c) {
    FluidDynamicListing l;
    if (c.shapeCount == 0 || c.count == 0) return l;
    const kernels::FluidBodyReport report = readFluidBodyReport(c).report;
    l.slots = c.bodySlots;
    l.counts.resize(c.count);
    l.contacts.resize(std::size_t{c.count} * c.bodySlots);
    l.bodies.resize(c.bodyCount);
    l.list.resize(report.dynamic);
    std::vector<Transfer> down{{&c.bodyCounts, l.counts.data(), l.counts.size() * 4},
                               {&c.bodyContacts, l.contacts.data(), l.contacts.size() * sizeof(kernels::FluidBodyContact)}};
    if (!l.bodies.empty()) down.push_back({&c.bodies, l.bodies.data(), l.bodies.size() * sizeof(kernels::FluidBodyMotion)});
    if (!l.list.empty()) down.push_back({&c.dynamicList, l.list.data(), l.list.size() * 4});
    download(*c.device, down);
    return l;
}

}  // namespace spindrift::gpu
