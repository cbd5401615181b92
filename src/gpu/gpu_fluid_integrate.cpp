// The constraint fluid's integration on the device: pipeline, buffers and the
// recorded pass of fluid_integrate.comp.
#include "gpu/gpu_fluid_integrate.h"

#include "gpu/shaders.h"
#include "kernels/fluid.glsl"
#include "kernels/layout.glsl"

#include <spindrift/errors.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <span>

namespace spindrift::gpu {
namespace {

constexpr std::uint32_t kBindings = kernels::SD_FLUID_INTEGRATE_BINDINGS;
constexpr std::uint32_t kWorkgroup = kernels::SD_FLUID_INTEGRATE_WORKGROUP;
using kernels::FluidIntegratePush;
using kernels::FluidIntegrateStats;

}  // namespace

float fromOrderKey(std::uint32_t key) {
    const std::uint32_t bits = (key & 0x80000000u) != 0u ? key & 0x7FFFFFFFu : ~key;
    return std::bit_cast<float>(bits);
}

GpuFluidIntegrate::~GpuFluidIntegrate() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    for (Buffer* b : {&anchors, &stills, &ids, &stats, &partials}) destroyBuffer(*device, *b);
    destroyComputePasses(*device, passes);
}

std::unique_ptr<GpuFluidIntegrate> createGpuFluidIntegrate(Device& d) {
    auto g = std::make_unique<GpuFluidIntegrate>();  // destroys what was made if a step throws
    g->device = &d;
    createComputePasses(d, kBindings, sizeof(FluidIntegratePush), 1,
                        std::span(shaders::kFluidIntegrate, shaders::kFluidIntegrateWords), 2, "fluid_integrate",
                        g->passes);
    recreateStorageBuffer(d, g->stats, sizeof(FluidIntegrateStats));
    return g;
}

void recordFluidIntegrate(VkCommandBuffer cmd, GpuFluidIntegrate& g, const GpuFluidGrid& grid, GpuFluidSetup& setup,
                          GpuFluidSolve& solve, GpuFluidContacts& contacts, const FluidSleepInputs& sleep,
                          const FluidIntegrateParams& params) {
    const std::uint32_t n = setup.count;
    const std::uint32_t d = setup.dimension;
    requireBufferBytes(sleep.anchors, VkDeviceSize{n} * d * 4, "gpu fluid integrate", "anchors");
    requireBufferBytes(sleep.stills, VkDeviceSize{n} * 4, "gpu fluid integrate", "stills");
    if (sleep.ids != nullptr) requireBufferBytes(sleep.ids, VkDeviceSize{n} * 4, "gpu fluid integrate", "ids");
    const std::uint32_t groups = workgroupsFor(*g.device, n, kWorkgroup, "gpu fluid integrate", "particles");
    if (n > g.capacity || g.anchors.buffer == VK_NULL_HANDLE) {
        const std::uint32_t room = std::max({n, 2 * g.capacity, kWorkgroup});
        recreateStorageBuffer(*g.device, g.anchors, VkDeviceSize{room} * 3 * 4);  // room for 3D
        recreateStorageBuffer(*g.device, g.stills, VkDeviceSize{room} * 4);
        recreateStorageBuffer(*g.device, g.ids, VkDeviceSize{room} * 4);
        recreateStorageBuffer(*g.device, g.partials, VkDeviceSize{(room + kWorkgroup - 1) / kWorkgroup} * 4);
        g.capacity = room;
    }
    g.count = n;
    g.dimension = d;
    std::array<const Buffer*, kBindings> buffers{};
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_ORDER] = &gridOrder(grid);
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_X] = &setup.x;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_V] = &setup.v;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_P] = &setup.p;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_MOTION] = &solve.motion;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_ANCHOR_IN] = sleep.anchors;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_STILL_IN] = sleep.stills;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_ANCHOR] = &g.anchors;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_STILL] = &g.stills;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_COLLIDERS] = &contacts.colliders;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_POLYGONS] = &contacts.polygons;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_STATS] = &g.stats;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_CONSTRAINTS] = &setup.constraints;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_COUNTS] = &setup.counts;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_PARTIALS] = &g.partials;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_ID_IN] = sleep.ids != nullptr ? sleep.ids : &g.ids;  // unread without
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_ID] = &g.ids;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_SHAPES] = &contacts.shapesAtEnd;
    buffers[kernels::SD_FLUID_INTEGRATE_BINDING_SHAPE_CELLS] = &contacts.shapeCells;
    writeStorageSet(*g.device, g.passes.sets[0], buffers);

    // The constants as the CPU's integratePositions computes them.
    FluidIntegratePush push{};
    const float gravity = glm::length(params.gravity);
    push.down = gravity > 0.0f ? glm::vec4(params.gravity / gravity, 0.0f) : glm::vec4(0.0f);
    push.count = n;
    push.dimension = d;
    push.colliders = contacts.colliderCount;
    push.polygons = contacts.polygonCount;
    push.dt = params.dt;
    push.sleepTime = params.sleepTime;
    push.wakeSpeed = kernels::SD_FLUID_WAKE_FACTOR * params.sleepSpeed;
    push.drift = kernels::fluidSleepDrift(params.sleepSpeed, params.sleepTime, params.spacing);
    push.split = params.split ? 1u : 0u;
    push.sleeps = params.sleepSpeed > 0.0f ? 1u : 0u;
    push.groups = n > 0 ? groups : 0u;
    push.carriesIds = sleep.ids != nullptr ? 1u : 0u;
    push.grid = glm::vec4(contacts.grid.x, contacts.grid.y, contacts.grid.z, contacts.binnedReach);
    push.cells = glm::ivec4(contacts.cells, static_cast<int>(contacts.shapeCount), 0);

    // The statistics start empty: no speed, empty ranges (low keys at the
    // most, high keys at the least), no counts. Fills of disjoint ranges.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    const VkDeviceSize lowX = offsetof(FluidIntegrateStats, lowX);
    const VkDeviceSize maxError = offsetof(FluidIntegrateStats, maxError);
    vkCmdFillBuffer(cmd, g.stats.buffer, 0, 4, 0u);                            // fastest
    vkCmdFillBuffer(cmd, g.stats.buffer, 4, 4, 0xFFFFFFFFu);                   // pressedLow
    vkCmdFillBuffer(cmd, g.stats.buffer, 8, lowX - 8, 0u);                     // pressedHigh, nonFinite
    vkCmdFillBuffer(cmd, g.stats.buffer, lowX, maxError - lowX, 0xFFFFFFFFu);  // lowX, lowY, lowZ
    vkCmdFillBuffer(cmd, g.stats.buffer, maxError, sizeof(FluidIntegrateStats) - maxError, 0u);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    if (n > 0) {
        dispatchCompute(cmd, g.passes.pipelines[kernels::SD_FLUID_INTEGRATE_PASS_MOVE], g.passes.pipelineLayout,
                        g.passes.sets[0], &push, sizeof(push), groups);
        computeToCompute(cmd);
        dispatchCompute(cmd, g.passes.pipelines[kernels::SD_FLUID_INTEGRATE_PASS_TOTALS], g.passes.pipelineLayout,
                        g.passes.sets[0], &push, sizeof(push), 1);
    }
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

FluidSubstepReport readFluidSubstepReport(GpuFluidSetup& setup, GpuFluidIntegrate& g) {
    FluidSubstepReport r;
    kernels::FluidSetupHeader header{};
    FluidIntegrateStats s{};
    const std::array<Transfer, 2> down{Transfer{&setup.header, &header, sizeof header},
                                       Transfer{&g.stats, &s, sizeof s}};
    download(*g.device, down);
    r.listEntries = header.entries;
    r.neighbourOverflows = header.overflows;
    r.maxSpeed = std::bit_cast<float>(s.fastest);
    const float low = fromOrderKey(s.pressedLow), high = fromOrderKey(s.pressedHigh);
    r.pressedDepth = s.pressedLow != 0xFFFFFFFFu && high > low ? high - low : 0.0f;
    r.nonFinite = s.nonFinite;
    if (s.lowX != 0xFFFFFFFFu) {  // some particle finite
        r.boxLow = glm::vec3(fromOrderKey(s.lowX), fromOrderKey(s.lowY), fromOrderKey(s.lowZ));
        r.boxHigh = glm::vec3(fromOrderKey(s.highX), fromOrderKey(s.highY), fromOrderKey(s.highZ));
    }
    r.maxDensityError = g.count > 0 ? fromOrderKey(s.maxError) : 0.0f;
    r.densityErrorSum = s.errorSum;
    r.neighbours = s.neighbours;
    for (std::uint32_t b = 0; b < kernels::SD_FLUID_APPROACH_BINS; ++b) r.approach[b] = s.approach[b];
    return r;
}

FluidIntegrateReadback readFluidIntegrate(GpuFluidSetup& setup, GpuFluidIntegrate& g) {
    FluidIntegrateReadback r;
    const FluidSubstepReport report = readFluidSubstepReport(setup, g);
    r.maxSpeed = report.maxSpeed;
    r.pressedDepth = report.pressedDepth;
    r.nonFinite = report.nonFinite;
    r.anchors = downloadArray<float>(*g.device, g.anchors, std::size_t{g.count} * g.dimension);
    r.stills = downloadArray<float>(*g.device, g.stills, g.count);
    return r;
}

}  // namespace spindrift::gpu
