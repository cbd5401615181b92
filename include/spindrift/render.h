// spindrift public API: drawing a world with Vulkan. A renderer draws the
// world's current state: effect particles as camera-facing sprites straight
// from the particle buffers (no copy back on the Vulkan backend, one upload
// per frame on the CPU backend), 2D fluids as a continuous liquid surface
// and other fluids as Sprinkle-style splats (FluidRenderDef::style), and the
// colliders and bodies with simple shading. It works without a GPU on Mesa's
// lavapipe.
#pragma once

#include <spindrift/export.h>

#include <spindrift/world.h>

#include <cstdint>
#include <string>
#include <vector>

namespace spindrift {

/// Where the viewer stands. Orthographic views suit 2D scenes (fluids in the
/// xy plane); perspective views orbit `target` in the viewer.
struct CameraDef {
    glm::vec3 eye{0.0f, 2.0f, 10.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovDegrees = 45.0f;   ///< vertical field of view of a perspective view
    bool orthographic = false;
    float orthoHeight = 10.0f;  ///< visible height (m) of an orthographic view
};

enum class BackgroundKind : std::uint32_t {
    Colour = 0,    ///< one colour
    Gradient = 1,  ///< `bottom` at the bottom row to `top` at the top row
    Image = 2,     ///< a PNG stretched over the frame
};

struct BackgroundDef {
    BackgroundKind kind = BackgroundKind::Gradient;
    glm::vec3 colour{0.02f, 0.02f, 0.03f};  ///< linear RGB (Colour)
    glm::vec3 top{0.10f, 0.14f, 0.22f};      ///< linear RGB (Gradient)
    glm::vec3 bottom{0.01f, 0.01f, 0.02f};   ///< linear RGB (Gradient)
    std::string image;                       ///< PNG path (Image)
};

/// Most pixels a side of a frame (RenderDef::width, height).
inline constexpr std::uint32_t kRenderMaxFrameSide = 16384;
/// The splat steps below, FluidRenderDef::upTo's largest n.
inline constexpr int kFluidRenderSteps = 7;

/// How fluids are drawn.
enum class FluidStyle : std::uint32_t {
    /// 2D fluids as one continuous liquid: the particles' kernels summed into
    /// a reduced-resolution field, blurred, cut at a threshold into an
    /// anti-aliased edge and shaded (refraction, depth tint, rim, foam).
    /// 3D fluids as a screen-space liquid: sphere depths smoothed by a
    /// bilateral filter, thickness for absorption, Fresnel reflection,
    /// refraction and the sun's highlight (docs/rendering.md).
    Surface = 0,
    /// Every fluid as Sprinkle's splats, with the step switches below.
    Splats = 1,
};

/// How fluids look. `style` picks the continuous 2D surface (the default) or
/// the Sprinkle document's splat steps (slides 62-68), each switchable; they
/// build on each other in this order and FluidRenderDef::upTo(n) turns on the
/// first n. The surface uses colour, opacity, refraction (of what is behind),
/// stretch (kernels along the velocity) and splashes (drawn as splats on top).
struct FluidRenderDef {
    FluidStyle style = FluidStyle::Surface;
    glm::vec3 colour{0.10f, 0.35f, 0.85f};  ///< linear RGB of water
    float opacity = 0.6f;                    ///< of a splat's centre (the surface's shallow water), in (0, 1]
    /// Surface style: the field's resolution as a fraction of the frame's
    /// (each side), in [1/8, 1]; lower is faster and softer.
    float surfaceScale = 0.5f;
    /// Splat radius as a multiple of the fluid's spacing (1 = touching discs).
    float radiusScale = 1.5f;
    bool sizeFromDensity = true;  ///< 2: splat size grows with density, strays shrink
    bool stretch = true;          ///< 3: edge particles stretched along the surface, plus velocity
    bool refraction = true;       ///< 4: the background behind the water distorted
    bool edges = true;            ///< 5: surface highlight; upward-facing particles brighter (sun)
    bool splashes = true;         ///< 6: ballistic splash particles from low-density, rising particles
    bool bubbles = true;          ///< 7: some dense particles drawn as bubbles
    /// The splat style with step 1 (raw point splats) alone, then steps
    /// 2..n: n in [1, 7].
    SPINDRIFT_API static FluidRenderDef upTo(int n);
};

/// How the frame's linear light becomes the 8-bit sRGB image
/// (docs/rendering.md, "Light").
enum class ToneMap : std::uint32_t {
    None = 0,  ///< a plain clamp to [0, 1]: what is brighter than 1 clips to white
    Aces = 1,  ///< the ACES filmic curve as fitted by Narkowicz (2016): 1 maps to about 0.8, brights roll off
};

/// Most point lights a frame carries (RenderDef::lights).
inline constexpr std::uint32_t kRenderMaxLights = 8;

/// A point light, such as a fire's glow on what is around it. It lights
/// colliders, bodies and the liquid, falling smoothly to nothing at `radius`
/// (docs/rendering.md, "Light").
struct LightDef {
    std::string name;
    /// World position (m); with `emitter`, an offset from its spawn centre.
    glm::vec3 position{0.0f};
    /// Linear RGB; 1 lights a surface facing it about as the default sun does.
    glm::vec3 colour{1.0f, 0.55f, 0.2f};
    float radius = 3.0f;  ///< m, > 0
    /// 0: fixed. Else the light follows the emitter's spawn centre (which
    /// rides its body) and scales with its rate over the rate it had when the
    /// renderer was created, so a fire's glow fades as the fire is doused.
    EmitterId emitter;
    /// In [0, 1]: how deep the light's flicker is (a fixed function of the
    /// world time, so frames are reproducible).
    float flicker = 0.0f;
};

/// How a world is drawn.
struct RenderDef {
    std::uint32_t width = 1280;   ///< pixels
    std::uint32_t height = 720;   ///< pixels
    CameraDef camera;
    BackgroundDef background;
    FluidRenderDef fluid;
    bool drawColliders = true;    ///< world colliders, fluid obstacles and bodies
    /// Direction toward the sun (normalised on use), for shading and highlights.
    glm::vec3 sunDirection{0.3f, 1.0f, 0.5f};
    /// The sun's light, linear RGB, relative to the default daylight (1, 1, 1);
    /// a night scene's moon is dim and blue.
    glm::vec3 sunColour{1.0f};
    /// The sky's light on everything (ambient), linear RGB, relative to the
    /// default (1, 1, 1).
    glm::vec3 ambient{1.0f};
    /// Point lights, at most kRenderMaxLights.
    std::vector<LightDef> lights;
    /// The frame is drawn in linear light into a 16-bit float target; this
    /// multiplies it before the tone map, > 0.
    float exposure = 1.0f;
    ToneMap toneMap = ToneMap::Aces;
    /// Strength of the glow of what is brighter than 1 (blurred at a quarter
    /// of the frame's size and smaller, added before the tone map), >= 0;
    /// 0 turns bloom off and skips its passes.
    float bloom = 0.5f;
    // Output settings read by `spindrift render` (not by renderFrame):
    float fps = 30.0f;            ///< frames per second of the video
    float seconds = 5.0f;         ///< length of the video
};

struct RendererId { std::uint32_t index = 0; };

/// One frame's pixels: RGBA, 8 bits per channel, sRGB-encoded, top row first.
struct Frame {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint8_t> rgba;
};

/// Time (ms) the device spent in each pass of the last frame, from timestamp
/// queries (0 where the device has none); cpuMs is host work (splat
/// preparation, uploads).
struct RenderStats {
    double backgroundMs = 0.0, collidersMs = 0.0, spritesMs = 0.0, sortMs = 0.0, fluidMs = 0.0;
    /// The liquid surface's field: kernels summed, then blurred (2D), and
    /// the screen-space liquid's depth, thickness and smoothing (3D); 0 when
    /// no fluid is drawn as a surface. The composites count in fluidMs.
    double surfaceFieldMs = 0.0;
    /// The copy of the frame that refraction samples, with the extra pass
    /// it needs (0 when nothing refracts).
    double refractionCopyMs = 0.0;
    /// Weighted blended OIT's accumulation pass (0 when no emitter uses
    /// SpriteBlend::WeightedOit); its composite counts in spritesMs.
    double oitAccumulateMs = 0.0;
    /// Bloom's passes (0 when RenderDef::bloom is 0) and the tone map into
    /// the 8-bit image.
    double lightMs = 0.0;
    double totalDeviceMs = 0.0;
    double cpuMs = 0.0;
    std::uint64_t sprites = 0;   ///< sprite instances drawn
    /// Fluid instances drawn: splats (splashes and bubbles included) and the
    /// liquid surface's kernels (mirror images behind walls included).
    std::uint64_t splats = 0;
};

/// Creates a renderer for `world` on the world's own Vulkan device (Vulkan
/// backend) or a device of its own (CPU backend; lavapipe without a GPU).
/// Throws Error when there is no Vulkan driver or `def` is invalid.
SPINDRIFT_API RendererId createRenderer(WorldId world, const RenderDef& def);
SPINDRIFT_API void destroyRenderer(RendererId renderer);
/// Changes the camera from the next frame on (the viewer's orbit).
SPINDRIFT_API void setRenderCamera(RendererId renderer, const CameraDef& camera);
/// Replaces the fluid splat settings from the next frame on.
SPINDRIFT_API void setFluidRender(RendererId renderer, const FluidRenderDef& fluid);
/// Draws the world as it is now and returns the pixels. Temporal effects
/// (orientation smoothing, splashes) advance by the world time since the
/// previous frame.
SPINDRIFT_API Frame renderFrame(RendererId renderer);
SPINDRIFT_API RenderStats renderStats(RendererId renderer);

/// Throws FieldError naming the field ("fps", "fluid.opacity", "camera.fov")
/// for a definition createRenderer rejects.
SPINDRIFT_API void validateRenderDef(const RenderDef& def);
/// One light's part of validateRenderDef; fields are named as a scene
/// file's [[light]] spells them ("radius"), the object as "light 'name'".
SPINDRIFT_API void validateLightDef(const LightDef& light);
/// The camera's part of validateRenderDef; fields are named without
/// "camera." ("fov"), as a scene file's [camera] spells them.
SPINDRIFT_API void validateCameraDef(const CameraDef& camera);

}  // namespace spindrift
