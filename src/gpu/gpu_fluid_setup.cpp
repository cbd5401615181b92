// The constraint fluid's setup on the device: pipelines, buffers and the
// recorded passes of fluid_setup.comp.
#include "gpu/gpu_fluid_setup.h"

#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "kernels/layout.glsl"

#include <spindrift/errors.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <span>

namespace spindrift::gpu {
namespace {

// Bindings, passes and push constants of fluid_setup.comp: src/kernels/layout.glsl.
constexpr std::uint32_t kBindings = kernels::SD_FLUID_SETUP_BINDINGS;
constexpr std::uint32_t kWorkgroup = kernels::SD_FLUID_SETUP_WORKGROUP;
using kernels::FluidSetupHeader;
using kernels::FluidSetupPush;

/// List entries per particle the lists hold at least: a particle at rest has
/// about 36 neighbours within h = 3.5 spacings in 2D and 113 in 3D; a
/// compressed fluid more.
constexpr std::uint32_t kEntriesPerParticle2D = 64;
constexpr std::uint32_t kEntriesPerParticle3D = 256;

// Per-particle buffers for `count` particles. Only between submissions.
void reserveParticles(GpuFluidSetup& s, std::uint32_t count) {
    if (count <= s.capacity && s.header.buffer != VK_NULL_HANDLE) {
        return;
    }
    Device& d = *s.device;
    const std::uint32_t n = std::max(count, std::max(2 * s.capacity, kWorkgroup));
    const VkDeviceSize floats = VkDeviceSize{n} * 4;
    for (Buffer* b : {&s.x, &s.v}) recreateStorageBuffer(d, *b, 3 * floats);  // room for 3D
    for (Buffer* b : {&s.p, &s.counts, &s.first}) recreateStorageBuffer(d, *b, floats);
    for (Buffer* b : {&s.constraints, &s.warm}) recreateStorageBuffer(d, *b, 4 * floats);
    recreateStorageBuffer(d, s.tiles, (VkDeviceSize{n} + kWorkgroup - 1) / kWorkgroup * 4);
    recreateStorageBuffer(d, s.header, sizeof(FluidSetupHeader));
    s.capacity = n;
}

void writeSet(GpuFluidSetup& s, const GpuFluidGrid& grid, const FluidSetupInputs& in) {
    std::array<const Buffer*, kBindings> buffers{};
    buffers[kernels::SD_FLUID_SETUP_BINDING_ORDER] = &gridOrder(grid);
    buffers[kernels::SD_FLUID_SETUP_BINDING_SORTED_KEYS] = &grid.sort->keys[grid.sortedPair];
    buffers[kernels::SD_FLUID_SETUP_BINDING_KEY_START] = &gridKeyStart(grid);
    buffers[kernels::SD_FLUID_SETUP_BINDING_POSITIONS] = in.positions;
    buffers[kernels::SD_FLUID_SETUP_BINDING_VELOCITIES] = in.velocities;
    buffers[kernels::SD_FLUID_SETUP_BINDING_PRESSURES] = in.pressures;
    buffers[kernels::SD_FLUID_SETUP_BINDING_X] = &s.x;
    buffers[kernels::SD_FLUID_SETUP_BINDING_V] = &s.v;
    buffers[kernels::SD_FLUID_SETUP_BINDING_P] = &s.p;
    buffers[kernels::SD_FLUID_SETUP_BINDING_WALL] = in.wall;
    buffers[kernels::SD_FLUID_SETUP_BINDING_COUNTS] = &s.counts;
    buffers[kernels::SD_FLUID_SETUP_BINDING_TILES] = &s.tiles;
    buffers[kernels::SD_FLUID_SETUP_BINDING_HEADER] = &s.header;
    buffers[kernels::SD_FLUID_SETUP_BINDING_FIRST] = &s.first;
    buffers[kernels::SD_FLUID_SETUP_BINDING_LIST_INDEX] = &s.listIndex;
    buffers[kernels::SD_FLUID_SETUP_BINDING_CONSTRAINTS] = &s.constraints;
    buffers[kernels::SD_FLUID_SETUP_BINDING_WARM] = &s.warm;
    writeStorageSet(*s.device, s.passes.sets[0], buffers);
}

// Throws unless `b` holds `bytes`.
}  // namespace

GpuFluidSetup::~GpuFluidSetup() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    Device& d = *device;
    for (Buffer* b : {&x, &v, &p, &counts, &first, &constraints, &warm, &tiles, &header, &listIndex}) {
        destroyBuffer(d, *b);
    }
    destroyComputePasses(d, passes);
}

std::unique_ptr<GpuFluidSetup> createGpuFluidSetup(Device& d) {
    auto s = std::make_unique<GpuFluidSetup>();  // destroys what was made if a step throws
    s->device = &d;
    createComputePasses(d, kBindings, sizeof(FluidSetupPush), 1, std::span(shaders::kFluidSetup, shaders::kFluidSetupWords),
                        4, "fluid_setup", s->passes);
    reserveParticles(*s, 1);
    reserveFluidLists(*s, kWorkgroup);
    return s;
}

void reserveFluidLists(GpuFluidSetup& s, std::uint32_t entries) {
    if (entries <= s.listCapacity) {
        return;
    }
    recreateStorageBuffer(*s.device, s.listIndex, VkDeviceSize{entries} * 4);
    s.listCapacity = entries;
}

void recordFluidGather(VkCommandBuffer cmd, GpuFluidSetup& s, const GpuFluidGrid& grid, const FluidSetupInputs& in,
                       const FluidSetupParams& params) {
    const std::uint32_t n = in.count;
    const std::uint32_t dimension = grid.dimension;
    if (n != grid.count) {
        throw Error(fmt::format("gpu fluid setup: {} particles, but the grid holds {}", n, grid.count));
    }
    requireBufferBytes(in.positions, VkDeviceSize{n} * dimension * 4, "gpu fluid setup", "positions");
    requireBufferBytes(in.velocities, VkDeviceSize{n} * dimension * 4, "gpu fluid setup", "velocities");
    requireBufferBytes(in.pressures, VkDeviceSize{n} * 4, "gpu fluid setup", "pressures");
    requireBufferBytes(in.wall, VkDeviceSize{n} * 16, "gpu fluid setup", "wall");
    const std::uint32_t groups = workgroupsFor(*s.device, n, kWorkgroup, "gpu fluid setup", "particles");
    reserveParticles(s, n);
    const std::uint64_t room = std::uint64_t{n} * (dimension == 2 ? kEntriesPerParticle2D : kEntriesPerParticle3D);
    reserveFluidLists(s, static_cast<std::uint32_t>(std::min<std::uint64_t>(room, 0x3FFFFFFFu)));
    s.count = n;
    s.dimension = dimension;
    s.groups = groups;
    writeSet(s, grid, in);

    FluidSetupPush push{};
    push.cells = glm::ivec4(grid.cells, static_cast<int>(dimension));
    push.velocityChange = glm::vec4(params.velocityChange, 0.0f);
    push.count = n;
    push.warmCap = params.warmCap;
    // The inputs' writers (a step's pass, an upload) and the last reader of
    // the header, before the header is cleared and the gather reads.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT |
                      VK_ACCESS_TRANSFER_READ_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, s.header.buffer, 0, sizeof(FluidSetupHeader), 0u);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    if (n > 0) {
        dispatchCompute(cmd, s.passes.pipelines[kernels::SD_FLUID_SETUP_PASS_GATHER], s.passes.pipelineLayout, s.passes.sets[0], &push,
                        sizeof(push), groups);
    }
    computeToCompute(cmd);
}

void recordFluidConstraints(VkCommandBuffer cmd, GpuFluidSetup& s, const GpuFluidGrid& grid,
                            const FluidSetupParams& params) {
    // The constants as the CPU's setupConstraints computes them.
    FluidSetupPush push{};
    push.cells = glm::ivec4(grid.cells, static_cast<int>(s.dimension));
    push.count = s.count;
    push.readLimit = params.readLimit;
    push.cap = params.cap;
    push.listCapacity = s.listCapacity;
    push.h = params.h;
    push.h2 = params.h * params.h;
    push.invH = 1.0f / params.h;
    push.invH2 = 1.0f / push.h2;
    push.restDensity = params.restDensity;
    push.baumgarte = params.baumgarte;
    push.invDt = 1.0f / params.dt;
    push.warmFraction = params.warmFraction;
    push.countClosing = params.countClosing ? 1u : 0u;
    push.invRest = 1.0f / params.restDensity;
    push.tiles = s.groups;
    push.relaxation = params.relaxation;
    computeToCompute(cmd);  // the gather's and the contacts' writes
    if (s.count > 0) {
        for (std::uint32_t pass = kernels::SD_FLUID_SETUP_PASS_COUNT; pass < 4; ++pass) {
            const std::uint32_t passGroups = pass == kernels::SD_FLUID_SETUP_PASS_TILES ? 1u : s.groups;
            dispatchCompute(cmd, s.passes.pipelines[pass], s.passes.pipelineLayout, s.passes.sets[0], &push, sizeof(push), passGroups);
            computeToCompute(cmd);
        }
    }
    // The results for whoever reads them next: a compute pass or a copy.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

void recordFluidSetup(VkCommandBuffer cmd, GpuFluidSetup& s, const GpuFluidGrid& grid, const FluidSetupInputs& in,
                      const FluidSetupParams& params) {
    recordFluidGather(cmd, s, grid, in, params);
    recordFluidConstraints(cmd, s, grid, params);
}

FluidSetupReadback readFluidSetup(GpuFluidSetup& s) {
    Device& d = *s.device;
    FluidSetupReadback r;
    const std::vector<FluidSetupHeader> header = downloadArray<FluidSetupHeader>(d, s.header, 1);
    r.entries = header[0].entries;
    r.overflows = header[0].overflows;
    const std::size_t n = s.count;
    r.x = downloadArray<float>(d, s.x, n * s.dimension);
    r.v = downloadArray<float>(d, s.v, n * s.dimension);
    r.p = downloadArray<float>(d, s.p, n);
    r.counts = downloadArray<std::uint32_t>(d, s.counts, n);
    r.first = downloadArray<std::uint32_t>(d, s.first, n);
    r.constraints = downloadArray<glm::vec4>(d, s.constraints, n);
    r.warm = downloadArray<glm::vec4>(d, s.warm, n);
    const std::size_t written = std::min(r.entries, s.listCapacity);
    r.listIndex = downloadArray<std::uint32_t>(d, s.listIndex, written);
    return r;
}

}  // namespace spindrift::gpu
