// Effect emitters as sprites, straight from the particle buffers (see
// sprite_pass.h). A Vulkan world's emitters are drawn from the world's own
// device buffers; a CPU world's are written into host-visible buffers of the
// same layout once per frame, so one vertex shader serves both.
#include "render/sprite_pass.h"

#include "effects/stateless.h"
#include "world/world.h"
#include "gpu/gpu_world.h"
#include "gpu/vulkan_pipeline.h"
#include "particles/params.h"
#include "render/render_images.h"

#include <spindrift/effects.h>

#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cstring>

namespace spindrift::render {
namespace {

// Push constants, modes and bindings of sprites.vert / sprites.frag:
// src/kernels/layout.glsl, which the shaders include.
using kernels::SpriteDraw;
constexpr std::uint32_t kModeSlots = kernels::SD_SPRITE_MODE_SLOTS;
constexpr std::uint32_t kModeOrdered = kernels::SD_SPRITE_MODE_ORDERED;
constexpr std::uint32_t kModeStateless = kernels::SD_SPRITE_MODE_STATELESS;

void writeSet(gpu::Device& d, VkDescriptorSet set, std::span<const gpu::Buffer* const> buffers, VkImageView image,
              VkSampler sampler) {
    std::vector<VkDescriptorBufferInfo> infos(buffers.size());
    std::vector<VkWriteDescriptorSet> writes;
    for (std::uint32_t i = 0; i < buffers.size(); ++i) {
        infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
        auto w = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        w.dstSet = set;
        w.dstBinding = i;
        w.descriptorCount = 1;
        w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        w.pBufferInfo = &infos[i];
        writes.push_back(w);
    }
    VkDescriptorImageInfo imageInfo{sampler, image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    auto w = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.dstBinding = static_cast<std::uint32_t>(buffers.size());
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &imageInfo;
    writes.push_back(w);
    vkUpdateDescriptorSets(d.device, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

// Host-visible copies of a CPU world emitter's slots (or nothing to store
// for a stateless one: its runs).
void createOwnBuffers(gpu::Device& d, SpriteEmitter& s, const EmitterState& e) {
    s.params = gpu::createHostStorageBuffer(d, sizeof(kernels::EmitterParams));
    std::memcpy(s.params.mapped, &e.params, sizeof(kernels::EmitterParams));
    const VkDeviceSize n = s.stateless ? 1 : s.capacity;
    s.positions = gpu::createHostStorageBuffer(d, n * 12);
    s.velocities = gpu::createHostStorageBuffer(d, n * 12);
    s.ages = gpu::createHostStorageBuffer(d, n * 4);
    s.births = gpu::createHostStorageBuffer(d, n * 4);
    s.rotations = gpu::createHostStorageBuffer(d, n * 4);
    s.trail = gpu::createHostStorageBuffer(d, std::max<VkDeviceSize>(n * s.trailPoints, 1) * 12);
}

// The trail's width and colour over its length (a placeholder without one).
void writeTrailLook(gpu::Device& d, SpriteEmitter& s, const TrailDef& trail) {
    kernels::TrailLook look{};
    look.widthOverLength = makeCurveParams(trail.widthOverLength);
    look.colorOverLength = makeCurveParams(trail.colorOverLength);
    look.width = trail.width;
    s.trailLook = gpu::createHostStorageBuffer(d, sizeof(look));
    std::memcpy(s.trailLook.mapped, &look, sizeof(look));
}

}  // namespace

void createSpriteEmitters(Renderer& r) {
    gpu::Device& d = *r.device;
    World& w = worldFromId(r.world);
    for (std::size_t i = 0; i < w.emitters.size(); ++i) {
        const EmitterState& e = *w.emitters[i];
        SpriteEmitter& s = r.emitters.emplace_back();
        s.index = i;
        s.stateless = e.def.stateless;
        s.blend = e.def.sprite.blend;
        s.alpha = s.blend == SpriteBlend::Alpha;
        s.capacity = e.def.capacity;
        s.stretch = e.def.sprite.stretch;
        s.flipbook = e.def.sprite.flipbook;
        s.softDistance = e.def.sprite.softDistance;
        s.trailPoints = e.def.trail.points;
        const bool onDevice = w.gpu && !s.stateless;
        if (!onDevice) {
            createOwnBuffers(d, s, e);
        }
        s.runs = gpu::createHostStorageBuffer(d, (1 + e.def.bursts.size()) * 16);
        writeTrailLook(d, s, e.def.trail);
        if (s.alpha && !s.stateless) {
            s.order = gpu::createBuffer(d, VkDeviceSize{s.capacity} * 4,
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        } else {
            s.order = gpu::createHostStorageBuffer(d, 4);
        }
        if (!e.def.sprite.texture.empty()) {
            s.texture = loadImage(d, e.def.sprite.texture, fmt::format("emitter '{}' sprite", e.def.name));
            s.ownTexture = true;
        }
        auto alloc = gpu::vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
        alloc.descriptorPool = r.pool;
        alloc.descriptorSetCount = 1;
        alloc.pSetLayouts = &r.spriteLayout;
        gpu::check(vkAllocateDescriptorSets(d.device, &alloc, &s.set), "vkAllocateDescriptorSets");
        const gpu::GpuEmitter* g = onDevice ? w.gpu->emitters[i].get() : nullptr;
        std::array<const gpu::Buffer*, kernels::SD_SPRITE_BUFFERS> buffers{};
        buffers[kernels::SD_SPRITE_BINDING_EMITTER] = g ? &g->params : &s.params;
        buffers[kernels::SD_SPRITE_BINDING_POSITIONS] = g ? &g->positions : &s.positions;
        buffers[kernels::SD_SPRITE_BINDING_VELOCITIES] = g ? &g->velocities : &s.velocities;
        buffers[kernels::SD_SPRITE_BINDING_AGES] = g ? &g->ages : &s.ages;
        buffers[kernels::SD_SPRITE_BINDING_BIRTHS] = g ? &g->births : &s.births;
        buffers[kernels::SD_SPRITE_BINDING_ROTATIONS] = g ? &g->rotations : &s.rotations;
        buffers[kernels::SD_SPRITE_BINDING_ORDER] = &s.order;
        buffers[kernels::SD_SPRITE_BINDING_RUNS] = &s.runs;
        buffers[kernels::SD_SPRITE_BINDING_TRAILS] = g ? &g->trail : &s.trail;
        buffers[kernels::SD_SPRITE_BINDING_TRAIL_LOOK] = &s.trailLook;
        writeSet(d, s.set, buffers, s.ownTexture ? s.texture.view : r.placeholderImage.view, r.linearSampler);
    }
}

void destroySpriteEmitters(Renderer& r) {
    gpu::Device& d = *r.device;
    for (SpriteEmitter& s : r.emitters) {
        for (gpu::Buffer* b : {&s.params, &s.positions, &s.velocities, &s.ages, &s.births, &s.rotations, &s.runs,
                               &s.trail, &s.trailLook, &s.order}) {
            if (b->buffer != VK_NULL_HANDLE) {
                gpu::destroyBuffer(d, *b);
            }
        }
        if (s.ownTexture) {
            gpu::destroyImage(d, s.texture);
        }
    }
    r.emitters.clear();
}

namespace {

void uploadSlots(SpriteEmitter& s, const EmitterState& e) {
    const ParticleArrays& p = e.particles;
    const std::size_t n = std::min<std::size_t>(s.capacity, p.position.size());
    std::memcpy(s.positions.mapped, p.position.data(), n * 12);
    std::memcpy(s.velocities.mapped, p.velocity.data(), n * 12);
    std::memcpy(s.ages.mapped, p.age.data(), n * 4);
    std::memcpy(s.births.mapped, p.birth.data(), n * 4);
    std::memcpy(s.rotations.mapped, p.rotation.data(), n * 4);
    if (s.trailPoints > 0) {
        std::memcpy(s.trail.mapped, p.trail.data(), std::min(p.trail.size(), n * s.trailPoints) * 12);
    }
    static_assert(sizeof(glm::vec3) == 12);
}

// The runs as sprites.vert reads them: first serial, instances before the
// run, age of its first serial and the birth interval (float bits).
std::uint32_t writeRuns(SpriteEmitter& s, const EmitterDef& def, double t) {
    std::vector<StatelessRun> runs = statelessRuns(def, t);
    auto* out = static_cast<std::uint32_t*>(s.runs.mapped);
    std::uint32_t before = 0;
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const float age = static_cast<float>(t - runs[k].bornAt(0));
        const float interval = runs[k].rate > 0.0 ? static_cast<float>(1.0 / runs[k].rate) : 0.0f;
        out[4 * k] = runs[k].firstSerial;
        out[4 * k + 1] = before;
        std::memcpy(&out[4 * k + 2], &age, 4);
        std::memcpy(&out[4 * k + 3], &interval, 4);
        before += runs[k].count;
    }
    s.runCount = static_cast<std::uint32_t>(runs.size());
    return before;
}

// Back to front on the device, into the emitter's order buffer: one
// submission per emitter (a GpuSort records one sort per submission).
void sortBackToFront(Renderer& r, SpriteEmitter& s, const gpu::Buffer& positions, const gpu::Buffer& ages) {
    gpu::Device& d = *r.device;
    if (!r.sort) {
        r.sort = gpu::createGpuSort(d);
    }
    gpu::SortInput input;
    input.positions = &positions;
    input.ages = &ages;
    input.count = s.capacity;
    input.eye = r.def.camera.eye;
    input.forward = glm::normalize(r.def.camera.target - r.def.camera.eye);
    gpu::submitOnce(d, [&](VkCommandBuffer cmd) {
        gpu::recordSortBackToFront(*r.sort, cmd, input);
        VkBufferCopy region{0, 0, VkDeviceSize{s.capacity} * 4};
        vkCmdCopyBuffer(cmd, gpu::sortedIndices(*r.sort).buffer, s.order.buffer, 1, &region);
        gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                           VK_PIPELINE_STAGE_VERTEX_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    });
}

}  // namespace

void prepareSprites(Renderer& r) {
    World& w = worldFromId(r.world);
    r.stats.sprites = 0;
    r.stats.sortMs = 0.0;
    for (SpriteEmitter& s : r.emitters) {
        const EmitterState& e = *w.emitters[s.index];
        if (s.stateless) {
            s.instances = writeRuns(s, e.def, w.time);
            r.stats.sprites += s.instances;
            continue;
        }
        const gpu::GpuEmitter* g = w.gpu ? w.gpu->emitters[s.index].get() : nullptr;
        if (!g) {
            // The parameters too: setEmitterSpeed and the like change them
            // during a run (a few hundred bytes).
            std::memcpy(s.params.mapped, &e.params, sizeof(kernels::EmitterParams));
            uploadSlots(s, e);
        }
        s.instances = s.capacity;
        s.trailHead = e.trailHead;
        r.stats.sprites += e.alive;
        if (s.alpha && s.capacity > 0) {
            auto start = std::chrono::steady_clock::now();
            sortBackToFront(r, s, g ? g->positions : s.positions, g ? g->ages : s.ages);
            r.stats.sortMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        }
    }
}

namespace {

SpriteDraw spriteDraw(const SpriteEmitter& s) {
    SpriteDraw draw{};
    draw.mode = s.stateless ? kModeStateless : (s.alpha ? kModeOrdered : kModeSlots);
    draw.runCount = s.runCount;
    draw.stretch = s.stretch;
    draw.textured = s.ownTexture ? 1u : 0u;
    draw.columns = s.flipbook.columns;
    draw.rows = s.flipbook.rows;
    draw.frames = s.flipbook.frameCount();
    draw.fps = s.flipbook.fps;
    draw.blendFrames = s.flipbook.blend ? 1u : 0u;
    draw.softDistance = s.softDistance;
    return draw;
}

}  // namespace

void recordSpriteGroup(Renderer& r, VkCommandBuffer cmd, const Pipeline& hard, const Pipeline& soft,
                       SpriteBlend blend) {
    const Pipeline* bound = nullptr;
    for (const SpriteEmitter& s : r.emitters) {
        if (s.blend != blend || s.instances == 0) {
            continue;
        }
        const Pipeline& p = s.softDistance > 0.0f ? soft : hard;
        if (bound != &p) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 0, 1, &r.frameSet, 0, nullptr);
            bound = &p;
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p.layout, 1, 1, &s.set, 0, nullptr);
        SpriteDraw draw = spriteDraw(s);
        vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(draw),
                           &draw);
        vkCmdDraw(cmd, 6, s.instances, 0, 0);
        if (s.trailPoints > 0) {
            // The ribbons, in the same order and blend: 6 vertices a segment.
            draw.trailPoints = s.trailPoints;
            draw.trailHead = s.trailHead;
            draw.textured = 0u;
            vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(draw), &draw);
            vkCmdDraw(cmd, 6 * (s.trailPoints - 1), s.instances, 0, 0);
        }
    }
}

void recordSprites(Renderer& r, VkCommandBuffer cmd) {
    recordSpriteGroup(r, cmd, r.spritesAdditive, r.spritesAdditiveSoft, SpriteBlend::Additive);
    recordSpriteGroup(r, cmd, r.spritesAlpha, r.spritesAlphaSoft, SpriteBlend::Alpha);
}

}  // namespace spindrift::render
