// GPU-visible parameter structs, defined once for both languages. Every struct is
// laid out for std430 with vec4 members first and scalars in groups of four, so
// the C++ layout (glm::vec4 is 16 bytes, 4-aligned) matches; the end of this
// file static_asserts sizes and offsets on the C++ side.
#ifndef SPINDRIFT_KERNELS_TYPES
#define SPINDRIFT_KERNELS_TYPES
#include "prelude.glsl"
SD_BEGIN

SD_CONST uint SD_MAX_CURVE_KEYS = 8u;

// Age of a dead slot in spawn mode: never reaches 0, so it is never re-born by
// the update (only the emission pass re-uses it).
SD_CONST float SD_DEAD_AGE = -3.0e38f;

// Piecewise-linear curve over normalised age. 8 keys: 176 bytes.
struct CurveParams {
    vec4 values[8];
    vec4 times[2];   // key i's t is times[i / 4][i % 4]
    uint count;      // 0: the curve is constant 1
    uint pad0;
    uint pad1;
    uint pad2;
};

// Lifecycle and shape flags of EmitterParams.flags.
SD_CONST uint SD_EMITTER_RECYCLE = 1u;
SD_CONST uint SD_EMITTER_SHAPE_SURFACE = 2u;
SD_CONST uint SD_EMITTER_KILL_ON_COLLISION = 4u;
SD_CONST uint SD_EMITTER_COLLISIONS = 8u;

SD_CONST uint SD_SHAPE_POINT = 0u;
SD_CONST uint SD_SHAPE_SPHERE = 1u;
SD_CONST uint SD_SHAPE_BOX = 2u;
SD_CONST uint SD_SHAPE_DISK = 3u;
SD_CONST uint SD_SHAPE_CONE = 4u;

SD_CONST uint SD_INTEGRATE_EXPLICIT_EULER = 0u;
SD_CONST uint SD_INTEGRATE_SEMI_IMPLICIT_EULER = 1u;
SD_CONST uint SD_INTEGRATE_VERLET = 2u;
SD_CONST uint SD_INTEGRATE_RK4 = 3u;

// Everything the update and spawn kernels need to know about one emitter.
// 896 bytes.
struct EmitterParams {
    vec4 shapeCenter;       // xyz (m), w: shape radius (m)
    vec4 shapeHalfExtents;  // xyz (m), w: spread half-angle (rad)
    vec4 shapeDirection;    // xyz unit launch direction / disk normal / cone axis
    vec4 colorMin;
    vec4 colorMax;
    vec4 statelessGravity;  // xyz (m/s^2)
    float speedMin, speedMax, lifetimeMin, lifetimeMax;
    float sizeMin, sizeMax, rotationMin, rotationMax;
    float angularVelocityMin, angularVelocityMax, mass, lifeLossOnCollision;
    uint shapeKind, integrator, flags, keyBase;  // keyBase: emitterKeyBase(seed, emitterIndex)
    uint emitterIndex, capacity, forceMask, colliderMask;
    CurveParams colorOverLife;
    CurveParams sizeOverLife;
    float overSpeedMin, overSpeedMax;  // m/s: speeds at t = 0 and 1 of the over-speed curves
    // m/s: the carrying body's velocity share every birth adds (x, y: bodies
    // move in the xy plane); 0 for an emitter fixed in the world.
    float carriedVelocityX, carriedVelocityY;
    CurveParams colorOverSpeed;
    CurveParams sizeOverSpeed;
};

SD_CONST uint SD_FORCE_GRAVITY = 0u;
SD_CONST uint SD_FORCE_WIND = 1u;
SD_CONST uint SD_FORCE_ATTRACTOR = 2u;
SD_CONST uint SD_FORCE_VORTEX = 3u;
SD_CONST uint SD_FORCE_DAMPING = 4u;
SD_CONST uint SD_FORCE_UNDAMPING = 5u;
SD_CONST uint SD_FORCE_FLOW_FIELD = 6u;
SD_CONST uint SD_FORCE_CURL_NOISE = 7u;

// One force. 112 bytes.
struct ForceParams {
    vec4 vector;        // gravity acceleration / wind velocity (xyz)
    vec4 position;      // xyz (m), w: range (m), 0 = unlimited
    vec4 axis;          // xyz unit, w: target speed (m/s) for undamping
    vec4 flowOffset;    // sampler coordinate = p * flowScale + flowOffset; w: viscosity eta (Pa s)
    vec4 flowScale;     // (1/m), see makeForceParams; curl noise: frequency (1/m), speed (1/s), octaves
    uint kind;
    uint flowField;     // index of the flow field's data; curl noise: its seed
    float strength;
    float radius;
    float falloff;
    float pad0, pad1, pad2;
};

SD_CONST uint SD_COLLIDER_PLANE = 0u;
SD_CONST uint SD_COLLIDER_SPHERE = 1u;
SD_CONST uint SD_COLLIDER_BOX = 2u;
SD_CONST uint SD_COLLIDER_TERRAIN = 3u;
SD_CONST uint SD_COLLIDER_CUBE_MAP = 4u;

// One collider. 144 bytes.
struct ColliderParams {
    vec4 position;     // plane point / centre / terrain origin (m); w: sphere radius
    vec4 normal;       // plane unit normal
    vec4 halfExtents;  // box half extents (m)
    vec4 axisX;        // box orientation: world-space unit axes of its frame
    vec4 axisY;
    vec4 axisZ;
    vec4 grid;         // terrain: size x, size z (m), nx, nz; cube map: res
    uint kind;
    uint dataIndex;    // which height map / cube map
    float friction;    // mu
    float resilience;  // e
    float restSpeed;   // m/s, no friction below this tangential speed
    float marchStep;   // m, sampling step for terrain and cube maps
    uint pad0, pad1;
};

// One collision or death event, as both backends hand them to the application
// (ParticleEvent in include/spindrift/world.h); made by updateEvent in
// update.glsl. 32 bytes in std430 and in C++ (asserted below).
SD_CONST uint SD_EVENT_KIND_COLLISION = 0u;
SD_CONST uint SD_EVENT_KIND_DEATH = 1u;
struct EventRecord {
    vec4 positionSpeed;  // xyz: position (m); w: speed (m/s)
    uvec4 header;        // kind, collider index + 1 (0: none), emitter index, birth serial
};

// Sub-emitters (src/kernels/sub_emit.glsl): one parent particle's event.
// The event kinds a sub-emitter can follow (SpawnEvent in effects.h).
SD_CONST uint SD_SPAWN_ON_BIRTH = 0u;
SD_CONST uint SD_SPAWN_ON_DEATH = 1u;
SD_CONST uint SD_SPAWN_ON_COLLISION = 2u;
SD_CONST uint SD_SPAWN_EVENT_KINDS = 3u;

// Serials of sub-emitted particles have this bit set (and the 30 bits below
// it hashed from their request); an emitter's own births count up from 0.
SD_CONST uint SD_SUB_SERIAL_BIT = 0x40000000u;

// Where and how one parent particle's event happened. 48 bytes.
struct SpawnRequest {
    vec4 position;  // xyz (m): where the particle was at the event
    vec4 velocity;  // xyz (m/s): its velocity then
    uvec4 header;   // x: its birth serial; y: collider index + 1 (collisions; 0 otherwise); z: world step; w: kind
};

SD_END

// The C++ side must have the std430 sizes and offsets too, or the GPU would
// read garbage: a drift fails the build of every file that includes this.
#ifdef __cplusplus
#include <cstddef>
namespace spindrift::kernels {

static_assert(sizeof(EventRecord) == 32);
static_assert(sizeof(SpawnRequest) == 48);
static_assert(offsetof(SpawnRequest, header) == 32);
static_assert(offsetof(EventRecord, header) == 16);
static_assert(sizeof(CurveParams) == 176);
static_assert(offsetof(CurveParams, times) == 128);
static_assert(offsetof(CurveParams, count) == 160);

static_assert(sizeof(EmitterParams) == 896);
static_assert(offsetof(EmitterParams, speedMin) == 96);
static_assert(offsetof(EmitterParams, shapeKind) == 144);
static_assert(offsetof(EmitterParams, emitterIndex) == 160);
static_assert(offsetof(EmitterParams, colorOverLife) == 176);
static_assert(offsetof(EmitterParams, sizeOverLife) == 352);
static_assert(offsetof(EmitterParams, overSpeedMin) == 528);
static_assert(offsetof(EmitterParams, colorOverSpeed) == 544);
static_assert(offsetof(EmitterParams, sizeOverSpeed) == 720);

static_assert(sizeof(ForceParams) == 112);
static_assert(offsetof(ForceParams, kind) == 80);
static_assert(offsetof(ForceParams, falloff) == 96);

static_assert(sizeof(ColliderParams) == 144);
static_assert(offsetof(ColliderParams, kind) == 112);
static_assert(offsetof(ColliderParams, marchStep) == 132);

}  // namespace spindrift::kernels
#endif

#endif
