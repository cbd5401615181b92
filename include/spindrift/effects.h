// spindrift public API: particle effects.
//
// The API follows Box2D v3: plain Def structs with sensible defaults, Create and
// Destroy functions, and small value ids. All units are SI: metres, seconds,
// kilograms, newtons; angles in radians (scene files use degrees).
#pragma once

#include <spindrift/errors.h>
#include <spindrift/export.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace spindrift {

/// Handles. A zero index means "none"; ids are only valid for the world that
/// made them.
struct WorldId { std::uint32_t index = 0; std::uint32_t generation = 0; };
struct EmitterId { std::uint32_t index = 0; };
struct ForceId { std::uint32_t index = 0; };
struct ColliderId { std::uint32_t index = 0; };
struct FlowFieldId { std::uint32_t index = 0; };
/// 1-based creation serial of a rigid body in its world (spindrift/bodies.h);
/// 0 is no body.
struct BodyId { std::uint32_t index = 0; };

/// A uniformly sampled range [min, max].
struct FloatRange { float min = 0.0f; float max = 0.0f; };
/// One random t mixes min and max, so colours stay on the line between the
/// two (what artists expect) instead of drifting through other hues.
struct ColorRange { glm::vec4 min{1.0f}; glm::vec4 max{1.0f}; };

/// One key of a piecewise-linear curve over normalised age t in [0, 1].
struct CurveKey { float t = 0.0f; glm::vec4 value{1.0f}; };
/// Piecewise-linear curve; empty means constant 1. At most kMaxCurveKeys keys,
/// t strictly increasing.
struct Curve { std::vector<CurveKey> keys; };
inline constexpr int kMaxCurveKeys = 8;

enum class Lifecycle : std::uint32_t {
    Recycle = 0,  ///< fixed slots, each re-born as soon as it dies (GPU talk)
    Spawn = 1,    ///< rate + bursts, dead slots go to a free list
};

/// How a particle's motion is stepped. Every integrator solves linear drag
/// (ForceKind::Wind and ForceKind::FlowField) exactly over the step: the
/// velocity relaxes toward the medium's by exp(-k dt / m), stable for any k,
/// mass and dt (docs/scene-format.md, "Integrators").
enum class Integrator : std::uint32_t {
    ExplicitEuler = 0,      ///< x += v dt; v += a dt (both from the old state)
    SemiImplicitEuler = 1,  ///< v += a dt; x += v dt (symplectic)
    Verlet = 2,             ///< velocity Verlet, a re-evaluated at the new position
    Rk4 = 3,                ///< classic Runge-Kutta 4, forces at every stage
};

enum class SpawnShapeKind : std::uint32_t { Point = 0, Sphere = 1, Box = 2, Disk = 3, Cone = 4 };

/// Where particles are born and which way they fly.
struct SpawnShapeDef {
    SpawnShapeKind kind = SpawnShapeKind::Point;
    glm::vec3 center{0.0f};
    /// Sphere, disk and cone radius (m). For a cone, the radius of its base disk.
    float radius = 0.0f;
    /// Box half extents (m).
    glm::vec3 halfExtents{0.0f};
    /// Sphere and box: born on the surface instead of in the volume.
    bool surface = false;
    /// Disk normal and cone axis; also the launch direction of every shape.
    glm::vec3 direction{0.0f, 1.0f, 0.0f};
    /// Half-angle (rad) of the cone of launch directions around `direction`.
    float spreadAngle = 0.0f;
};

/// Most slots an emitter may have (EmitterDef::capacity); also the limit of a
/// fluid (kFluidMaxCapacity). The API and scene files check against it.
inline constexpr std::uint32_t kEmitterMaxCapacity = 16 * 1024 * 1024;
/// Most particles one burst of the API may ask for (BurstDef::count).
inline constexpr std::uint32_t kEmitterMaxBurstCount = (1u << 20) - 1;
/// Most particles a sub-emitter makes per parent event (SpawnOnDef::count).
inline constexpr std::uint32_t kMaxSpawnPerEvent = 4096;
/// Most positions a particle's trail keeps (TrailDef::points).
inline constexpr std::uint32_t kMaxTrailPoints = 64;
/// Most trail positions one emitter keeps, capacity x points (12 bytes each:
/// 192 MiB).
inline constexpr std::uint64_t kEmitterMaxTrailPositions = 16u * 1024u * 1024u;

/// Most samples along one axis of a flow field (FlowFieldDef::nx, ny, nz) and
/// in all (48 MiB of vec3); the API and scene files check against them.
inline constexpr std::uint32_t kFlowFieldMaxAxis = 512;
inline constexpr std::uint32_t kFlowFieldMaxSamples = 4 * 1024 * 1024;
/// Most heights along one axis of a terrain (ColliderDef::terrainNx, terrainNz).
inline constexpr std::uint32_t kTerrainMaxAxis = 4096;
/// Most texels along a cube map face's edge (ColliderDef::cubeResolution).
inline constexpr std::uint32_t kCubeMapMaxResolution = 1024;

struct BurstDef {
    float time = 0.0f;         ///< s since the emitter started
    std::uint32_t count = 0;   ///< particles born at that time
};

/// Which colliders an emitter's particles hit, and what a hit does to them.
struct CollisionResponseDef {
    bool enabled = true;
    /// Colliders by id; empty means every collider in the world.
    std::vector<ColliderId> colliders;
    bool killOnCollision = false;
    /// Fraction of the remaining life lost at each hit, in [0, 1].
    float lifeLossOnCollision = 0.0f;
};

enum class SpriteBlend : std::uint32_t {
    Additive = 0,  ///< colours add up (fire, sparks): order-free
    Alpha = 1,     ///< "over" compositing (smoke), drawn back to front
    /// Weighted blended order-independent transparency (McGuire and Bavoil
    /// 2013): "over" approximated without a sort; exact for one layer and for
    /// layers of one colour.
    WeightedOit = 2,
};

/// A sprite sheet of `rows` x `columns` frames, read left to right, top row
/// first, played over the particle's life or at a frame rate.
struct FlipbookDef {
    std::uint32_t rows = 1;
    std::uint32_t columns = 1;
    /// Frames used, from the first; 0: rows x columns.
    std::uint32_t frames = 0;
    /// Frames per second, looping; 0: the frames spread once over the life.
    float fps = 0.0f;
    /// Cross-fade from each frame to the next instead of cutting.
    bool blend = false;

    bool animated() const { return rows * columns > 1; }
    std::uint32_t frameCount() const { return frames > 0 ? frames : rows * columns; }
};

/// How an emitter's particles are drawn (include/spindrift/render.h): a
/// camera-facing quad of the particle's size, rotation and colour.
struct SpriteDef {
    SpriteBlend blend = SpriteBlend::Additive;
    /// Velocity stretch (s): the quad is lengthened along the screen-space
    /// velocity by speed x stretch metres; 0: round sprites that rotate.
    float stretch = 0.0f;
    /// PNG sprite image (its alpha is the coverage); empty: a soft round
    /// procedural spot.
    std::string texture;
    /// The texture as a sprite sheet (needs `texture` when animated).
    FlipbookDef flipbook;
    /// Soft particles: a sprite fades out linearly over this distance (m, along
    /// the view) in front of opaque geometry; 0: hard intersections.
    float softDistance = 0.0f;
};

/// The events of another emitter's particles that a sub-emitter follows.
enum class SpawnEvent : std::uint32_t {
    Birth = 0,      ///< each particle born
    Death = 1,      ///< each particle that dies (age, or killed by a collider)
    Collision = 2,  ///< each impact on a collider (one per collider hit)
};

/// A sub-emitter (docs/scene-format.md, "Sub-emitters"): besides its own rate
/// and bursts, the emitter gets `count` particles at each `event` of the
/// parent's particles, born where the event happened: its `shape` is centred
/// there, and each particle gets `inheritVelocity` of the parent particle's
/// velocity on top of its launch velocity. On the vulkan backend the events
/// feed the child's births on the device, with no round trip.
struct SpawnOnDef {
    /// The parent, created before this emitter; 0: not a sub-emitter.
    EmitterId parent;
    SpawnEvent event = SpawnEvent::Death;
    std::uint32_t count = 1;      ///< particles per event, 1 to kMaxSpawnPerEvent
    float inheritVelocity = 0.0f; ///< share in [0, 1] of the parent particle's velocity

    bool enabled() const { return parent.index != 0; }
};

/// A ribbon through each particle's last positions, one kept per step
/// (docs/scene-format.md, "Trails"): drawn from the particle's current
/// position back along its path, facing the camera, in the sprite's blend
/// mode. Both backends keep the positions where the particles live (on the
/// device for Vulkan worlds); readParticles returns them.
struct TrailDef {
    /// Positions kept per particle, the current one included: 0 (no trail) or
    /// 2 to kMaxTrailPoints; capacity x points at most
    /// kEmitterMaxTrailPositions. The ribbon spans the last points - 1 steps; a newborn's starts
    /// as a point at its birth position and grows.
    std::uint32_t points = 0;
    float width = 0.05f;    ///< m, at the head (the particle)
    Curve widthOverLength;  ///< multiplies `width` from the head (t = 0) to the tail (1); uses .x
    Curve colorOverLength;  ///< multiplies the particle's colour from the head (0) to the tail (1)

    bool enabled() const { return points > 0; }
};

struct EmitterDef {
    std::string name;
    Lifecycle lifecycle = Lifecycle::Spawn;
    /// Slots (recycle: all of them cycle; spawn: the most alive at once).
    std::uint32_t capacity = 1024;
    /// Spawn mode: particles per second.
    float rate = 100.0f;
    /// Spawn mode and stateless emitters: timed bursts.
    std::vector<BurstDef> bursts;
    /// Stop emitting after this many seconds (< 0: never).
    float duration = -1.0f;

    SpawnShapeDef shape;
    /// Rides on a rigid body (0: fixed in the world): `shape.center` and
    /// `shape.direction` are then in the body's frame (x and y from the
    /// body's origin, turned with it; z as given) and the emitter follows the
    /// body's pose every step. Spawn shapes keep their world axes (a box does
    /// not turn). Not for stateless emitters. A destroyed body leaves the
    /// emitter where it last was.
    BodyId body;
    /// Share in [0, 1] of the body's velocity at `shape.center` (its centre's
    /// velocity plus the spin's) that every particle is born with, on top of
    /// its launch velocity.
    float inheritVelocity = 0.0f;
    FloatRange speed{1.0f, 1.0f};            ///< m/s
    FloatRange lifetime{1.0f, 1.0f};         ///< s, > 0
    FloatRange size{0.1f, 0.1f};             ///< diameter, m
    FloatRange rotation{0.0f, 0.0f};         ///< rad
    FloatRange angularVelocity{0.0f, 0.0f};  ///< rad/s
    ColorRange color;                        ///< linear RGBA
    float mass = 1.0f;                       ///< kg, > 0

    Curve colorOverLife;  ///< multiplies the start colour
    Curve sizeOverLife;   ///< multiplies the start size (uses .x)
    /// Colour and size by speed: curves over the particle's speed |v| mapped
    /// onto [0, 1] by `overSpeedRange` (t = 0 at or below min, 1 at or above
    /// max; with min = max a step at that speed). They multiply the start
    /// values together with the over-life curves.
    FloatRange overSpeedRange{0.0f, 1.0f};  ///< m/s, 0 <= min <= max
    Curve colorOverSpeed;  ///< multiplies the colour (after colorOverLife)
    Curve sizeOverSpeed;   ///< multiplies the size (after sizeOverLife; uses .x)

    Integrator integrator = Integrator::SemiImplicitEuler;
    /// Forces acting on this emitter; empty means every force in the world.
    std::vector<ForceId> forces;
    CollisionResponseDef collision;

    /// Stateless: a closed-form function of time, p = p0 + v0 t + g t^2 / 2,
    /// using `statelessGravity`; nothing is stored or simulated.
    bool stateless = false;
    glm::vec3 statelessGravity{0.0f, -9.81f, 0.0f};

    SpriteDef sprite;  ///< how the renderer draws it
    TrailDef trail;    ///< a ribbon behind each particle (state-preserving emitters)
    /// Born at another emitter's particle events (spawn lifecycle only).
    SpawnOnDef spawnOn;
};

enum class ForceKind : std::uint32_t {
    Gravity = 0,    ///< uniform acceleration `vector` (m/s^2), F = m g
    Wind = 1,       ///< linear drag toward wind velocity `vector`: F = strength (w - v)
    Attractor = 2,  ///< toward `position`: |F| = strength (radius / d)^falloff; strength < 0 repels
    Vortex = 3,     ///< around the line through `position` along `axis`, same falloff law
    Damping = 4,    ///< speed decays exactly: s(t) = s0 exp(-strength t)
    Undamping = 5,  ///< speed relaxes exactly toward `targetSpeed` at rate `strength` (bees)
    FlowField = 6,  ///< Stokes drag toward the field: F = 6 pi viscosity r (v_flow - v)
    /// Stokes drag toward an animated curl-noise velocity of rms `strength`
    /// (m/s), divergence-free at every instant (docs/scene-format.md)
    CurlNoise = 7,
};

struct ForceDef {
    std::string name;
    ForceKind kind = ForceKind::Gravity;
    glm::vec3 vector{0.0f, -9.81f, 0.0f};  ///< gravity acceleration or wind velocity
    glm::vec3 position{0.0f};
    glm::vec3 axis{0.0f, 1.0f, 0.0f};
    float strength = 1.0f;
    /// Reference distance of the falloff law (m), > 0.
    float radius = 1.0f;
    /// Exponent of (radius / d): 2 = inverse square, 0 = constant, -1 = spring.
    float falloff = 2.0f;
    /// Force is zero beyond this distance (m); 0 means unlimited. For damping
    /// and undamping it makes the force local, with rate scaled by (1 - d/range).
    float range = 0.0f;
    float targetSpeed = 1.0f;  ///< undamping, m/s
    FlowFieldId flowField;     ///< flow field forces
    float viscosity = 1.8e-5f; ///< eta, Pa s (air by default); flow field and curl noise forces
    float frequency = 1.0f;    ///< curl noise: noise cells per metre (1/m), > 0
    float speed = 0.0f;        ///< curl noise: noise slices per second (1/s), >= 0; 0 is a static field
    std::uint32_t octaves = 1; ///< curl noise: 1 to 4 layers, each at twice the frequency
    std::uint32_t seed = 0;    ///< curl noise
};

/// A grid of flow velocities over an axis-aligned box. 2D fields have nz = 1
/// and are extruded along z.
struct FlowFieldDef {
    std::string name;
    glm::vec3 boundsMin{-1.0f};
    glm::vec3 boundsMax{1.0f};
    std::uint32_t nx = 0, ny = 0, nz = 0;
    /// nx * ny * nz velocities (m/s), x fastest, then y, then z, sampled at the
    /// grid's vertices: vertex (i, j, k) sits at boundsMin + (i/(nx-1), j/(ny-1),
    /// k/(nz-1)) * (boundsMax - boundsMin); trilinear in between, the edge value
    /// outside the box.
    std::vector<glm::vec3> velocities;
};

enum class ColliderKind : std::uint32_t { Plane = 0, Sphere = 1, Box = 2, Terrain = 3, CubeMap = 4 };

/// Particles stay on the outside of every collider (the side the plane normal
/// points to; outside spheres and boxes; above terrain; outside the cube-map
/// shape).
/// A surface's texture for the renderer (ColliderDef::texture,
/// BodyDef::texture): a PNG whose colour multiplies the surface's colour
/// (white when it has none), repeated every `scale` metres and projected
/// along each face's main axis, in the body's own frame for a body.
struct SurfaceTexture {
    std::string path;    ///< PNG file; empty: no texture
    float scale = 1.0f;  ///< m the image covers before it repeats, > 0
};

struct ColliderDef {
    std::string name;
    ColliderKind kind = ColliderKind::Plane;
    /// Plane: a point on it and its unit normal. Sphere, box, cube map: centre.
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    float radius = 1.0f;               ///< sphere
    glm::vec3 halfExtents{0.5f};       ///< box
    glm::vec3 rotationDegrees{0.0f};   ///< box orientation, XYZ Euler (deg)
    /// Terrain: heights at the vertices of an nx by nz grid spanning
    /// [position.x, position.x + sizeX] x [position.z, position.z + sizeZ]
    /// (height (i, j) at x = position.x + sizeX i / (nx - 1)), x fastest; surface
    /// y = position.y + h, bilinear between vertices, edge heights beyond.
    std::uint32_t terrainNx = 0, terrainNz = 0;
    float terrainSizeX = 0.0f, terrainSizeZ = 0.0f;
    std::vector<float> heights;
    /// Cube map: res x res texels per face, faces in Vulkan order
    /// (+x, -x, +y, -y, +z, -z); each texel the distance (m) from `position` to
    /// the shape's surface along the texel's direction.
    std::uint32_t cubeResolution = 0;
    std::vector<float> cubeDepths;

    float friction = 0.0f;    ///< mu, fraction of tangential velocity removed
    float resilience = 0.5f;  ///< e, fraction of normal velocity kept
    /// Below this tangential speed (m/s) friction is not applied, and a contact
    /// approaching slower than this is resting, not an impact: it is not
    /// counted as a hit and does not trigger kill or life loss.
    float restSpeed = 0.01f;
    /// Linear RGB the renderer draws this collider in, each channel >= 0 and
    /// finite (above 1 is allowed: HDR); unset: the renderer's default (grey,
    /// green for terrain). A debug-draw colour in Box2D v3's sense
    /// (b2ShapeDef::customColor): it changes nothing in the simulation.
    std::optional<glm::vec3> colour;
    /// An image on its faces (drawing only).
    SurfaceTexture texture;
};

}  // namespace spindrift
