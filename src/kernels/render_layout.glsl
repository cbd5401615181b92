// The renderer's contract with its shaders (src/render, src/render/shaders),
// written once for both languages as layout.glsl is for the simulation's:
// the frame's uniforms, the sprite, splat, surface, screen-space liquid and
// light passes' sets, bindings and push constants. Apart from layout.glsl,
// which every compute shader includes, because the compute shaders need
// none of it, and because of a bug of Debian 12's glslc (glslang 11.13): on a
// shader that declares `precise` values, its no-contraction propagation can
// loop, allocating without end, depending on the declarations in scope (not
// on their number alone: fluid_contacts.comp compiled with 10, 20 and 40
// extra constants and hung with 30; without `precise` it always compiled).
// It hung on fluid_contacts.comp when the fluid contacts' listing gained two
// passes and two bindings, and on fluid_integrate.comp when the carry's
// layout was added (carry_layout.glsl); with these declarations moved here
// every shader compiles in under a second. A shader whose glslc runs for
// more than a few seconds has met it again: moving declarations it does not
// need out of its scope is the remedy that worked.
#ifndef SPINDRIFT_KERNELS_RENDER_LAYOUT
#define SPINDRIFT_KERNELS_RENDER_LAYOUT
#include "layout.glsl"
SD_BEGIN

// The renderer (src/render): what every render pipeline reads, the camera and
// the frame's settings, a std140 uniform block (src/render/shaders/frame.glsl).
// 592 bytes.
SD_CONST uint SD_RENDER_SET_FRAME = 0u;
SD_CONST uint SD_RENDER_BINDING_FRAME = 0u;         // uniform FrameUniforms
SD_CONST uint SD_RENDER_BINDING_BACKGROUND = 1u;    // sampler2D, the background image
SD_CONST uint SD_RENDER_BINDING_SCENE_BEHIND = 2u;  // sampler2D, the colour target before the water
SD_CONST uint SD_RENDER_BINDING_DEPTH = 3u;         // sampler2D, the opaque depth (pass B's read-only depth)
SD_CONST uint SD_RENDER_BINDING_MATERIALS = 4u;     // sampler2DArray, the colliders' and bodies' textures
SD_CONST uint SD_RENDER_FRAME_BINDINGS = 5u;
// Point lights a frame carries (RenderDef::lights; kRenderMaxLights).
SD_CONST uint SD_MAX_LIGHTS = 8u;
struct FrameUniforms {
    mat4 viewProj;
    vec4 eye;             // xyz camera position (m); w: 1 orthographic, 0 perspective
    vec4 right;           // xyz camera right (world); w: viewport width (px)
    vec4 up;              // xyz camera up (world); w: viewport height (px)
    vec4 forward;         // xyz view direction (world); w: world time (s)
    vec4 sun;             // xyz unit direction toward the sun
    vec4 backgroundTop;   // rgb linear; w: background kind (0 colour, 1 gradient, 2 image)
    vec4 backgroundBottom;
    vec4 waterColour;     // rgb linear; a: opacity
    vec4 waterFlags;      // x refraction, y edges (0 or 1); z refraction strength (uv units)
    vec4 surface;         // liquid surface: xy one field texel (uv); z depth-tint reach (uv of the frame's height); w field threshold
    vec4 depthRange;      // the projection's near x and far y planes (m along the view; may be < 0 orthographic); z 1 orthographic
    mat4 invViewProj;     // clip to world: a pixel's world point (the 2D liquid's light)
    vec4 ambient;         // rgb linear, the sky's light relative to the default; w: point lights in use
    vec4 sunColour;       // rgb linear, the sun's light relative to the default
    vec4 lightPosition[SD_MAX_LIGHTS];  // xyz world (m); w reach (m)
    vec4 lightColour[SD_MAX_LIGHTS];    // rgb linear, at the light (flicker and the emitter's rate included)
};

// Effect sprites (src/render/shaders/sprites.*, src/render/sprite_pass.cpp):
// set 1 of the sprite pipelines, in order, then the sprite image.
SD_CONST uint SD_SPRITE_SET = 1u;
SD_CONST uint SD_SPRITE_BINDING_EMITTER = 0u;     // EmitterParams
SD_CONST uint SD_SPRITE_BINDING_POSITIONS = 1u;   // float[3 capacity], the GPU world's layout
SD_CONST uint SD_SPRITE_BINDING_VELOCITIES = 2u;
SD_CONST uint SD_SPRITE_BINDING_AGES = 3u;
SD_CONST uint SD_SPRITE_BINDING_BIRTHS = 4u;
SD_CONST uint SD_SPRITE_BINDING_ROTATIONS = 5u;
SD_CONST uint SD_SPRITE_BINDING_ORDER = 6u;       // uint[capacity]: slot of instance i
SD_CONST uint SD_SPRITE_BINDING_RUNS = 7u;        // uvec4[]: stateless runs
SD_CONST uint SD_SPRITE_BINDING_TRAILS = 8u;      // float[3 points capacity]: trail.glsl
SD_CONST uint SD_SPRITE_BINDING_TRAIL_LOOK = 9u;  // TrailLook
SD_CONST uint SD_SPRITE_BINDING_IMAGE = 10u;      // sampler2D
SD_CONST uint SD_SPRITE_BUFFERS = 10u;            // storage buffers before the image
// SpriteDraw::mode.
SD_CONST uint SD_SPRITE_MODE_SLOTS = 0u;      // stored slots in instance order
SD_CONST uint SD_SPRITE_MODE_ORDERED = 1u;    // stored slots via order[] (back to front)
SD_CONST uint SD_SPRITE_MODE_STATELESS = 2u;  // stateless runs
// The sprite pipelines' push constants (vertex and fragment). 48 bytes.
struct SpriteDraw {
    uint mode;      // SD_SPRITE_MODE_*
    uint runCount;  // stateless runs
    float stretch;  // s: quad lengthened by speed x stretch (m) along the screen velocity
    uint textured;  // 1: sample the sprite image
    uint columns;   // flipbook: frames across the image (1: the whole image)
    uint rows;      // flipbook: frames down the image
    uint frames;    // flipbook: frames played (rows x columns or fewer)
    float fps;      // flipbook: frames/s, looping; 0: once over the life
    uint blendFrames;    // flipbook: 1 cross-fades to the next frame
    float softDistance;  // m: soft particles' depth fade; 0 off
    uint trailPoints;    // > 0: draw the trails (6 (trailPoints - 1) vertices an instance), not the quads
    uint trailHead;      // ring index of the trails' newest points (trail.glsl)
};

// How an emitter's trails look (EmitterDef::trail), set 1 of the sprite
// pipelines. 368 bytes.
struct TrailLook {
    CurveParams widthOverLength;  // .x multiplies width, head (t = 0) to tail (1)
    CurveParams colorOverLength;  // multiplies the particle's colour
    float width;                  // m, at the head
    uint pad0, pad1, pad2;
};

// Weighted blended OIT (src/render/oit_pass.cpp): the accumulation targets,
// read by the composite at set 1.
SD_CONST uint SD_OIT_SET = 1u;
SD_CONST uint SD_OIT_BINDING_ACCUM = 0u;   // sampler2D: rgb sum of w a c, a product of (1 - a) (the revealage)
SD_CONST uint SD_OIT_BINDING_WEIGHTS = 1u;  // sampler2D: r sum of w a
SD_CONST uint SD_OIT_BINDINGS = 2u;

// Fluid splats (src/render/shaders/splats.*, src/render/fluid_splats.cpp):
// one instance per particle, splash or bubble, set 1 binding 0. 48 bytes.
SD_CONST uint SD_SPLAT_SET = 1u;
SD_CONST uint SD_SPLAT_BINDING_INSTANCES = 0u;
SD_CONST uint SD_SPLAT_WATER = 0u;   // SplatInstance::shade.z
SD_CONST uint SD_SPLAT_SPLASH = 1u;
SD_CONST uint SD_SPLAT_BUBBLE = 2u;
struct SplatInstance {
    vec4 centre;  // xyz position (m); w: radius (m) across the major axis
    vec4 axis;    // xyz unit major axis (2D: z = 0; (1,0,0) unoriented); w: stretch >= 1 (major semi-axis / radius)
    vec4 shade;   // x: brightness (1 base, > 1 sun highlight, splashes); y: edge factor in [0,1]; z: SD_SPLAT_*; w: rho / rho0 (0 for splashes)
                  // (liquid surface: x the kernel's amplitude, y foam in [0,1]; centre.w the kernel radius)
};

// A device fluid's liquid drawn from its own buffers (issue 16;
// src/render/device_water.cpp, shaders/fluid_water.comp): one invocation a
// particle writes its kernel or sphere (fluid_look.glsl) into the splat
// instances at `first`, then for each wall plane p near the water its mirror image at
// first + (p + 1) count + i (radius 0, drawn as nothing, where it has none:
// the host's order of instances, without a compaction), and lists the
// particles that throw a splash this frame for the host, which keeps the
// splashes' state.
SD_CONST uint SD_FLUID_WATER_WORKGROUP = 64u;
SD_CONST uint SD_FLUID_WATER_BINDING_X = 0u;          // float[]: positions, `dimension` floats a particle
SD_CONST uint SD_FLUID_WATER_BINDING_V = 1u;          // float[]: velocities, the same
SD_CONST uint SD_FLUID_WATER_BINDING_DENSITY = 2u;    // vec4[]: the last setup's constraints, z rho / rho0
SD_CONST uint SD_FLUID_WATER_BINDING_IDS = 3u;        // uint[]: serials
SD_CONST uint SD_FLUID_WATER_BINDING_INSTANCES = 4u;  // SplatInstance[]: the renderer's splat buffer
SD_CONST uint SD_FLUID_WATER_BINDING_PLANES = 5u;     // vec4[2 planes]: a point, then the unit normal
SD_CONST uint SD_FLUID_WATER_BINDING_SPLASHES = 6u;   // FluidSplashList: the particles that throw one
SD_CONST uint SD_FLUID_WATER_BINDING_COUNTS = 7u;     // uint[]: the last setup's neighbours a particle (splats)
SD_CONST uint SD_FLUID_WATER_BINDING_FIRST = 8u;      // uint[]: its first list entry
SD_CONST uint SD_FLUID_WATER_BINDING_LIST = 9u;       // uint[]: each entry's neighbour
SD_CONST uint SD_FLUID_WATER_BINDING_SHOWN = 10u;     // vec4[] by serial: a splat's shown axis, w its stretch (0: unseen)
SD_CONST uint SD_FLUID_WATER_BINDINGS = 11u;
SD_CONST uint SD_FLUID_WATER_SURFACE = 0u;  // FluidWaterPush::style: the 2D surface's kernels
SD_CONST uint SD_FLUID_WATER_SCREEN = 1u;   // the 3D screen-space liquid's spheres
SD_CONST uint SD_FLUID_WATER_SPLATS = 2u;   // Sprinkle's splats (fluid_look.glsl, splatOfParticle)
// Most splash throwers one frame lists: more, and the host reads the
// particles back that frame instead (every thrower, in particle order).
SD_CONST uint SD_FLUID_SPLASH_ROOM = 1024u;
// Which of Sprinkle's splat steps are on (FluidRenderDef), and the frame's
// constants (src/kernels/fluid_look.glsl, splatOfParticle). 48 bytes.
struct SplatSteps {
    vec4 up;               // xyz: unit vector against gravity (highlights); w: the frame's dt (s)
    float radius;          // m, rule 1's splat radius
    uint sizeFromDensity;  // rule 2
    uint stretch;          // rule 3
    uint edges;            // rule 5
    uint bubbles;          // rule 7
    uint dimension;
    uint pad0, pad1;
};

struct FluidWaterPush {
    vec4 up;          // xyz: unit vector against gravity; w: a splash's chance this frame
    uint count;       // particles
    uint dimension;   // 2 or 3
    uint first;       // the first instance written
    uint style;       // SD_FLUID_WATER_*
    uint stretch;     // 1: kernels stretched along the velocity
    uint densities;   // 1: the density binding holds the particles' densities; 0: rho / rho0 = 1
    uint planes;      // wall planes (mirror images; surface style only)
    uint splashes;    // 1: list the splash throwers
    uint frame;       // the splash RNG's counter (FluidSplatState::frame)
    float radius;     // m, a kernel's or sphere's
    float invH2;      // 1 / h^2 (1/m^2): the splats' pair entries g (fluid.glsl, fluidPairG)
    uint lists;       // 1: the list bindings hold the last setup's lists
    SplatSteps steps;  // the splat style's steps (fluid_look.glsl)
};
// A particle that throws a splash: its index (particle order), serial,
// position and velocity (m, m/s; z 0 in 2D). 48 bytes.
struct FluidSplashThrower {
    vec4 position;
    vec4 velocity;
    uint index;
    uint id;
    uint pad0, pad1;
};

// The 2D liquid surface (src/render/surface_pass.cpp, shaders surface_*): the
// particles' kernels (SplatInstance, set 1 of surface_field.vert as for the
// splats) are summed into a reduced-resolution field, blurred twice (one
// direction each), then the composite reads the field at set 1 binding 0.
// The blur reads the field the same way.
SD_CONST uint SD_SURFACE_SET = 1u;
SD_CONST uint SD_SURFACE_BINDING_FIELD = 0u;  // sampler2D: r sum of kernels, g sum of kernels x foam
// The blur's and the composite's push constants (vertex and fragment). 16 bytes.
struct SurfacePush {
    vec4 values;  // blur: xy one field texel along the blur's direction (uv); composite: x half side of its quad (m)
};

// 3D fluids drawn as a screen-space liquid (src/render/screen_fluid_pass.cpp,
// shaders screen_fluid_*; van der Laan, Green and Sainz 2009): spheres' view
// depths and their summed thickness at reduced resolution, the depth smoothed,
// then a composite. Set 1 of the smoothing and composite pipelines; the
// spheres read the splats' instance set as surface_field.vert does.
SD_CONST uint SD_SCREEN_FLUID_SET = 1u;
SD_CONST uint SD_SCREEN_FLUID_BINDING_DEPTH = 0u;      // sampler2D: view depth, (z - near) / (far - near); 1: none
SD_CONST uint SD_SCREEN_FLUID_BINDING_THICKNESS = 1u;  // sampler2D: r water thickness (m), g thickness x foam
// Push constants of the screen-space liquid's passes (vertex and fragment). 32 bytes.
struct ScreenFluidPush {
    vec4 pass;  // smoothing: xy one texel step (texels), z depth falloff (m); sphere and composite: w sphere radius (m)
    vec4 view;  // perspective: x tan of half the horizontal field of view, y of the vertical one, z 0;
                // orthographic: x, y half the view's width and height (m), z 1
};

// Light (src/render/light_pass.cpp, shaders bloom_*.frag and tone_map.frag):
// the frame drawn into a float target, its bloom at reduced resolution, and
// the tone map into the 8-bit sRGB image. Set 1 of their pipelines.
SD_CONST uint SD_LIGHT_SET = 1u;
SD_CONST uint SD_LIGHT_BINDING_SOURCE = 0u;  // sampler2D: the float frame (threshold, tone map) or the bloom level read
SD_CONST uint SD_LIGHT_BINDING_BLOOM = 1u;   // sampler2D: the bloom's finest level (tone map)
SD_CONST uint SD_LIGHT_BINDINGS = 2u;
// The finest bloom level is this fraction of the frame's side (each texel
// the mean of SD_BLOOM_DIVISOR^2 frame texels); each further level halves it.
SD_CONST uint SD_BLOOM_DIVISOR = 4u;
// LightPush::values.z of the tone map.
SD_CONST uint SD_TONE_MAP_NONE = 0u;  // a clamp to [0, 1]
SD_CONST uint SD_TONE_MAP_ACES = 1u;  // acesFilm (src/kernels/light.glsl)
// The light passes' push constants (vertex and fragment). 16 bytes.
struct LightPush {
    vec4 values;  // bloom threshold: xy level 0's size (texels); blur: xy the fetches' offset (uv); tone map: x exposure, y bloom weight, z SD_TONE_MAP_*
};

SD_END

#ifdef __cplusplus
#include <cstddef>
namespace spindrift::kernels {
static_assert(sizeof(SpriteDraw) == 48);
static_assert(offsetof(SpriteDraw, softDistance) == 36);
static_assert(offsetof(SpriteDraw, trailHead) == 44);
static_assert(sizeof(TrailLook) == 368);
static_assert(offsetof(TrailLook, width) == 352);
static_assert(SD_SPRITE_BINDING_IMAGE == SD_SPRITE_BUFFERS);
static_assert(sizeof(SplatInstance) == 48);
static_assert(sizeof(FluidWaterPush) == 112);
static_assert(offsetof(FluidWaterPush, steps) == 64);
static_assert(sizeof(SplatSteps) == 48);
static_assert(sizeof(FluidSplashThrower) == 48);
static_assert(SD_FLUID_WATER_BINDING_SHOWN + 1u == SD_FLUID_WATER_BINDINGS);
static_assert(offsetof(SplatInstance, shade) == 32);
static_assert(sizeof(FrameUniforms) == 592);
static_assert(offsetof(FrameUniforms, invViewProj) == 240);
static_assert(offsetof(FrameUniforms, ambient) == 304);
static_assert(offsetof(FrameUniforms, lightPosition) == 336);
static_assert(offsetof(FrameUniforms, lightColour) == 464);
static_assert(offsetof(FrameUniforms, depthRange) == 224);
static_assert(offsetof(FrameUniforms, eye) == 64);
static_assert(offsetof(FrameUniforms, waterFlags) == 192);
static_assert(offsetof(FrameUniforms, surface) == 208);
static_assert(sizeof(SurfacePush) == 16);
static_assert(sizeof(LightPush) == 16);
static_assert(sizeof(ScreenFluidPush) == 32);
static_assert(SD_SCREEN_FLUID_SET == SD_SPLAT_SET);  // screen_fluid_sphere.vert reads the splats' instance set
static_assert(SD_SURFACE_SET == SD_SPLAT_SET);  // surface_field.vert reads the splats' instance set
}  // namespace spindrift::kernels
#endif

#endif
