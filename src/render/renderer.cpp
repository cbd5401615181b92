// The renderer: creation, the frame's uniforms and its passes (see
// renderer.h for the order). About 500 lines: the frame's pass list reads top
// to bottom here; each pass's own work is in its file (sprite_pass,
// surface_pass, oit_pass, ...).
#include "render/renderer.h"

#include "world/world.h"
#include "gpu/gpu_world.h"
#include "gpu/shaders.h"
#include "gpu/vulkan_pipeline.h"
#include "render/collider_mesh.h"
#include "render/light_pass.h"
#include "render/oit_pass.h"
#include "render/render_images.h"
#include "render/render_pipelines.h"
#include "render/splat_pass.h"
#include "render/sprite_pass.h"
#include "render/surface_field.h"
#include "render/screen_fluid_pass.h"
#include "render/surface_pass.h"

#include <spindrift/bodies.h>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstring>

namespace spindrift::render {
namespace {

// Timestamps written in a frame: start, after the liquid surface's field,
// after the background, after the colliders (end of pass A), after the copy,
// after the OIT accumulation, after the fluids (surface composite and
// splats), after the sprites (end of pass B), after bloom and the tone map.
constexpr std::uint32_t kTimestamps = 9;
// The liquid surface's depth tint reaches its deepest this far (m) below the
// water above a point.
constexpr float kSurfaceTintDepth = 0.5f;
// How far refraction moves what is seen through a splat's rim, in fractions
// of the frame (a lens, not physics: Sprinkle distorts the background).
constexpr float kRefractionStrength = 0.012f;

template <class T>
std::span<const std::uint32_t> code(const T* words, std::size_t count) {
    return {words, count};
}

VkDescriptorImageInfo materialsImage(const Renderer& r) {
    return {r.materials.sampler, r.materials.image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

void createDescriptors(Renderer& r) {
    gpu::Device& d = *r.device;
    // Bindings by number, as src/kernels/layout.glsl gives them to the shaders.
    VkDescriptorType frameTypes[kernels::SD_RENDER_FRAME_BINDINGS];
    frameTypes[kernels::SD_RENDER_BINDING_FRAME] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    frameTypes[kernels::SD_RENDER_BINDING_BACKGROUND] = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    frameTypes[kernels::SD_RENDER_BINDING_SCENE_BEHIND] = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    frameTypes[kernels::SD_RENDER_BINDING_DEPTH] = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    frameTypes[kernels::SD_RENDER_BINDING_MATERIALS] = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    r.frameLayout = createSetLayout(d, frameTypes);
    VkDescriptorType spriteTypes[kernels::SD_SPRITE_BUFFERS + 1];
    std::fill(spriteTypes, spriteTypes + kernels::SD_SPRITE_BUFFERS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    spriteTypes[kernels::SD_SPRITE_BINDING_IMAGE] = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    r.spriteLayout = createSetLayout(d, spriteTypes);
    static_assert(kernels::SD_SPLAT_BINDING_INSTANCES == 0);
    const VkDescriptorType splatTypes[1] = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    r.splatLayout = createSetLayout(d, splatTypes);

    const std::uint32_t sets = static_cast<std::uint32_t>(worldFromId(r.world).emitters.size()) + 2;
    VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4 + sets},
                                     {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kernels::SD_SPRITE_BUFFERS * sets + 1}};
    auto info = gpu::vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    info.maxSets = sets;
    info.poolSizeCount = 3;
    info.pPoolSizes = sizes;
    gpu::check(vkCreateDescriptorPool(d.device, &info, nullptr, &r.pool), "vkCreateDescriptorPool");
    VkDescriptorSetLayout layouts[2] = {r.frameLayout, r.splatLayout};
    VkDescriptorSet out[2];
    auto alloc = gpu::vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = r.pool;
    alloc.descriptorSetCount = 2;
    alloc.pSetLayouts = layouts;
    gpu::check(vkAllocateDescriptorSets(d.device, &alloc, out), "vkAllocateDescriptorSets");
    r.frameSet = out[0];
    r.splatSet = out[1];

    r.frameUniforms = gpu::createBuffer(d, sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VkDescriptorBufferInfo uniforms{r.frameUniforms.buffer, 0, VK_WHOLE_SIZE};
    VkDescriptorImageInfo background{r.linearSampler,
                                     r.def.background.kind == BackgroundKind::Image ? r.backgroundImage.view
                                                                                    : r.placeholderImage.view,
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo behind{r.linearSampler, r.target.behind.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorImageInfo depth{r.nearestSampler, r.target.depth.view, kDepthReadLayout};
    VkDescriptorImageInfo materials = materialsImage(r);
    VkWriteDescriptorSet writes[kernels::SD_RENDER_FRAME_BINDINGS];
    for (std::uint32_t i = 0; i < kernels::SD_RENDER_FRAME_BINDINGS; ++i) {
        writes[i] = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        writes[i].dstSet = r.frameSet;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = frameTypes[i];
    }
    writes[kernels::SD_RENDER_BINDING_FRAME].pBufferInfo = &uniforms;
    writes[kernels::SD_RENDER_BINDING_BACKGROUND].pImageInfo = &background;
    writes[kernels::SD_RENDER_BINDING_SCENE_BEHIND].pImageInfo = &behind;
    writes[kernels::SD_RENDER_BINDING_DEPTH].pImageInfo = &depth;
    writes[kernels::SD_RENDER_BINDING_MATERIALS].pImageInfo = &materials;
    vkUpdateDescriptorSets(d.device, kernels::SD_RENDER_FRAME_BINDINGS, writes, 0, nullptr);
}

void createPipelines(Renderer& r) {
    namespace s = gpu::shaders;
    gpu::Device& d = *r.device;
    PipelineDesc background;
    background.name = "background";
    background.vertexCode = code(s::kBackgroundVert, s::kBackgroundVertWords);
    background.fragmentCode = code(s::kBackgroundFrag, s::kBackgroundFragWords);
    background.setLayouts = {r.frameLayout};
    background.renderPass = r.passes.first;
    r.background = makePipeline(d, background);

    PipelineDesc mesh = background;
    mesh.name = "colliders";
    mesh.vertexCode = code(s::kMeshVert, s::kMeshVertWords);
    mesh.fragmentCode = code(s::kMeshFrag, s::kMeshFragWords);
    mesh.vertexFloat3Attributes = 4;  // MeshVertex
    mesh.depthTest = mesh.depthWrite = true;
    mesh.cullBackFaces = true;
    r.mesh = makePipeline(d, mesh);

    PipelineDesc splats;
    splats.name = "fluid splats";
    splats.vertexCode = code(s::kSplatsVert, s::kSplatsVertWords);
    splats.fragmentCode = code(s::kSplatsFrag, s::kSplatsFragWords);
    splats.setLayouts = {r.frameLayout, r.splatLayout};
    splats.blend = Blend::PremultipliedAlpha;
    splats.depthTest = true;
    splats.renderPass = r.passes.second;
    r.splats = makePipeline(d, splats);

    PipelineDesc sprites;
    sprites.name = "sprites";
    sprites.vertexCode = code(s::kSpritesVert, s::kSpritesVertWords);
    sprites.fragmentCode = code(s::kSpritesFrag, s::kSpritesFragWords);
    sprites.setLayouts = {r.frameLayout, r.spriteLayout};
    sprites.pushConstantBytes = sizeof(kernels::SpriteDraw);
    sprites.blend = Blend::Additive;
    sprites.depthTest = true;
    sprites.renderPass = r.passes.second;
    r.spritesAdditive = makePipeline(d, sprites);
    sprites.blend = Blend::PremultipliedAlpha;
    r.spritesAlpha = makePipeline(d, sprites);
    // Soft particles read the depth: drawn in pass B, where it is read-only.
    sprites.fragmentCode = code(s::kSpritesSoftFrag, s::kSpritesSoftFragWords);
    r.spritesAlphaSoft = makePipeline(d, sprites);
    sprites.blend = Blend::Additive;
    r.spritesAdditiveSoft = makePipeline(d, sprites);
}

// A host-visible vertex buffer holding `vertices` (at least one vertex of room).
gpu::Buffer vertexBuffer(gpu::Device& d, const std::vector<MeshVertex>& vertices) {
    gpu::Buffer b = gpu::createBuffer(d, std::max<std::size_t>(vertices.size(), 1) * sizeof(MeshVertex),
                                      VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    if (!vertices.empty()) {
        std::memcpy(b.mapped, vertices.data(), vertices.size() * sizeof(MeshVertex));
    }
    return b;
}

void createCommands(Renderer& r) {
    gpu::Device& d = *r.device;
    auto pool = gpu::vkStruct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = d.queueFamily;
    gpu::check(vkCreateCommandPool(d.device, &pool, nullptr, &r.commandPool), "vkCreateCommandPool");
    auto alloc = gpu::vkStruct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    alloc.commandPool = r.commandPool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    gpu::check(vkAllocateCommandBuffers(d.device, &alloc, &r.cmd), "vkAllocateCommandBuffers");
    auto fence = gpu::vkStruct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
    gpu::check(vkCreateFence(d.device, &fence, nullptr, &r.fence), "vkCreateFence");
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &families, nullptr);
    std::vector<VkQueueFamilyProperties> props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(d.physical, &families, props.data());
    if (props[d.queueFamily].timestampValidBits > 0 && d.properties.limits.timestampPeriod > 0.0f) {
        auto q = gpu::vkStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
        q.queryType = VK_QUERY_TYPE_TIMESTAMP;
        q.queryCount = kTimestamps;
        gpu::check(vkCreateQueryPool(d.device, &q, nullptr, &r.timestamps), "vkCreateQueryPool");
        r.timestampPeriodNs = d.properties.limits.timestampPeriod;
    }
}

void createResources(Renderer& r) {
    gpu::Device& d = *r.device;
    if (!d.graphics) {
        throw Error("render: the Vulkan device's queue cannot draw (no graphics queue)");
    }
    r.passes = createRenderPasses(d);
    r.target = createRenderTarget(d, r.passes, r.def.width, r.def.height);
    r.linearSampler = gpu::createLinearSampler(d);
    r.nearestSampler = gpu::createSampler(d, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false);
    r.placeholderImage = whiteImage(d);
    createMaterialTextures(d, r.materials, surfaceTexturePaths(r.world));
    if (r.def.background.kind == BackgroundKind::Image) {
        r.backgroundImage = loadImage(d, r.def.background.image, "render background");
    }
    createDescriptors(r);
    createPipelines(r);
    createLight(r);
    createSurface(r);
    createCommands(r);
    const float aspect = float(r.def.width) / float(r.def.height);
    r.staticMesh = vertexBuffer(d, r.def.drawColliders ? staticColliderMesh(r.world, planeExtent(r.def.camera, aspect), r.materials.paths)
                                                       : std::vector<MeshVertex>{});
    r.staticVertices = r.def.drawColliders
                           ? static_cast<std::uint32_t>(r.staticMesh.size / sizeof(MeshVertex))
                           : 0u;
    createSpriteEmitters(r);
    createOit(r);
    r.softSprites = std::any_of(r.emitters.begin(), r.emitters.end(),
                                [](const SpriteEmitter& s) { return s.softDistance > 0.0f; });
}

FrameUniforms frameUniforms(const RenderDef& def, double time) {
    const CameraDef& c = def.camera;
    const float aspect = float(def.width) / float(def.height);
    const glm::vec3 forward = glm::normalize(c.target - c.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float distance = glm::length(c.target - c.eye);
    const float reach = distance + 4.0f * planeExtent(c, aspect);
    glm::mat4 proj;
    glm::vec4 depthRange;  // near, far, orthographic: what soft particles undo
    if (c.orthographic) {
        // Near plane behind the eye: in a 2D view nothing in front of the
        // camera plane should be cut away (collider slabs reach toward it).
        const float h = 0.5f * c.orthoHeight;
        proj = glm::orthoRH_ZO(-h * aspect, h * aspect, -h, h, -reach, reach);
        depthRange = {-reach, reach, 1.0f, 0.0f};
    } else {
        const float nearPlane = std::max(1e-3f, 0.01f * distance);
        proj = glm::perspectiveRH_ZO(glm::radians(c.fovDegrees), aspect, nearPlane, reach);
        depthRange = {nearPlane, reach, 0.0f, 0.0f};
    }
    proj[1][1] *= -1.0f;  // Vulkan's clip space has y down
    FrameUniforms u{};
    u.viewProj = proj * glm::lookAtRH(c.eye, c.target, c.up);
    u.eye = glm::vec4(c.eye, c.orthographic ? 1.0f : 0.0f);
    u.right = glm::vec4(right, float(def.width));
    u.up = glm::vec4(up, float(def.height));
    u.forward = glm::vec4(forward, static_cast<float>(time));
    u.sun = glm::vec4(glm::normalize(def.sunDirection), 0.0f);
    const BackgroundDef& b = def.background;
    u.backgroundTop = glm::vec4(b.kind == BackgroundKind::Colour ? b.colour : b.top, float(b.kind));
    u.backgroundBottom = glm::vec4(b.bottom, 0.0f);
    u.waterColour = glm::vec4(def.fluid.colour, def.fluid.opacity);
    u.waterFlags = glm::vec4(def.fluid.refraction ? 1.0f : 0.0f, def.fluid.edges ? 1.0f : 0.0f,
                             kRefractionStrength, 0.0f);
    // The surface's field texel is set per frame (prepareFrame); its tint
    // reach in fractions of the frame's height.
    const float visibleHeight = c.orthographic ? c.orthoHeight
                                               : 2.0f * distance * std::tan(0.5f * glm::radians(c.fovDegrees));
    u.surface = glm::vec4(0.0f, 0.0f, kSurfaceTintDepth / visibleHeight, kSurfaceThreshold);
    u.depthRange = depthRange;
    u.invViewProj = glm::inverse(u.viewProj);
    return u;
}

// A body made after the renderer may bring a texture it has not loaded: the
// array is made again with it (the previous frame has finished, so neither
// the old image nor the descriptor is in use).
void growMaterials(Renderer& r, const std::vector<BodySnapshot>& bodies) {
    MaterialLayers paths = r.materials.paths;
    if (!addBodyTexturePaths(paths, bodies)) {
        return;
    }
    createMaterialTextures(*r.device, r.materials, paths);
    VkDescriptorImageInfo materials = materialsImage(r);
    auto write = gpu::vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    write.dstSet = r.frameSet;
    write.dstBinding = kernels::SD_RENDER_BINDING_MATERIALS;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    write.pImageInfo = &materials;
    vkUpdateDescriptorSets(r.device->device, 1, &write, 0, nullptr);
}

// The bodies' mesh of this frame, in a host-visible buffer that grows as
// needed (the previous frame has finished: renderFrame waits for it).
void prepareBodies(Renderer& r) {
    r.dynamicVertices = 0;
    if (!r.def.drawColliders || bodyCount(r.world) == 0) {
        return;
    }
    const std::vector<BodySnapshot> bodies = readBodies(r.world);
    growMaterials(r, bodies);
    std::vector<MeshVertex> vertices = bodyMesh(bodies, r.materials.paths);
    const VkDeviceSize bytes = vertices.size() * sizeof(MeshVertex);
    if (r.dynamicMesh.buffer == VK_NULL_HANDLE || r.dynamicMesh.size < bytes) {
        if (r.dynamicMesh.buffer != VK_NULL_HANDLE) {
            gpu::destroyBuffer(*r.device, r.dynamicMesh);
        }
        r.dynamicMesh = vertexBuffer(*r.device, vertices);
    } else if (bytes > 0) {
        std::memcpy(r.dynamicMesh.mapped, vertices.data(), bytes);
    }
    r.dynamicVertices = static_cast<std::uint32_t>(vertices.size());
}

void recordMesh(Renderer& r, VkCommandBuffer cmd, const gpu::Buffer& mesh, std::uint32_t vertices) {
    if (vertices == 0) {
        return;
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.mesh.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.mesh.layout, 0, 1, &r.frameSet, 0, nullptr);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &mesh.buffer, &offset);
    vkCmdDraw(cmd, vertices, 1, 0, 0);
}

void timestamp(Renderer& r, VkCommandBuffer cmd, VkPipelineStageFlagBits stage, std::uint32_t index) {
    if (r.timestamps != VK_NULL_HANDLE) {
        vkCmdWriteTimestamp(cmd, stage, r.timestamps, index);
    }
}

}  // namespace

void readFrameTimes(Renderer& r) {
    if (r.timestamps == VK_NULL_HANDLE) {
        return;
    }
    std::uint64_t t[kTimestamps] = {};
    if (vkGetQueryPoolResults(r.device->device, r.timestamps, 0, kTimestamps, sizeof(t), t, sizeof(std::uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT) != VK_SUCCESS) {
        return;
    }
    auto ms = [&](std::uint32_t a, std::uint32_t b) { return double(t[b] - t[a]) * r.timestampPeriodNs * 1e-6; };
    r.stats.surfaceFieldMs = ms(0, 1);
    r.stats.backgroundMs = ms(1, 2);
    r.stats.collidersMs = ms(2, 3);
    r.stats.refractionCopyMs = ms(3, 4);
    r.stats.oitAccumulateMs = ms(4, 5);
    r.stats.fluidMs = ms(5, 6);
    r.stats.spritesMs = ms(6, 7);
    r.stats.lightMs = ms(7, 8);
    r.stats.totalDeviceMs = ms(0, 8);
}

namespace {

void beginPass(Renderer& r, VkCommandBuffer cmd, bool first) {
    VkClearValue clear[2] = {};
    clear[1].depthStencil = {1.0f, 0};
    auto info = gpu::vkStruct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
    info.renderPass = first ? r.passes.first : r.passes.second;
    info.framebuffer = first ? r.target.framebufferA : r.target.framebufferB;
    info.renderArea = {{0, 0}, {r.target.width, r.target.height}};
    info.clearValueCount = first ? 2u : 0u;
    info.pClearValues = clear;
    vkCmdBeginRenderPass(cmd, &info, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport viewport{0.0f, 0.0f, float(r.target.width), float(r.target.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {r.target.width, r.target.height}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace

std::unique_ptr<Renderer> createRenderer(WorldId world, const RenderDef& def) {
    auto r = std::make_unique<Renderer>();
    r->world = world;
    r->def = def;
    World& w = worldFromId(world);
    r->pointLights = capturePointLights(w, def.lights);
    if (w.gpu) {
        r->device = w.gpu->device.get();  // draw straight from the world's buffers
    } else {
        r->ownDevice = gpu::createDevice(gpu::worldDeviceOptions());
        r->device = r->ownDevice.get();
    }
    try {
        createResources(*r);
    } catch (...) {
        destroyRenderer(*r);
        throw;
    }
    return r;
}

void destroyRenderer(Renderer& r) {
    if (r.device == nullptr) {
        return;
    }
    gpu::Device& d = *r.device;
    if (d.device != VK_NULL_HANDLE) {
        vkDeviceWaitIdle(d.device);
        destroyOit(r);
        destroySpriteEmitters(r);
        destroySplats(r);
        if (r.light.layout != VK_NULL_HANDLE) {
            destroyLight(r);
        }
        if (r.surface.pass != VK_NULL_HANDLE) {
            destroySurface(r);
        }
        destroyScreenFluid(r);
        r.sort.reset();
        for (gpu::Buffer* b : {&r.staticMesh, &r.dynamicMesh, &r.frameUniforms}) {
            if (b->buffer != VK_NULL_HANDLE) {
                gpu::destroyBuffer(d, *b);
            }
        }
        for (Pipeline* p : {&r.background, &r.mesh, &r.spritesAdditive, &r.spritesAlpha, &r.spritesAdditiveSoft,
                            &r.spritesAlphaSoft, &r.splats}) {
            destroyPipeline(d, *p);
        }
        vkDestroyDescriptorPool(d.device, r.pool, nullptr);
        for (VkDescriptorSetLayout l : {r.frameLayout, r.spriteLayout, r.splatLayout}) {
            vkDestroyDescriptorSetLayout(d.device, l, nullptr);
        }
        destroyMaterialTextures(d, r.materials);
        for (gpu::Image* i : {&r.backgroundImage, &r.placeholderImage}) {
            if (i->image != VK_NULL_HANDLE) {
                gpu::destroyImage(d, *i);
            }
        }
        vkDestroySampler(d.device, r.linearSampler, nullptr);
        vkDestroySampler(d.device, r.nearestSampler, nullptr);
        if (r.target.colour.image != VK_NULL_HANDLE) {
            destroyRenderTarget(d, r.target);
        }
        destroyRenderPasses(d, r.passes);
        vkDestroyQueryPool(d.device, r.timestamps, nullptr);
        vkDestroyFence(d.device, r.fence, nullptr);
        vkDestroyCommandPool(d.device, r.commandPool, nullptr);
    }
    if (r.ownDevice) {
        gpu::destroyDevice(*r.ownDevice);
        r.ownDevice.reset();
    }
    r.device = nullptr;
}

void prepareFrame(Renderer& r) {
    // A Vulkan world's steps in flight need no wait here: the frame is
    // submitted after them to the same queue and its first barrier makes
    // their writes visible; renderFrame waits for the frame before the next
    // step can be submitted.
    World& w = worldFromId(r.world);
    const float dt = r.lastTime < 0.0 ? 0.0f : static_cast<float>(std::max(0.0, w.time - r.lastTime));
    r.lastTime = w.time;
    prepareBodies(r);
    prepareSplats(r, dt);
    prepareSurface(r);
    prepareScreenFluid(r);
    prepareSprites(r);
    FrameUniforms u = frameUniforms(r.def, w.time);
    writeLights(r.pointLights, r.def, w, w.time, u);
    if (r.surface.drawn) {
        u.surface.x = 1.0f / float(r.surface.width);
        u.surface.y = 1.0f / float(r.surface.height);
    }
    std::memcpy(r.frameUniforms.mapped, &u, sizeof(u));
}

void recordFrame(Renderer& r, VkCommandBuffer cmd) {
    // Particle data written by the world's compute passes (Vulkan world) or
    // by the host (CPU world) is read by the vertex stage.
    gpu::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_VERTEX_SHADER_BIT,
                       VK_ACCESS_SHADER_READ_BIT);
    if (r.timestamps != VK_NULL_HANDLE) {
        vkCmdResetQueryPool(cmd, r.timestamps, 0, kTimestamps);
    }
    timestamp(r, cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0);
    recordSurfaceField(r, cmd);  // its own passes, before the frame's
    recordScreenFluidField(r, cmd);
    timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 1);
    // One render pass, or two: around a copy of the colour target when
    // something refracts (the copy is what the water shows behind it), the
    // OIT accumulation, or so that soft particles and the screen-space
    // liquid can read the depth (on
    // lavapipe each extra pass costs a full-frame store and load).
    const bool refracts = r.def.fluid.refraction && r.splatCount > 0;
    {  // Background and colliders.
        beginPass(r, cmd, true);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.background.pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r.background.layout, 0, 1, &r.frameSet, 0,
                                nullptr);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 2);
        recordMesh(r, cmd, r.staticMesh, r.staticVertices);
        recordMesh(r, cmd, r.dynamicMesh, r.dynamicVertices);
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 3);
    }
    const bool oit = r.oit.pass != VK_NULL_HANDLE;
    if (refracts || oit || r.softSprites || r.screen.drawn) {
        vkCmdEndRenderPass(cmd);
        if (refracts) {  // What refraction sees behind the water.
            recordCopyBehind(cmd, r.target);
        }
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 4);
        recordOitAccumulation(r, cmd);  // needs only pass A's depth
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 5);
        beginPass(r, cmd, false);
    } else {
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 4);
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 5);
    }
    {  // Fluids (splats, then the liquid surface over the splashes that fell
       // back into it), then sprites, then the OIT layer over them.
        recordSplats(r, cmd);
        recordSurfaceComposite(r, cmd);
        recordScreenFluidComposite(r, cmd);
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 6);
        recordSprites(r, cmd);
        recordOitComposite(r, cmd);
        vkCmdEndRenderPass(cmd);
        timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 7);
    }
    recordLight(r, cmd);  // bloom, then the tone map into the sRGB image
    timestamp(r, cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 8);
}

Frame renderFrame(Renderer& r) {
    gpu::Device& d = *r.device;
    auto start = std::chrono::steady_clock::now();
    prepareFrame(r);
    r.stats.cpuMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() -
                    r.stats.sortMs;
    gpu::check(vkResetCommandBuffer(r.cmd, 0), "vkResetCommandBuffer");
    auto begin = gpu::vkStruct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    gpu::check(vkBeginCommandBuffer(r.cmd, &begin), "vkBeginCommandBuffer");
    recordFrame(r, r.cmd);
    recordReadback(r.cmd, r.target);
    gpu::check(vkEndCommandBuffer(r.cmd), "vkEndCommandBuffer");
    auto submit = gpu::vkStruct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &r.cmd;
    gpu::check(vkResetFences(d.device, 1, &r.fence), "vkResetFences");
    gpu::check(vkQueueSubmit(d.queue, 1, &submit, r.fence), "vkQueueSubmit");
    gpu::check(vkWaitForFences(d.device, 1, &r.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    readFrameTimes(r);
    return readFrame(r.target);
}

}  // namespace spindrift::render
