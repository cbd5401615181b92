// Fluid splats (see splat_pass.h).
#include "render/splat_pass.h"

#include "render/surface_field.h"

#include <spindrift/fluid.h>

#include <cstring>

namespace spindrift::render {
namespace {

void bindSplatBuffer(Renderer& r) {
    VkDescriptorBufferInfo info{r.splatBuffer.buffer, 0, VK_WHOLE_SIZE};
    auto w = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = r.splatSet;
    w.dstBinding = 0;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &info;
    vkUpdateDescriptorSets(r.device->device, 1, &w, 0, nullptr);
}

// Room for `count` instances; the renderer waits for each frame, so the old
// buffer is not in use when it is replaced.
void reserve(Renderer& r, std::size_t count) {
    const VkDeviceSize bytes = std::max<VkDeviceSize>(count, 1024) * sizeof(SplatInstance);
    if (r.splatBuffer.buffer != VK_NULL_HANDLE && r.splatBuffer.size >= bytes) {
        return;
    }
    if (r.splatBuffer.buffer != VK_NULL_HANDLE) {
        gpu::destroyBuffer(*r.device, r.splatBuffer);
    }
    r.splatBuffer = gpu::createHostStorageBuffer(*r.device, bytes + bytes / 2);  // head room: jets keep adding
    bindSplatBuffer(r);
}

}  // namespace

void prepareSplats(Renderer& r, float dt) {
    const std::uint32_t fluids = fluidCount(r.world);
    r.fluids.resize(fluids);
    std::size_t total = 0;
    for (std::uint32_t f = 0; f < fluids; ++f) {
        SplatFluid& sf = r.fluids[f];
        const FluidId id{f + 1};
        const bool liquid = r.def.fluid.style == FluidStyle::Surface;
        const std::uint32_t dimension = fluidDimension(r.world, id);
        sf.surface = liquid && dimension == 2;
        sf.screen = liquid && dimension == 3;
        sf.spacing = fluidSpacing(r.world, id);
        if (sf.surface || sf.screen) {
            // The splat rules give the splashes; the water's instances are
            // then replaced by the surface's kernels.
            FluidRenderDef splashesOnly = FluidRenderDef::upTo(1);
            splashesOnly.splashes = r.def.fluid.splashes;
            updateFluidSplats(sf.state, r.world, id, splashesOnly, dt, sf.instances);
            sf.particles = static_cast<std::uint32_t>(
                sf.surface ? surfaceInstances(r.world, id, r.def.fluid.stretch, sf.instances)
                           : screenFluidInstances(r.world, id, sf.instances));
        } else {
            updateFluidSplats(sf.state, r.world, id, r.def.fluid, dt, sf.instances);
            sf.particles = 0;
        }
        sf.first = static_cast<std::uint32_t>(total);
        total += sf.instances.size();
    }
    reserve(r, total);
    auto* out = static_cast<SplatInstance*>(r.splatBuffer.mapped);
    for (const SplatFluid& f : r.fluids) {
        if (!f.instances.empty()) {
            std::memcpy(out, f.instances.data(), f.instances.size() * sizeof(SplatInstance));
            out += f.instances.size();
        }
    }
    r.splatCount = static_cast<std::uint32_t>(total);
    r.stats.splats = total;
}

void recordSplats(Renderer& r, VkCommandBuffer cmd) {
    if (r.splatCount == 0) {
        return;
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.splats.pipeline);
    VkDescriptorSet sets[2] = {r.frameSet, r.splatSet};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.splats.layout, 0, 2, sets, 0, nullptr);
    // A liquid's water is drawn by its own passes (surface_pass.cpp in 2D,
    // screen_fluid_pass.cpp in 3D); its splashes are splats.
    for (const SplatFluid& f : r.fluids) {
        const auto count = static_cast<std::uint32_t>(f.instances.size()) - f.particles;
        if (count > 0) {
            vkCmdDraw(cmd, 6, count, 0, f.first + f.particles);
        }
    }
}

void destroySplats(Renderer& r) {
    if (r.splatBuffer.buffer != VK_NULL_HANDLE) {
        gpu::destroyBuffer(*r.device, r.splatBuffer);
    }
    r.fluids.clear();
}

}  // namespace spindrift::render
