#include "particles/params.h"

#include "core/field_rules.h"
#include "particles/collider_rules.h"
#include "particles/emitter_rules.h"
#include "particles/flow_field_rules.h"
#include "particles/force_rules.h"
#include "particles/sprite_rules.h"

#include "kernels/math.glsl"
#include "kernels/random.glsl"
#include "kernels/stateless.glsl"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace spindrift {
namespace {

glm::vec4 v4(glm::vec3 v, float w) { return glm::vec4(v, w); }

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The public limit (include/spindrift/effects.h) is the kernel's array size
// (src/kernels/types.glsl); the public header cannot include the kernel.
static_assert(kMaxCurveKeys == static_cast<int>(kernels::SD_MAX_CURVE_KEYS));
static_assert(sizeof(kernels::CurveParams::values) / sizeof(kernels::CurveParams::values[0]) ==
              kernels::SD_MAX_CURVE_KEYS);
// Burst b's particles get serials b * SD_BURST_SERIAL_STRIDE + j
// (src/kernels/stateless.glsl): a larger burst would run into the next one's.
static_assert(kEmitterMaxBurstCount == kernels::SD_BURST_SERIAL_STRIDE - 1);
static_assert(kMaxTrailPoints == kernels::SD_MAX_TRAIL_POINTS);
static_assert(static_cast<std::uint32_t>(SpawnEvent::Birth) == kernels::SD_SPAWN_ON_BIRTH);
static_assert(static_cast<std::uint32_t>(SpawnEvent::Death) == kernels::SD_SPAWN_ON_DEATH);
static_assert(static_cast<std::uint32_t>(SpawnEvent::Collision) == kernels::SD_SPAWN_ON_COLLISION);

// `color`'s two ends, each channel and the opacity against its rule.
void checkColorRange(const FieldCheck& check, const ColorRange& color) {
    for (const glm::vec4& end : {color.min, color.max}) {
        for (int c = 0; c < 3; ++c) {
            check.number("color", end[c], emitter_rules::kColorChannel);
        }
        check.number("color", end.a, emitter_rules::kColorAlpha);
    }
}

// A curve over normalised age: at most kMaxCurveKeys keys (the kernel's
// array), times strictly increasing in [0, 1], factors >= 0 (a size curve's
// factor is its value's x).
void checkCurve(const FieldCheck& check, std::string_view field, const Curve& curve, int channels) {
    const std::size_t count = curve.keys.size();
    check.expect(count <= static_cast<std::size_t>(kMaxCurveKeys), field,
                 fmt::format("at most {} curve keys", kMaxCurveKeys), fmt::format("{}", count));
    for (std::size_t i = 0; i < count; ++i) {
        const CurveKey& k = curve.keys[i];
        const std::string time = fieldPath(field, i, "t");
        check.number(time, k.t, emitter_rules::kCurveTime);
        if (i > 0) {
            const float previous = curve.keys[i - 1].t;
            check.expect(k.t > previous, time,
                         fmt::format("t > {} (the previous key's t): curve keys must be in strictly "
                                     "increasing t",
                                     previous),
                         fmt::format("{}", k.t));
        }
        for (int c = 0; c < channels; ++c) {
            check.number(fieldPath(field, i, "value"), k.value[c], emitter_rules::kCurveFactor);
        }
    }
}

// A trail: 0 or 2+ points, within the emitter's share of memory, on an
// emitter that stores its particles.
void checkTrail(const FieldCheck& check, const EmitterDef& d) {
    const TrailDef& t = d.trail;
    check.number("trail.points", t.points, emitter_rules::kTrailPoints);
    check.expect(t.points != 1, "trail.points", "0 (no trail) or at least 2 (a ribbon joins two points)", "1");
    if (!t.enabled()) {
        return;
    }
    if (d.stateless) {
        check.fail("trail", "a stateless emitter keeps no past positions; expected no trail, or stateless = false");
    }
    const std::uint64_t positions = std::uint64_t{d.capacity} * t.points;
    check.expect(positions <= kEmitterMaxTrailPositions, "trail.points",
                 fmt::format("capacity x points at most {} (12 bytes each)", kEmitterMaxTrailPositions),
                 fmt::format("{} x {} = {}", d.capacity, t.points, positions));
    check.number("trail.width", t.width, emitter_rules::kTrailWidth);
    checkCurve(check, "trail.width_over_length", t.widthOverLength, 1);
    checkCurve(check, "trail.color_over_length", t.colorOverLength, 4);
}

// A sub-emitter: a spawn-mode emitter that stores its particles; the parent
// is checked by the world that holds it (createEmitter).
void checkSpawnOn(const FieldCheck& check, const EmitterDef& d) {
    const SpawnOnDef& on = d.spawnOn;
    if (!on.enabled()) {
        return;
    }
    check.number("spawn_on.count", on.count, emitter_rules::kSpawnCount);
    check.number("spawn_on.inherit_velocity", on.inheritVelocity, emitter_rules::kSpawnInherit);
    if (d.stateless) {
        check.fail("spawn_on", "a stateless emitter is a closed form of time and cannot be born at events; "
                               "expected no spawn_on, or stateless = false");
    }
    if (d.lifecycle != Lifecycle::Spawn) {
        check.fail("spawn_on", "a recycle emitter re-births its own slots; expected lifecycle = \"spawn\" for a "
                               "sub-emitter");
    }
}

}  // namespace

kernels::CurveParams makeCurveParams(const Curve& curve) {
    kernels::CurveParams c;
    std::memset(&c, 0, sizeof c);
    for (std::size_t i = 0; i < curve.keys.size(); ++i) {
        c.values[i] = curve.keys[i].value;
        c.times[i / 4][i % 4] = curve.keys[i].t;
    }
    c.count = static_cast<std::uint32_t>(curve.keys.size());
    return c;
}

void validateEmitterDef(const EmitterDef& d) {
    // Each field against its rule (emitter_rules.h), named as a scene file
    // spells its key, so the scene loader can point at it (validateAt).
    namespace rules = emitter_rules;
    const FieldCheck check(objectLabel("emitter", d.name));
    check.number("capacity", d.capacity, rules::kCapacity);
    check.number("rate", d.rate, rules::kRate);
    check.number("duration", d.duration, rules::kDuration);
    for (std::size_t i = 0; i < d.bursts.size(); ++i) {
        check.number(fieldPath("bursts", i, "time"), d.bursts[i].time, rules::kBurstTime);
        check.number(fieldPath("bursts", i, "count"), d.bursts[i].count, rules::kBurstCount);
    }
    const SpawnShapeDef& s = d.shape;
    check.finite("shape.center", s.center);
    const bool rim = s.kind == SpawnShapeKind::Disk || s.kind == SpawnShapeKind::Cone;
    if (rim || s.kind == SpawnShapeKind::Sphere) {
        check.number("shape.radius", s.radius, rim ? rules::kRimRadius : rules::kSphereRadius);
    }
    if (s.kind == SpawnShapeKind::Box) {
        for (std::size_t a = 0; a < 3; ++a) {
            check.number(fieldPath("shape.half_extents", a), s.halfExtents[static_cast<int>(a)], rules::kHalfExtent);
        }
    }
    check.finite("shape.direction", s.direction);
    check.expect(glm::length(s.direction) > 0.0f, "shape.direction", "a non-zero direction",
                 fmt::format("[{}, {}, {}]", s.direction.x, s.direction.y, s.direction.z));
    check.number("shape.spread", s.spreadAngle, rules::kSpread);
    check.number("inherit_velocity", d.inheritVelocity, rules::kInheritVelocity);
    if (d.stateless && d.body.index != 0) {
        check.fail("body", "a stateless emitter is a closed form of time and cannot ride on a body; expected no "
                           "body, or stateless = false");
    }
    check.range("speed", d.speed, rules::kSpeed);
    check.range("lifetime", d.lifetime, rules::kLifetime);
    check.range("size", d.size, rules::kSize);
    check.range("rotation", d.rotation, rules::kRotation);
    check.range("angular_velocity", d.angularVelocity, rules::kAngularVelocity);
    check.number("mass", d.mass, rules::kMass);
    check.number("collision.life_loss", d.collision.lifeLossOnCollision, rules::kLifeLoss);
    checkColorRange(check, d.color);
    checkCurve(check, "color_over_life", d.colorOverLife, 4);
    checkCurve(check, "size_over_life", d.sizeOverLife, 1);
    check.range("over_speed_range", d.overSpeedRange, rules::kOverSpeed);
    checkCurve(check, "color_over_speed", d.colorOverSpeed, 4);
    checkCurve(check, "size_over_speed", d.sizeOverSpeed, 1);
    sprite_rules::validateSpriteDef(check, d.sprite);
    checkTrail(check, d);
    checkSpawnOn(check, d);
}

kernels::EmitterParams makeEmitterParams(const EmitterDef& d, std::uint32_t seed, std::uint32_t emitterIndex,
                                         std::uint32_t forceMask, std::uint32_t colliderMask) {
    validateEmitterDef(d);
    kernels::EmitterParams e;
    std::memset(&e, 0, sizeof e);
    e.shapeCenter = v4(d.shape.center, d.shape.radius);
    e.shapeHalfExtents = v4(d.shape.halfExtents, d.shape.spreadAngle);
    e.shapeDirection = v4(glm::normalize(d.shape.direction), 0.0f);
    e.colorMin = d.color.min;
    e.colorMax = d.color.max;
    e.statelessGravity = v4(d.statelessGravity, 0.0f);
    e.speedMin = d.speed.min;
    e.speedMax = d.speed.max;
    e.lifetimeMin = d.lifetime.min;
    e.lifetimeMax = d.lifetime.max;
    e.sizeMin = d.size.min;
    e.sizeMax = d.size.max;
    e.rotationMin = d.rotation.min;
    e.rotationMax = d.rotation.max;
    e.angularVelocityMin = d.angularVelocity.min;
    e.angularVelocityMax = d.angularVelocity.max;
    e.mass = d.mass;
    e.lifeLossOnCollision = d.collision.lifeLossOnCollision;
    e.shapeKind = static_cast<std::uint32_t>(d.shape.kind);
    e.integrator = static_cast<std::uint32_t>(d.integrator);
    e.flags = (d.lifecycle == Lifecycle::Recycle ? kernels::SD_EMITTER_RECYCLE : 0u) |
              (d.shape.surface ? kernels::SD_EMITTER_SHAPE_SURFACE : 0u) |
              (d.collision.killOnCollision ? kernels::SD_EMITTER_KILL_ON_COLLISION : 0u) |
              (d.collision.enabled && colliderMask != 0 ? kernels::SD_EMITTER_COLLISIONS : 0u);
    e.keyBase = kernels::emitterKeyBase(seed, emitterIndex);
    e.emitterIndex = emitterIndex;
    e.capacity = d.capacity;
    e.forceMask = forceMask;
    e.colliderMask = colliderMask;
    e.colorOverLife = makeCurveParams(d.colorOverLife);
    e.sizeOverLife = makeCurveParams(d.sizeOverLife);
    e.overSpeedMin = d.overSpeedRange.min;
    e.overSpeedMax = d.overSpeedRange.max;
    e.colorOverSpeed = makeCurveParams(d.colorOverSpeed);
    e.sizeOverSpeed = makeCurveParams(d.sizeOverSpeed);
    return e;
}

void validateFlowFieldGrid(const FlowFieldDef& d) {
    // Each field against its rule (flow_field_rules.h), named as a scene file
    // spells its key.
    namespace rules = flow_field_rules;
    const FieldCheck check(objectLabel("flow field", d.name));
    const std::uint32_t n[3] = {d.nx, d.ny, d.nz};
    for (std::size_t a = 0; a < 3; ++a) check.number(fieldPath("resolution", a), n[a], rules::kAxis);
    const std::size_t samples = static_cast<std::size_t>(d.nx) * d.ny * d.nz;
    check.expect(samples <= kFlowFieldMaxSamples, "resolution",
                 fmt::format("at most {} samples (nx * ny * nz)", kFlowFieldMaxSamples),
                 fmt::format("{} x {} x {}", d.nx, d.ny, d.nz));
    check.finite("bounds_min", d.boundsMin);
    check.finite("bounds_max", d.boundsMax);
    for (std::size_t a = 0; a < 3; ++a) {
        const float lo = d.boundsMin[static_cast<int>(a)];
        const float hi = d.boundsMax[static_cast<int>(a)];
        check.expect(hi > lo, fieldPath("bounds_max", a), fmt::format("a number > bounds_min[{}] = {}", a, lo),
                     formatNumber(hi));
    }
}

void validateFlowFieldDef(const FlowFieldDef& d) {
    validateFlowFieldGrid(d);
    const FieldCheck check(objectLabel("flow field", d.name));
    const std::size_t samples = static_cast<std::size_t>(d.nx) * d.ny * d.nz;
    check.expect(d.velocities.size() == samples, "velocities", fmt::format("{} velocities (nx * ny * nz)", samples),
                 fmt::format("{}", d.velocities.size()));
    for (std::size_t i = 0; i < d.velocities.size(); ++i) {
        if (!finite(d.velocities[i])) check.finite(fieldPath("velocities", i), d.velocities[i]);
    }
}

void validateForceDef(const ForceDef& d) {
    // Each field against its rule (force_rules.h), named as a scene file
    // spells its key for the force's kind.
    namespace rules = force_rules;
    const FieldCheck check(objectLabel("force", d.name));
    check.finite(d.kind == ForceKind::Gravity ? "acceleration" : d.kind == ForceKind::Wind ? "velocity" : "vector",
                 d.vector);
    check.finite("position", d.position);
    check.finite("axis", d.axis);
    if (d.kind == ForceKind::Vortex) {
        check.expect(glm::length(d.axis) > 0.0f, "axis", "a non-zero axis",
                     fmt::format("[{}, {}, {}]", d.axis.x, d.axis.y, d.axis.z));
    }
    const bool rate = d.kind == ForceKind::Damping || d.kind == ForceKind::Undamping || d.kind == ForceKind::Wind;
    check.number("strength", d.strength,
                 rate ? rules::kRate : (d.kind == ForceKind::CurlNoise ? rules::kNoiseStrength : rules::kStrength));
    check.number("radius", d.radius, rules::kRadius);
    check.number("falloff", d.falloff, rules::kFalloff);
    check.number("range", d.range, rules::kRange);
    check.number("target_speed", d.targetSpeed, rules::kTargetSpeed);
    check.number("viscosity", d.viscosity, rules::kViscosity);
    check.number("frequency", d.frequency, rules::kFrequency);
    check.number("speed", d.speed, rules::kSpeed);
    check.number("octaves", d.octaves, rules::kOctaves);
}

kernels::ForceParams makeForceParams(const ForceDef& d, const FlowFieldDef* flow, std::uint32_t flowIndex) {
    validateForceDef(d);
    kernels::ForceParams f;
    std::memset(&f, 0, sizeof f);
    f.vector = v4(d.vector, 0.0f);
    f.position = v4(d.position, d.range);
    glm::vec3 axis = glm::length(d.axis) > 0.0f ? glm::normalize(d.axis) : glm::vec3(0.0f, 1.0f, 0.0f);
    f.axis = v4(axis, d.targetSpeed);
    if (flow != nullptr) {
        // Velocities are samples at the grid's vertices, vertex i of n at i / (n - 1)
        // across the box; a sampler's texel i has its centre at (i + 0.5) / n.
        glm::vec3 n(flow->nx, flow->ny, flow->nz);
        glm::vec3 scale = (n - 1.0f) / (n * (flow->boundsMax - flow->boundsMin));
        glm::vec3 offset = 0.5f / n - flow->boundsMin * scale;
        f.flowOffset = v4(offset, d.viscosity);
        f.flowScale = v4(scale, 0.0f);
    }
    if (d.kind == ForceKind::CurlNoise) {
        // The layout curlNoiseVelocity (src/kernels/noise.glsl) reads.
        f.flowOffset = v4(glm::vec3(0.0f), d.viscosity);
        f.flowScale = glm::vec4(d.frequency, d.speed, static_cast<float>(d.octaves), 0.0f);
    }
    f.kind = static_cast<std::uint32_t>(d.kind);
    f.flowField = d.kind == ForceKind::CurlNoise ? d.seed : flowIndex;
    f.strength = d.strength;
    f.radius = d.radius;
    f.falloff = d.falloff;
    return f;
}

void validateColliderGrid(const ColliderDef& d) {
    namespace rules = collider_rules;
    const FieldCheck check(objectLabel("collider", d.name));
    if (d.kind == ColliderKind::Terrain) {
        check.number("resolution[0]", d.terrainNx, rules::kTerrainAxis);
        check.number("resolution[1]", d.terrainNz, rules::kTerrainAxis);
    } else if (d.kind == ColliderKind::CubeMap) {
        check.number("resolution", d.cubeResolution, rules::kCubeResolution);
    }
}

void validateColliderDef(const ColliderDef& d) {
    // Each field against its rule (collider_rules.h), named as a scene file
    // spells its key for the collider's kind.
    namespace rules = collider_rules;
    const FieldCheck check(objectLabel("collider", d.name));
    check.number("friction", d.friction, rules::kFriction);
    check.number("resilience", d.resilience, rules::kResilience);
    check.number("rest_speed", d.restSpeed, rules::kRestSpeed);
    check.finite(d.kind == ColliderKind::Plane ? "point" : d.kind == ColliderKind::Terrain ? "origin" : "center",
                 d.position);
    check.finite("normal", d.normal);
    check.finite("half_extents", d.halfExtents);
    check.finite("rotation", d.rotationDegrees);
    if (d.colour) check.colour("color", *d.colour);
    check.number("texture_scale", d.texture.scale, kTextureScale);
    switch (d.kind) {
        case ColliderKind::Plane:
            check.expect(glm::length(d.normal) > 0.0f, "normal", "a non-zero normal",
                         fmt::format("[{}, {}, {}]", d.normal.x, d.normal.y, d.normal.z));
            break;
        case ColliderKind::Sphere:
            check.number("radius", d.radius, rules::kRadius);
            break;
        case ColliderKind::Box:
            for (std::size_t a = 0; a < 3; ++a) {
                check.number(fieldPath("half_extents", a), d.halfExtents[static_cast<int>(a)], rules::kHalfExtent);
            }
            break;
        case ColliderKind::Terrain: {
            validateColliderGrid(d);
            check.number("size[0]", d.terrainSizeX, rules::kTerrainSize);
            check.number("size[1]", d.terrainSizeZ, rules::kTerrainSize);
            const std::size_t count = static_cast<std::size_t>(d.terrainNx) * d.terrainNz;
            check.expect(d.heights.size() == count, "heights", fmt::format("{} heights (nx * nz)", count),
                         fmt::format("{}", d.heights.size()));
            for (std::size_t i = 0; i < d.heights.size(); ++i) {
                if (!std::isfinite(d.heights[i])) {
                    check.number(fieldPath("heights", i), d.heights[i], FieldRule::number(Bounds::any()));
                }
            }
            break;
        }
        case ColliderKind::CubeMap: {
            validateColliderGrid(d);
            const std::size_t count = 6ull * d.cubeResolution * d.cubeResolution;
            check.expect(d.cubeDepths.size() == count, "depths", fmt::format("{} depths (6 * res * res)", count),
                         fmt::format("{}", d.cubeDepths.size()));
            for (std::size_t i = 0; i < d.cubeDepths.size(); ++i) {
                if (!(std::isfinite(d.cubeDepths[i]) && rules::kCubeDepth.bounds.contains(d.cubeDepths[i]))) {
                    check.number(fieldPath("depths", i), d.cubeDepths[i], rules::kCubeDepth);
                }
            }
            break;
        }
    }
}

kernels::ColliderParams makeColliderParams(const ColliderDef& d, std::uint32_t dataIndex) {
    validateColliderDef(d);
    kernels::ColliderParams c;
    std::memset(&c, 0, sizeof c);
    c.position = v4(d.position, d.radius);
    c.normal = v4(glm::length(d.normal) > 0.0f ? glm::normalize(d.normal) : glm::vec3(0.0f, 1.0f, 0.0f), 0.0f);
    c.halfExtents = v4(d.halfExtents, 0.0f);
    // Box frame from XYZ Euler angles: R = Rz * Ry * Rx, columns are the axes.
    // The kernels' sine and cosine (src/kernels/math.glsl), not the C
    // library's, so the frame has the same bits on every machine.
    glm::vec3 r = glm::radians(d.rotationDegrees);
    const glm::vec2 x = kernels::sdSinCos(r.x), y = kernels::sdSinCos(r.y), z = kernels::sdSinCos(r.z);
    glm::mat3 rx(1, 0, 0, 0, x.y, x.x, 0, -x.x, x.y);
    glm::mat3 ry(y.y, 0, -y.x, 0, 1, 0, y.x, 0, y.y);
    glm::mat3 rz(z.y, z.x, 0, -z.x, z.y, 0, 0, 0, 1);
    glm::mat3 rot = rz * ry * rx;
    c.axisX = v4(rot[0], 0.0f);
    c.axisY = v4(rot[1], 0.0f);
    c.axisZ = v4(rot[2], 0.0f);
    c.kind = static_cast<std::uint32_t>(d.kind);
    c.dataIndex = dataIndex;
    c.friction = d.friction;
    c.resilience = d.resilience;
    c.restSpeed = d.restSpeed;
    if (d.kind == ColliderKind::Terrain) {
        c.grid = glm::vec4(d.terrainSizeX, d.terrainSizeZ, static_cast<float>(d.terrainNx),
                           static_cast<float>(d.terrainNz));
        // Half a cell: a march this fine cannot step over a bump of the bilinear surface.
        c.marchStep = 0.5f * std::min(d.terrainSizeX / (d.terrainNx - 1), d.terrainSizeZ / (d.terrainNz - 1));
    } else if (d.kind == ColliderKind::CubeMap) {
        c.grid = glm::vec4(static_cast<float>(d.cubeResolution), 0.0f, 0.0f, 0.0f);
        float minDepth = d.cubeDepths.empty() ? 1.0f : *std::min_element(d.cubeDepths.begin(), d.cubeDepths.end());
        // About half a texel's arc at the closest surface.
        c.marchStep = std::max(1e-3f, 0.5f * 2.0f * std::max(minDepth, 1e-3f) / static_cast<float>(d.cubeResolution));
    } else {
        c.marchStep = 1.0f;
    }
    return c;
}

}  // namespace spindrift
