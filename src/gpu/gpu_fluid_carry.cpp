// The carry after Box2D's step on the device: pipeline and dispatch of
// fluid_carry.comp (see gpu_fluid_carry.h).
#include "gpu/gpu_fluid_carry.h"

#include "gpu/gpu_fluid_integrate.h"
#include "gpu/shaders.h"

#include <algorithm>
#include <array>

namespace spindrift::gpu {
namespace {

constexpr std::uint32_t kBindings = kernels::SD_FLUID_CARRY_BINDINGS;
constexpr std::uint32_t kWorkgroup = kernels::SD_FLUID_CARRY_WORKGROUP;

}  // namespace

GpuFluidCarry::~GpuFluidCarry() {
    if (device == nullptr || device->device == VK_NULL_HANDLE) {
        return;
    }
    for (Buffer* b : {&shapes, &boxes, &bodies, &box}) destroyBuffer(*device, *b);
    destroyComputePasses(*device, passes);
}

std::unique_ptr<GpuFluidCarry> createGpuFluidCarry(Device& d) {
    auto c = std::make_unique<GpuFluidCarry>();  // destroys what was made if a step throws
    c->device = &d;
    createComputePasses(d, kBindings, sizeof(kernels::FluidCarryPush), 1,
                        std::span(shaders::kFluidCarry, shaders::kFluidCarryWords), 1, "fluid_carry", c->passes);
    recreateStorageBuffer(d, c->box, 6 * sizeof(std::uint32_t));
    return c;
}

glm::vec4 carryOnDevice(GpuFluidCarry& c, const GpuFluidContacts& surfaces, Buffer& x, std::uint32_t count,
                        const FluidCarryInputs& inputs) {
    Device& d = *c.device;
    uploadGrowing(d, c.shapes, inputs.shapes.data(), inputs.shapes.size_bytes());
    uploadGrowing(d, c.boxes, inputs.boxes.data(), inputs.boxes.size_bytes());
    uploadGrowing(d, c.bodies, inputs.bodies.data(), inputs.bodies.size_bytes());
    std::array<const Buffer*, kBindings> buffers{};
    buffers[kernels::SD_FLUID_CARRY_BINDING_X] = &x;
    buffers[kernels::SD_FLUID_CARRY_BINDING_SHAPES] = &c.shapes;
    buffers[kernels::SD_FLUID_CARRY_BINDING_BOXES] = &c.boxes;
    buffers[kernels::SD_FLUID_CARRY_BINDING_BODIES] = &c.bodies;
    buffers[kernels::SD_FLUID_CARRY_BINDING_COLLIDERS] = &surfaces.colliders;
    buffers[kernels::SD_FLUID_CARRY_BINDING_POLYGONS] = &surfaces.polygons;
    buffers[kernels::SD_FLUID_CARRY_BINDING_BOX] = &c.box;
    writeStorageSet(d, c.passes.sets[0], buffers);
    kernels::FluidCarryPush push{};
    push.count = count;
    push.shapes = static_cast<std::uint32_t>(inputs.shapes.size());
    push.colliders = surfaces.colliderCount;
    push.polygons = surfaces.polygonCount;
    const std::uint32_t groups = workgroupsFor(d, std::max(count, 1u), kWorkgroup, "gpu fluid carry", "particles");
    submitOnce(d, [&](VkCommandBuffer cmd) {
        // The box starts empty: low keys at the most, high keys at the least.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        vkCmdFillBuffer(cmd, c.box.buffer, 0, 3 * sizeof(std::uint32_t), 0xFFFFFFFFu);
        vkCmdFillBuffer(cmd, c.box.buffer, 3 * sizeof(std::uint32_t), 3 * sizeof(std::uint32_t), 0u);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        if (count > 0) {
            dispatchCompute(cmd, c.passes.pipelines[0], c.passes.pipelineLayout, c.passes.sets[0], &push, sizeof(push),
                            groups);
        }
        memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
    });
    std::array<std::uint32_t, 6> keys{};
    const Transfer down{&c.box, keys.data(), sizeof keys};
    download(d, std::span(&down, 1));
    if (keys[0] == 0xFFFFFFFFu) return glm::vec4(3.0e38f, 3.0e38f, -3.0e38f, -3.0e38f);
    return glm::vec4(fromOrderKey(keys[0]), fromOrderKey(keys[1]), fromOrderKey(keys[3]), fromOrderKey(keys[4]));
}

}  // namespace spindrift::gpu
