// The Vulkan renderer behind include/spindrift/render.h: plain structs and
// free functions (zeux/niagara style). A frame is:
//   pass A (clears): background, colliders and bodies;
//   before it, when a 2D fluid is drawn as a liquid surface, its field at
//   reduced resolution: kernels summed, blurred across, blurred down, depth;
//   copy of the colour target (what refraction sees behind the water);
//   when an emitter uses weighted blended OIT, its accumulation pass (depth
//   tested against pass A's, read-only);
//   pass B (loads): the liquid surface's composite, fluid splats, then effect
//   sprites (additive, then alpha back to front, then the OIT composite);
//   passes A and B draw into a 16-bit float target;
//   light: bloom of what is brighter than 1 at reduced resolution, then the
//   tone map into the 8-bit sRGB image that is read back or presented.
// Internal, so the viewer (apps/spindrift) can record a frame into its own
// command buffer and present the colour target.
#pragma once

#include "gpu/gpu_sort.h"
#include "gpu/vulkan_buffer.h"
#include "kernels/render_layout.glsl"
#include "render/device_water.h"
#include "render/fluid_splats.h"
#include "render/material_textures.h"
#include "render/point_lights.h"
#include "render/render_pipelines.h"
#include "render/render_target.h"

#include <spindrift/effects.h>
#include <spindrift/render.h>

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace spindrift::render {

/// `Frame` of src/render/shaders/frame.glsl (std140), defined once in
/// src/kernels/layout.glsl.
using FrameUniforms = kernels::FrameUniforms;

/// What one effect emitter draws with: its particle buffers (the GPU world's
/// own, or host-visible copies written each frame for a CPU world), its draw
/// order, its sprite image.
struct SpriteEmitter {
    std::size_t index = 0;  // into World::emitters
    bool stateless = false;
    SpriteBlend blend = SpriteBlend::Additive;
    bool alpha = false;  // sorted back to front ("over" with SpriteBlend::Alpha)
    std::uint32_t capacity = 0;
    float stretch = 0.0f;  // SpriteDef::stretch (s)
    FlipbookDef flipbook;
    float softDistance = 0.0f;  // m
    std::uint32_t trailPoints = 0;  // TrailDef::points (0: no trail)
    std::uint32_t trailHead = 0;    // this frame's (EmitterState::trailHead)
    // Owned (CPU world, or stateless): host-visible, mapped.
    gpu::Buffer params, positions, velocities, ages, births, rotations, runs, trail;
    gpu::Buffer trailLook;  // host-visible: kernels::TrailLook
    gpu::Buffer order;  // device-local: slot per instance (alpha blending)
    gpu::Image texture;
    bool ownTexture = false;
    VkDescriptorSet set = VK_NULL_HANDLE;
    std::uint32_t instances = 0;  // this frame
    std::uint32_t runCount = 0;   // stateless: this frame
};

/// Per-fluid splat state and its instance buffer.
struct SplatFluid {
    FluidSplatState state;
    std::vector<SplatInstance> instances;
    /// Drawn as a liquid surface: the first `particles` instances are its
    /// kernels (surface_field.h: particles and their mirror images behind
    /// planes), the rest splashes drawn as splats.
    bool surface = false;
    /// A 3D fluid drawn as a screen-space liquid: the first `particles`
    /// instances are its spheres (screen_fluid_pass.cpp), the rest splashes.
    bool screen = false;
    float spacing = 0.0f;  // m, the fluid's (screen: the spheres' radius and thickness scale)
    std::uint32_t particles = 0;
    std::uint32_t first = 0;  // of its instances in Renderer::splatBuffer
    /// A fluid on the device drawn from its buffers (device_water.h): its
    /// first `onDevice` instances (the water, `particles` of them) are
    /// written there by the device; `instances` holds only what follows.
    std::uint32_t onDevice = 0;
    /// Its splats' shown orientations by serial, kept on the device (the
    /// splat style of a fluid drawn from the device's buffers).
    gpu::Buffer shownOnDevice;
};

/// The liquid surface's field (surface_pass.cpp): two float images at a
/// fraction of the frame's size, written by one render pass that clears.
struct SurfaceField {
    std::uint32_t width = 0, height = 0;
    float scale = 0.0f;  // FluidRenderDef::surfaceScale the images were made for
    gpu::Image a, b;     // a: the sum, then blurred both ways; b: blurred across, then the result with depth
    VkFramebuffer framebufferA = VK_NULL_HANDLE, framebufferB = VK_NULL_HANDLE;
    VkRenderPass pass = VK_NULL_HANDLE;
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet readA = VK_NULL_HANDLE, readB = VK_NULL_HANDLE;
    bool drawn = false;  // this frame: some fluid is a surface
};

/// The screen-space liquid of 3D fluids (screen_fluid_pass.cpp): at a
/// fraction of the frame's size (FluidRenderDef::surfaceScale), the nearest
/// spheres' view depth, the summed thickness, and the depth smoothed twice
/// each way (ping-pong between a and b). Pipelines and passes are made on
/// first use: most worlds draw no 3D fluid.
struct ScreenFluid {
    std::uint32_t width = 0, height = 0;
    float scale = 0.0f;  // FluidRenderDef::surfaceScale the images were made for
    gpu::Image depth;      // D32_SFLOAT
    gpu::Image thickness;  // R16G16B16A16_SFLOAT
    gpu::Image a, b;       // R32_SFLOAT: the smoothed depth
    VkFramebuffer depthFramebuffer = VK_NULL_HANDLE, thicknessFramebuffer = VK_NULL_HANDLE;
    VkFramebuffer framebufferA = VK_NULL_HANDLE, framebufferB = VK_NULL_HANDLE;
    VkRenderPass depthPass = VK_NULL_HANDLE, thicknessPass = VK_NULL_HANDLE, smoothPass = VK_NULL_HANDLE;
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet readDepth = VK_NULL_HANDLE, readA = VK_NULL_HANDLE, readB = VK_NULL_HANDLE;
    Pipeline spheres, thicknessSpheres, smooth, composite;
    bool drawn = false;  // this frame: some fluid is drawn so
};

/// Weighted blended OIT (oit_pass.cpp): the sums and the revealage at the
/// frame's size, their pass (clears, then tests the depth read-only), and
/// the composite's descriptor set. Made only when an emitter uses it.
struct OitTargets {
    gpu::Image sums, weights;  // sums: rgb the weighted colours, a the revealage; weights: their sum
    VkRenderPass pass = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    Pipeline accumulate, composite;
};

/// Bloom's levels: a quarter of the frame's side, then halved 3 times
/// (1/4 to 1/32): a glow about 50 pixels wide at 960x540.
inline constexpr std::uint32_t kBloomLevels = 4;

/// Bloom and the tone map (light_pass.cpp). The levels, their passes and sets
/// exist only when RenderDef::bloom > 0.
struct Light {
    VkRenderPass down = VK_NULL_HANDLE, up = VK_NULL_HANDLE;  // overwrite a level / add onto it
    gpu::Image levels[kBloomLevels];
    glm::uvec2 sizes[kBloomLevels] = {};
    VkFramebuffer framebuffers[kBloomLevels] = {};
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet toneMapSet = VK_NULL_HANDLE, thresholdSet = VK_NULL_HANDLE;
    VkDescriptorSet levelSets[kBloomLevels] = {};
    Pipeline threshold, blurDown, blurUp, toneMap;
};

struct Renderer {
    WorldId world;
    RenderDef def;
    RenderStats stats;
    double lastTime = -1.0;  // world time of the previous frame; < 0: none yet

    gpu::Device* device = nullptr;             // the world's, or `ownDevice`
    std::unique_ptr<gpu::Device> ownDevice;    // CPU worlds
    RenderPasses passes;
    RenderTarget target;
    VkSampler linearSampler = VK_NULL_HANDLE;
    VkSampler nearestSampler = VK_NULL_HANDLE;  // the depth soft particles read (texelFetch)
    VkDescriptorSetLayout frameLayout = VK_NULL_HANDLE, spriteLayout = VK_NULL_HANDLE,
                          splatLayout = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet frameSet = VK_NULL_HANDLE, splatSet = VK_NULL_HANDLE;
    gpu::Buffer frameUniforms;  // host-visible
    gpu::Image backgroundImage, placeholderImage;
    Pipeline background, mesh, spritesAdditive, spritesAlpha, splats;
    Pipeline spritesAdditiveSoft, spritesAlphaSoft;  // read the depth: pass B only
    bool softSprites = false;  // some emitter has SpriteDef::softDistance > 0: pass B is begun
    Pipeline surfaceField, surfaceBlur, surfaceDepth, surfaceComposite;
    SurfaceField surface;
    ScreenFluid screen;  // depthPass == VK_NULL_HANDLE: not made yet
    OitTargets oit;  // pass == VK_NULL_HANDLE: no emitter uses OIT
    Light light;
    PointLights pointLights;
    MaterialTextures materials;  // colliders' and bodies' textures

    // Colliders: the static mesh, built once; bodies are rebuilt each frame.
    gpu::Buffer staticMesh, dynamicMesh;
    std::uint32_t staticVertices = 0, dynamicVertices = 0;

    std::vector<SpriteEmitter> emitters;
    std::unique_ptr<gpu::GpuSort> sort;
    std::vector<SplatFluid> fluids;
    gpu::Buffer splatBuffer;  // host-visible SplatInstance array of every fluid
    std::uint32_t splatCount = 0;
    DeviceWater deviceWater;  // a device fluid's liquid from its buffers
    /// Draw a device fluid's liquid from its buffers (false: read the
    /// particles back and build it on the host, as for a CPU fluid; tests
    /// compare the two).
    bool drawDeviceWater = true;

    VkCommandPool commandPool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkQueryPool timestamps = VK_NULL_HANDLE;
    double timestampPeriodNs = 0.0;
};

std::unique_ptr<Renderer> createRenderer(WorldId world, const RenderDef& def);
void destroyRenderer(Renderer& r);

/// Host work of a frame: uniforms, particle uploads (CPU worlds), stateless
/// runs, fluid splats, bodies; and the back-to-front sorts of alpha emitters,
/// each its own submission (a GpuSort sorts once per submission).
void prepareFrame(Renderer& r);
/// Records the frame's passes into `cmd`; leaves the sRGB image
/// (r.target.colour) in TRANSFER_SRC_OPTIMAL.
void recordFrame(Renderer& r, VkCommandBuffer cmd);
/// prepareFrame, recordFrame, a copy to the read-back buffer, submit and wait.
Frame renderFrame(Renderer& r);
/// Fills r.stats' device times from the timestamps of the last recorded
/// frame; call once its submission has finished (the viewer, which submits
/// frames itself).
void readFrameTimes(Renderer& r);

/// The renderer behind a public id (render_api.cpp), for the viewer, which
/// records frames into its own command buffers. Throws Error for a bad id.
Renderer& rendererOf(RendererId id);

}  // namespace spindrift::render
