// Fluid splats (see splat_pass.h).
#include "render/splat_pass.h"

#include "fluid/fluid_state.h"
#include "render/surface_field.h"
#include "world/device_fluid.h"
#include "world/world.h"

#include <spindrift/fluid.h>

#include <algorithm>
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

/// Whether fluid `id`'s water is drawn from the device's buffers: a fluid
/// the device solves, unless the renderer is told to read it back.
DeviceFluid* drawnFromDevice(const Renderer& r, FluidId id) {
    return r.drawDeviceWater ? deviceFluidFromId(worldFromId(r.world), id) : nullptr;
}

/// The wall planes that may mirror some particle of `g` (its box, as its
/// last substep reported it, reaches within a kernel radius in front of
/// them): the others' slots would all be radius 0. Each a point, then the
/// unit normal, in the colliders' order.
std::vector<glm::vec4> planesNear(const Renderer& r, const SplatFluid& sf, const DeviceFluid& g) {
    std::vector<glm::vec4> near;
    if (!sf.surface) return near;
    const DeviceFluidExtent box = deviceFluidExtent(g);
    const float radius = kSurfaceKernelSpacings * sf.spacing;
    const std::vector<glm::vec4> planes = wallPlanes(worldFromId(r.world));
    for (std::size_t p = 0; p + 1 < planes.size(); p += 2) {
        const glm::vec3 point(planes[p]), normal(planes[p + 1]);
        // The distance is linear in x: its extremes over the box are at
        // its corners, the low or the high end along each axis.
        float lowest = 0.0f, highest = 0.0f;
        for (int a = 0; a < 3; ++a) {
            const float low = (box.low[a] - point[a]) * normal[a], high = (box.high[a] - point[a]) * normal[a];
            lowest += std::min(low, high);
            highest += std::max(low, high);
        }
        // A margin of a thousandth of the radius: the sums above round
        // otherwise than the pass's dot product.
        if (highest < -1e-3f * radius || lowest >= radius * 1.001f) continue;
        near.push_back(planes[p]);
        near.push_back(planes[p + 1]);
    }
    return near;
}

/// The water of fluid `id`, on the device, drawn from its buffers: its
/// instances' count (the particles, and in the surface style a slot per
/// particle and nearby wall plane for the mirror images).
std::uint32_t deviceWaterSlots(const Renderer& r, const SplatFluid& sf, const DeviceFluid& g) {
    return deviceWaterInstances(deviceFluidBuffers(g).count, planesNear(r, sf, g).size() / 2);
}

/// Writes fluid `id`'s water on the device at sf.first and its splashes into
/// sf.instances, from the particles that throw one (read back, 48 bytes
/// each); more throwers than the list holds, and the particles are read back
/// for them as for a CPU fluid.
void drawWaterFromDevice(Renderer& r, SplatFluid& sf, FluidId id, DeviceFluid& g, float dt) {
    const World& world = worldFromId(r.world);
    const fluid::FluidState& f = fluidSettingsFromId(world, id);
    const DeviceFluidBuffers buffers = deviceFluidBuffers(g);
    const bool splats = !sf.surface && !sf.screen;
    DeviceWaterJob job;
    job.first = sf.first;
    job.style = sf.surface  ? kernels::SD_FLUID_WATER_SURFACE
                : sf.screen ? kernels::SD_FLUID_WATER_SCREEN
                            : kernels::SD_FLUID_WATER_SPLATS;
    job.stretch = r.def.fluid.stretch;
    job.radius = (sf.surface ? kSurfaceKernelSpacings : kScreenSphereSpacings) * sf.spacing;
    job.planes = planesNear(r, sf, g);
    job.splashes = r.def.fluid.splashes && dt > 0.0f;
    job.frame = sf.state.frame;
    job.up = splashUp(r.world, id);
    job.chance = splashChance(dt);
    // The splats' own rules take the splash's settings as the liquid's
    // splashes do: the liquid styles draw splashes as raw splats.
    FluidRenderDef splashSettings = FluidRenderDef::upTo(1);
    splashSettings.splashes = r.def.fluid.splashes;
    if (splats) {
        splashSettings = r.def.fluid;
        job.steps = splatSteps(r.def.fluid, splatRadius(r.def.fluid, sf.spacing), job.up, dt, f.def.dimension);
        job.invH2 = 1.0f / (f.h * f.h);
        job.shown = &sf.shownOnDevice;
        job.serials = f.nextSerial;
    }
    const SplashThrowers thrown = buildDeviceWater(*r.device, r.deviceWater, buffers, r.splatBuffer, job);
    if (thrown.complete) {
        updateSplashes(sf.state, r.world, id, splashSettings, dt, thrown.throwers, sf.instances);
        return;
    }
    updateFluidSplats(sf.state, r.world, id, splashSettings, dt, sf.instances);
    sf.instances.erase(sf.instances.begin(), sf.instances.begin() + static_cast<std::ptrdiff_t>(buffers.count));
}

}  // namespace

void prepareSplats(Renderer& r, float dt) {
    const std::uint32_t fluids = fluidCount(r.world);
    r.fluids.resize(fluids);
    std::vector<DeviceFluid*> fromDevice(fluids, nullptr);  // fluids drawn from the device's buffers
    std::size_t total = 0;
    for (std::uint32_t f = 0; f < fluids; ++f) {
        SplatFluid& sf = r.fluids[f];
        const FluidId id{f + 1};
        const bool liquid = r.def.fluid.style == FluidStyle::Surface;
        const std::uint32_t dimension = fluidDimension(r.world, id);
        sf.surface = liquid && dimension == 2;
        sf.screen = liquid && dimension == 3;
        sf.spacing = fluidSpacing(r.world, id);
        sf.first = static_cast<std::uint32_t>(total);
        sf.onDevice = 0;
        DeviceFluid* g = drawnFromDevice(r, id);
        if (g != nullptr) {
            // Drawn below, once the buffer has room: the water, and at most
            // every splash alive after it.
            fromDevice[f] = g;
            sf.onDevice = deviceWaterSlots(r, sf, *g);
            sf.particles = sf.surface || sf.screen ? sf.onDevice : 0;  // splats: every instance a splat
            sf.instances.clear();
            total += sf.onDevice + kMaxSplashes;
            continue;
        }
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
        total += sf.instances.size();
    }
    reserve(r, total);
    std::size_t drawn = 0;
    for (std::uint32_t f = 0; f < fluids; ++f) {
        SplatFluid& sf = r.fluids[f];
        if (fromDevice[f] != nullptr) drawWaterFromDevice(r, sf, FluidId{f + 1}, *fromDevice[f], dt);
        auto* out = static_cast<SplatInstance*>(r.splatBuffer.mapped) + sf.first + sf.onDevice;
        if (!sf.instances.empty()) std::memcpy(out, sf.instances.data(), sf.instances.size() * sizeof(SplatInstance));
        drawn += sf.onDevice + sf.instances.size();
    }
    r.splatCount = static_cast<std::uint32_t>(total);
    r.stats.splats = drawn;
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
        const auto count = static_cast<std::uint32_t>(f.onDevice + f.instances.size()) - f.particles;
        if (count > 0) {
            vkCmdDraw(cmd, 6, count, 0, f.first + f.particles);
        }
    }
}

void destroySplats(Renderer& r) {
    destroyDeviceWater(*r.device, r.deviceWater);
    for (SplatFluid& f : r.fluids) gpu::destroyBuffer(*r.device, f.shownOnDevice);
    if (r.splatBuffer.buffer != VK_NULL_HANDLE) {
        gpu::destroyBuffer(*r.device, r.splatBuffer);
    }
    r.fluids.clear();
}

}  // namespace spindrift::render
