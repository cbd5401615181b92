// A device fluid's liquid from the device's buffers: see device_water.h.
#include "render/device_water.h"

#include "gpu/shaders.h"
#include "world/device_fluid.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace spindrift::render {
namespace {

constexpr std::uint32_t kBindings = kernels::SD_FLUID_WATER_BINDINGS;
constexpr std::uint32_t kRoom = kernels::SD_FLUID_SPLASH_ROOM;
/// The splash list's header: the count and three pad words.
constexpr VkDeviceSize kHeaderBytes = 4 * sizeof(std::uint32_t);

void makePass(gpu::Device& d, DeviceWater& w) {
    gpu::createComputePasses(d, kBindings, sizeof(kernels::FluidWaterPush), 1,
                             std::span(gpu::shaders::kFluidWaterComp, gpu::shaders::kFluidWaterCompWords), 1,
                             "fluid_water", w.passes);
    w.splashes = gpu::createStorageBuffer(d, kHeaderBytes + kRoom * sizeof(kernels::FluidSplashThrower));
}

/// The wall planes in a host-visible buffer (at least one slot: a binding
/// needs a buffer).
void writePlanes(gpu::Device& d, DeviceWater& w, const std::vector<glm::vec4>& planes) {
    const VkDeviceSize bytes = std::max<VkDeviceSize>(planes.size(), 2) * sizeof(glm::vec4);
    if (w.planes.buffer == VK_NULL_HANDLE || w.planes.size < bytes) {
        gpu::destroyBuffer(d, w.planes);
        w.planes = gpu::createHostStorageBuffer(d, bytes);
    }
    if (!planes.empty()) std::memcpy(w.planes.mapped, planes.data(), planes.size() * sizeof(glm::vec4));
}

/// `shown` grown to hold `serials` orientations, keeping those it holds;
/// new ones are 0 (never seen). Grows by half again, so a jet's births do
/// not copy it every frame.
void growShown(gpu::Device& d, gpu::Buffer& shown, std::uint32_t serials) {
    const VkDeviceSize bytes = std::max<VkDeviceSize>(serials, 1) * sizeof(glm::vec4);
    if (shown.buffer != VK_NULL_HANDLE && shown.size >= bytes) return;
    gpu::Buffer grown = gpu::createStorageBuffer(d, bytes + bytes / 2);
    gpu::submitOnce(d, [&](VkCommandBuffer cmd) {
        VkDeviceSize kept = 0;
        if (shown.buffer != VK_NULL_HANDLE) {
            kept = shown.size;
            const VkBufferCopy region{0, 0, kept};
            vkCmdCopyBuffer(cmd, shown.buffer, grown.buffer, 1, &region);
        }
        vkCmdFillBuffer(cmd, grown.buffer, kept, VK_WHOLE_SIZE, 0u);
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    });
    gpu::destroyBuffer(d, shown);
    shown = grown;
}

}  // namespace

std::uint32_t deviceWaterInstances(std::uint32_t particles, std::size_t planes) {
    return particles * static_cast<std::uint32_t>(1 + planes);
}

SplashThrowers buildDeviceWater(gpu::Device& d, DeviceWater& w, const DeviceFluidBuffers& fluid,
                                gpu::Buffer& instances, const DeviceWaterJob& job) {
    if (w.passes.pipelines.empty()) makePass(d, w);
    const std::size_t planes = job.planes.size() / 2;
    writePlanes(d, w, job.planes);
    gpu::requireBufferBytes(&instances,
                            (VkDeviceSize{job.first} + deviceWaterInstances(fluid.count, planes)) *
                                sizeof(kernels::SplatInstance),
                            "fluid water", "splat instances");
    std::array<const gpu::Buffer*, kBindings> buffers{};
    buffers[kernels::SD_FLUID_WATER_BINDING_X] = fluid.x;
    buffers[kernels::SD_FLUID_WATER_BINDING_V] = fluid.v;
    // Without a setup's densities the binding is never read (densities 0).
    buffers[kernels::SD_FLUID_WATER_BINDING_DENSITY] = fluid.constraints != nullptr ? fluid.constraints : fluid.x;
    buffers[kernels::SD_FLUID_WATER_BINDING_IDS] = fluid.ids;
    buffers[kernels::SD_FLUID_WATER_BINDING_INSTANCES] = &instances;
    buffers[kernels::SD_FLUID_WATER_BINDING_PLANES] = &w.planes;
    buffers[kernels::SD_FLUID_WATER_BINDING_SPLASHES] = &w.splashes;
    // Bindings a style does not read hold any buffer (the positions).
    const bool splats = job.style == kernels::SD_FLUID_WATER_SPLATS;
    const bool lists = splats && fluid.list != nullptr;
    if (splats && job.shown != nullptr) growShown(d, *job.shown, job.serials);
    buffers[kernels::SD_FLUID_WATER_BINDING_COUNTS] = lists ? fluid.counts : fluid.x;
    buffers[kernels::SD_FLUID_WATER_BINDING_FIRST] = lists ? fluid.first : fluid.x;
    buffers[kernels::SD_FLUID_WATER_BINDING_LIST] = lists ? fluid.list : fluid.x;
    buffers[kernels::SD_FLUID_WATER_BINDING_SHOWN] = splats && job.shown != nullptr ? job.shown : &w.splashes;
    gpu::writeStorageSet(d, w.passes.sets[0], buffers);
    kernels::FluidWaterPush push{};
    push.up = glm::vec4(job.up, job.chance);
    push.count = fluid.count;
    push.dimension = fluid.dimension;
    push.first = job.first;
    push.style = job.style;
    push.stretch = job.stretch ? 1u : 0u;
    push.densities = fluid.constraints != nullptr ? 1u : 0u;
    push.planes = static_cast<std::uint32_t>(planes);
    push.splashes = job.splashes ? 1u : 0u;
    push.frame = job.frame;
    push.radius = job.radius;
    push.invH2 = job.invH2;
    push.lists = lists ? 1u : 0u;
    push.steps = job.steps;
    const std::uint32_t groups =
        gpu::workgroupsFor(d, std::max(fluid.count, 1u), kernels::SD_FLUID_WATER_WORKGROUP, "fluid water", "particles");
    gpu::submitOnce(d, [&](VkCommandBuffer cmd) {
        // The fluid's last step (compute) and the last frame's reads of the
        // list (transfer) before the list is cleared and the pass runs.
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
        vkCmdFillBuffer(cmd, w.splashes.buffer, 0, kHeaderBytes, 0u);
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        if (fluid.count > 0) {
            gpu::dispatchCompute(cmd, w.passes.pipelines[0], w.passes.pipelineLayout, w.passes.sets[0], &push,
                                 sizeof(push), groups);
        }
        // The instances to the frame's vertex shaders, the list to its
        // read-back.
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                           VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                           VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
    });
    SplashThrowers out;
    if (!job.splashes) return out;
    std::array<std::uint32_t, 4> header{};
    const gpu::Transfer count{&w.splashes, header.data(), kHeaderBytes};
    gpu::download(d, std::span(&count, 1));
    if (header[0] > kRoom) {
        out.complete = false;
        return out;
    }
    if (header[0] == 0) return out;
    out.throwers.resize(header[0]);
    const gpu::Transfer list{&w.splashes, out.throwers.data(), header[0] * sizeof(kernels::FluidSplashThrower),
                             kHeaderBytes};
    gpu::download(d, std::span(&list, 1));
    // Appended in any order by the invocations: the host's order is the
    // particles'.
    std::sort(out.throwers.begin(), out.throwers.end(),
              [](const kernels::FluidSplashThrower& a, const kernels::FluidSplashThrower& b) { return a.index < b.index; });
    return out;
}

void destroyDeviceWater(gpu::Device& d, DeviceWater& w) {
    gpu::destroyComputePasses(d, w.passes);
    gpu::destroyBuffer(d, w.planes);
    gpu::destroyBuffer(d, w.splashes);
    w = DeviceWater{};
}

}  // namespace spindrift::render
