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

namespace spindrift::gpu {
namespace {

// Bindings, passes and push constants of fluid_contacts.comp: src/kernels/layout.glsl.
constexpr std::uint32_t kBindings = kernels::SD_FLUID_CONTACTS_BINDINGS;
constexpr std::uint32_t kWorkgroup = kernels::SD_FLUID_CONTACTS_WORKGROUP;
using kernels::FluidContactsPush;

// Uploads `bytes` of `data` into `b`, grown to hold them (16 bytes at least:
// an empty list still binds a buffer).
void uploadInto(Device& d, Buffer& b, const void* data, VkDeviceSize bytes) {
    if (b.buffer == VK_NULL_HANDLE || b.size < std::max<VkDeviceSize>(bytes, 16u)) {
        recreateStorageBuffer(d, b, bytes);
    }
    if (bytes > 0) {
        const Transfer t{&b, const_cast<void*>(data), bytes};
        upload(d, std::span(&t, 1));
    }
}

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
    return push;
}

}  // namespace

GpuFluidContacts::~GpuFluidContacts() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    for (Buffer* b : {&colliders, &polygons, &wallTable, &masks}) destroyBuffer(*device, *b);
    destroyComputePasses(*device, passes);
}

std::unique_ptr<GpuFluidContacts> createGpuFluidContacts(Device& d) {
    auto c = std::make_unique<GpuFluidContacts>();  // destroys what was made if a step throws
    c->device = &d;
    createComputePasses(d, kBindings, sizeof(FluidContactsPush), 2,
                        std::span(shaders::kFluidContacts, shaders::kFluidContactsWords), 2, "fluid_contacts",
                        c->passes);
    const glm::vec2 empty[2] = {glm::vec2(0.0f), glm::vec2(0.0f)};
    setFluidSurfaces(*c, {{}, {}, empty, 0.0f, 1.0f});
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
    uploadInto(d, c.colliders, surfaces.colliders.data(), surfaces.colliders.size_bytes());
    uploadInto(d, c.polygons, surfaces.polygons.data(), surfaces.polygons.size_bytes());
    uploadInto(d, c.wallTable, surfaces.wallTable.data(), surfaces.wallTable.size_bytes());
    c.colliderCount = static_cast<std::uint32_t>(surfaces.colliders.size());
    c.polygonCount = static_cast<std::uint32_t>(surfaces.polygons.size());
    c.tableSize = static_cast<std::uint32_t>(surfaces.wallTable.size());
    c.tableStart = surfaces.tableStart;
    c.tableStep = surfaces.tableStep;
}

void recordFluidContactsFind(VkCommandBuffer cmd, GpuFluidContacts& c, const GpuFluidSetup& setup, Buffer& wall,
                             const FluidContactParams& params) {
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
    // The solve pass's set names the masks too; it is written when a solve
    // is recorded. Here the motion binding is a placeholder (not read).
    writeSet(c, c.passes.sets[0], setup.x, setup.v, wall, c.masks);
    const FluidContactsPush push = pushOf(c);
    computeToCompute(cmd);  // the gather
    if (n > 0) {
        dispatchCompute(cmd, c.passes.pipelines[kernels::SD_FLUID_CONTACTS_PASS_FIND], c.passes.pipelineLayout,
                        c.passes.sets[0], &push, sizeof(push), groups);
    }
    computeToCompute(cmd);
}

void recordFluidContactsSolve(VkCommandBuffer cmd, GpuFluidContacts& c, const Buffer& motion, bool firstAfterFind) {
    if (c.count == 0 || c.colliderCount + c.polygonCount == 0) {
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
}

}  // namespace spindrift::gpu
