// [[emitter]]: spawning, launch shape, per-particle ranges, curves, forces,
// collisions, the stateless closed form, and the sprite and trail it is drawn
// with.
// Angles in the file are degrees.
//
// Fields that have an EmitterDef rule (src/particles/emitter_rules.h) are
// read with type checks only, angles converted from degrees to the API's
// radians, and checked once by validateEmitterDef through validateAt. What is
// checked here is what only a file says: a duration left out for "forever"
// (so one written is > 0) and a burst that fits the capacity.
#include "particles/emitter_rules.h"
#include "particles/params.h"
#include "particles/sprite_rules.h"
#include "scene/parse_internal.h"

#include <fmt/format.h>

#include <glm/gtc/constants.hpp>

#include <set>

namespace spindrift::scene {

namespace {

constexpr float kRadiansPerDegree = glm::pi<float>() / 180.0f;

const std::vector<std::string_view> kEmitterKeys = {
    "name",           "lifecycle",  "capacity",
    "rate",           "bursts",     "duration",
    "shape",          "speed",      "lifetime",
    "size",           "rotation",   "angular_velocity",
    "color",          "mass",       "color_over_life",
    "size_over_life", "integrator", "forces",
    "collision",      "stateless",  "stateless_gravity",
    "sprite",         "over_speed_range", "color_over_speed",
    "size_over_speed", "body",      "inherit_velocity",
    "trail",          "spawn_on"};

FloatRange toRadians(FloatRange degrees) {
    return {degrees.min * kRadiansPerDegree, degrees.max * kRadiansPerDegree};
}

// --- Shape -------------------------------------------------------------------

std::vector<std::string_view> shapeKeys(SpawnShapeKind kind) {
    std::vector<std::string_view> keys = {"kind", "center", "direction", "spread"};
    switch (kind) {
        case SpawnShapeKind::Point:
            break;
        case SpawnShapeKind::Sphere:
            keys.insert(keys.end(), {"radius", "surface"});
            break;
        case SpawnShapeKind::Box:
            keys.insert(keys.end(), {"half_extents", "surface"});
            break;
        case SpawnShapeKind::Disk:
        case SpawnShapeKind::Cone:
            keys.push_back("radius");  // required, > 0
            break;
    }
    return keys;
}

SpawnShapeDef readShape(const Table& t) {
    SpawnShapeDef def;
    const Value kind = t.require("kind", "\"point\", \"sphere\", \"box\", \"disk\" or \"cone\"");
    def.kind = kind.choice<SpawnShapeKind>({{"point", SpawnShapeKind::Point},
                                            {"sphere", SpawnShapeKind::Sphere},
                                            {"box", SpawnShapeKind::Box},
                                            {"disk", SpawnShapeKind::Disk},
                                            {"cone", SpawnShapeKind::Cone}});
    t.allowOnly(shapeKeys(def.kind), fmt::format("a shape of kind \"{}\"", kind.string()));
    def.center = t.vec3("center", def.center);
    def.direction = t.direction("direction", def.direction);
    def.spreadAngle = t.real("spread", 0.0f) * kRadiansPerDegree;
    def.surface = t.boolean("surface", def.surface);
    if (def.kind == SpawnShapeKind::Box) {
        def.halfExtents = t.require("half_extents", "[hx, hy, hz] (m), each >= 0").vec3();
    } else if (def.kind == SpawnShapeKind::Sphere) {
        def.radius = t.require("radius", "a number >= 0 (m)").real(emitter_rules::kSphereRadius);
    } else if (def.kind != SpawnShapeKind::Point) {
        def.radius = t.require("radius", "a number > 0 (m)").real(emitter_rules::kRimRadius);
    }
    return def;
}

// --- Colours and curves ------------------------------------------------------

// [r, g, b, a]: four numbers; their ranges (emitter_rules.h) are the API's
// to check (validateEmitterDef), once.
glm::vec4 readColor(const Value& v, const FieldRule& rgb, const FieldRule& alpha) {
    if (!v.node().is_array() || v.array().size() != 4) {
        v.failExpected("a colour [r, g, b, a]");
    }
    glm::vec4 c;
    for (std::size_t i = 0; i < 3; ++i) {
        c[static_cast<int>(i)] = v.element(i).real(rgb);
    }
    c.a = v.element(3).real(alpha);
    return c;
}

// `color = [r, g, b, a]` or `color = [[r, g, b, a], [r, g, b, a]]`.
ColorRange readColorRange(const Value& v) {
    if (v.node().is_array() && v.array().size() == 2 && v.array().get(0)->is_array()) {
        return {readColor(v.element(0), emitter_rules::kColorChannel, emitter_rules::kColorAlpha),
                readColor(v.element(1), emitter_rules::kColorChannel, emitter_rules::kColorAlpha)};
    }
    if (!v.node().is_array() || v.array().size() != 4) {
        v.failExpected("a colour [r, g, b, a] or two colours [[r, g, b, a], [r, g, b, a]]");
    }
    const glm::vec4 c = readColor(v, emitter_rules::kColorChannel, emitter_rules::kColorAlpha);
    return {c, c};
}

// Keys {t = ..., value = ...}; how many, their order and ranges are the
// API's to check (validateEmitterDef), once.
Curve readCurve(const Value& v, bool colorValues) {
    const toml::array& keys = v.array();
    Curve curve;
    for (std::size_t i = 0; i < keys.size(); ++i) {
        const Value key = v.element(i);
        if (!key.node().is_table()) {
            key.failExpected("a curve key {t = ..., value = ...}");
        }
        const Table t(key.context(), *key.node().as_table(), key.path());
        t.allowOnly({"t", "value"}, "a curve key");
        CurveKey k;
        k.t = t.require("t", "a number in [0, 1] (normalised age, speed or length)").real(emitter_rules::kCurveTime);
        const Value value =
            t.require("value", colorValues ? "a colour factor [r, g, b, a]" : "a size factor >= 0");
        k.value = colorValues ? readColor(value, emitter_rules::kCurveFactor, emitter_rules::kCurveFactor)
                              : glm::vec4(value.real(emitter_rules::kCurveFactor));
        curve.keys.push_back(k);
    }
    return curve;
}

// --- Spawning ----------------------------------------------------------------

// Bursts of at most `capacity` particles: a larger one could never be born
// whole. A type error is worded with that range; the range itself is checked
// after the capacity (checkBurstCounts).
FieldRule burstCountRule(std::uint32_t capacity) { return FieldRule::whole(Bounds::between(1, capacity)); }

std::vector<BurstDef> readBursts(const Value& v, std::uint32_t capacity) {
    std::vector<BurstDef> bursts;
    for (std::size_t i = 0; i < v.array().size(); ++i) {
        const Value item = v.element(i);
        if (!item.node().is_table()) {
            item.failExpected("a burst {time = ..., count = ...}");
        }
        const Table t(item.context(), *item.node().as_table(), item.path());
        t.allowOnly({"time", "count"}, "a burst");
        BurstDef burst;
        burst.time = t.require("time", "a number >= 0 (s)").real(emitter_rules::kBurstTime);
        burst.count = t.require("count", "an integer >= 1").whole<std::uint32_t>(burstCountRule(capacity));
        bursts.push_back(burst);
    }
    return bursts;
}

void readSpawning(const Table& t, EmitterDef& def) {
    if (auto v = t.find("lifecycle")) {
        def.lifecycle =
            v->choice<Lifecycle>({{"spawn", Lifecycle::Spawn}, {"recycle", Lifecycle::Recycle}});
    }
    def.capacity = t.whole<std::uint32_t>("capacity", def.capacity, emitter_rules::kCapacity);
    // Recycle mode re-births every slot as it dies: there is nothing to pace.
    if (def.lifecycle == Lifecycle::Recycle && !def.stateless) {
        for (std::string_view key : {"rate", "bursts"}) {
            if (t.has(key)) {
                t.failAtKey(key, fmt::format("`{}` applies to lifecycle = \"spawn\" (or stateless "
                                             "emitters); a recycle emitter re-births each of its "
                                             "`capacity` slots as soon as it dies",
                                             key));
            }
        }
    }
    def.rate = t.real("rate", def.rate, emitter_rules::kRate);
    if (auto v = t.find("bursts")) {
        def.bursts = readBursts(*v, def.capacity);
    }
    // The file says "forever" by leaving duration out; the API uses -1.
    def.duration = t.real("duration", -1.0f, Bounds::positive());
}

// --- Per-particle ranges -----------------------------------------------------

void readParticleRanges(const Table& t, EmitterDef& def) {
    def.speed = t.range("speed", def.speed, emitter_rules::kSpeed);
    def.lifetime = t.range("lifetime", def.lifetime, emitter_rules::kLifetime);
    def.size = t.range("size", def.size, emitter_rules::kSize);
    if (auto v = t.find("rotation")) {
        def.rotation = toRadians(v->range(emitter_rules::kRotation));
    }
    if (auto v = t.find("angular_velocity")) {
        def.angularVelocity = toRadians(v->range(emitter_rules::kAngularVelocity));
    }
    if (auto v = t.find("color")) {
        def.color = readColorRange(*v);
    }
    def.mass = t.real("mass", def.mass, emitter_rules::kMass);
    if (auto v = t.find("color_over_life")) {
        def.colorOverLife = readCurve(*v, true);
    }
    if (auto v = t.find("size_over_life")) {
        def.sizeOverLife = readCurve(*v, false);
    }
    def.overSpeedRange = t.range("over_speed_range", def.overSpeedRange, emitter_rules::kOverSpeed);
    if (auto v = t.find("color_over_speed")) {
        def.colorOverSpeed = readCurve(*v, true);
    }
    if (auto v = t.find("size_over_speed")) {
        def.sizeOverSpeed = readCurve(*v, false);
    }
}

// --- Forces, collisions, integration -----------------------------------------

// A list of names, each resolved to its 1-based id. An empty list is refused:
// the API reads empty as "all", the opposite of what `[]` seems to say.
template <class Id>
std::vector<Id> readReferences(const Value& v, const NameTable& names, std::string_view kind) {
    const toml::array& items = v.array();
    if (items.empty()) {
        v.fail(fmt::format("expected at least one {0} name; leave the key out to use every {0}",
                           kind));
    }
    std::vector<Id> ids;
    std::set<std::uint32_t> seen;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Value item = v.element(i);
        const std::uint32_t index = names.resolve(item);
        if (!seen.insert(index).second) {
            item.fail(fmt::format("{} \"{}\" is listed twice", kind, item.string()));
        }
        ids.push_back(Id{index + 1});
    }
    return ids;
}

CollisionResponseDef readCollision(const Table& t, const NameTable& colliders) {
    t.allowOnly({"enabled", "colliders", "kill", "life_loss"}, "[emitter.collision]");
    CollisionResponseDef def;
    def.enabled = t.boolean("enabled", def.enabled);
    if (auto v = t.find("colliders")) {
        def.colliders = readReferences<ColliderId>(*v, colliders, "collider");
    }
    def.killOnCollision = t.boolean("kill", def.killOnCollision);
    def.lifeLossOnCollision = t.real("life_loss", def.lifeLossOnCollision, emitter_rules::kLifeLoss);
    return def;
}

void readStatelessRules(const Table& t, EmitterDef& def) {
    def.stateless = t.boolean("stateless", def.stateless);
    if (def.stateless) {
        for (std::string_view key : {"integrator", "forces", "collision", "mass"}) {
            if (t.has(key)) {
                t.failAtKey(key, fmt::format("`{}` has no effect on a stateless emitter: its "
                                             "particles follow p0 + v0 t + g t^2 / 2 with "
                                             "g = stateless_gravity",
                                             key));
            }
        }
        def.statelessGravity = t.vec3("stateless_gravity", def.statelessGravity);
    } else if (t.has("stateless_gravity")) {
        t.failAtKey("stateless_gravity",
                    "`stateless_gravity` applies only with stateless = true; state-preserving "
                    "emitters feel the scene's [[force]]s");
    }
}

void readDynamics(const Table& t, EmitterDef& def, const NameTable& forces,
                  const NameTable& colliders) {
    if (auto v = t.find("integrator")) {
        def.integrator =
            v->choice<Integrator>({{"explicit_euler", Integrator::ExplicitEuler},
                                   {"semi_implicit_euler", Integrator::SemiImplicitEuler},
                                   {"verlet", Integrator::Verlet},
                                   {"rk4", Integrator::Rk4}});
    }
    if (auto v = t.find("forces")) {
        def.forces = readReferences<ForceId>(*v, forces, "force");
    }
    if (auto sub = t.subTable("collision")) {
        def.collision = readCollision(*sub, colliders);
    }
}

// Checked after validateEmitterDef, so a bad capacity is reported as such and
// not as every burst being too large for it.
void checkBurstCounts(const Table& t, const EmitterDef& def) {
    const FieldRule rule = burstCountRule(def.capacity);
    for (std::size_t i = 0; i < def.bursts.size(); ++i) {
        if (!rule.bounds.contains(def.bursts[i].count)) {
            t.failAtField(fieldPath("bursts", i, "count"),
                          fmt::format("expected {}, got {}", rule.describe(), def.bursts[i].count));
        }
    }
}

// --- Drawing -------------------------------------------------------------------

FlipbookDef readFlipbook(const Table& t) {
    t.allowOnly({"rows", "columns", "frames", "fps", "blend"}, "[emitter.sprite.flipbook]");
    FlipbookDef def;
    def.rows = t.whole<std::uint32_t>("rows", def.rows, sprite_rules::kSheetSide);
    def.columns = t.whole<std::uint32_t>("columns", def.columns, sprite_rules::kSheetSide);
    def.frames = t.whole<std::uint32_t>("frames", def.frames, sprite_rules::kFrames);
    def.fps = t.real("fps", def.fps, sprite_rules::kFps);
    def.blend = t.boolean("blend", def.blend);
    return def;
}

SpriteDef readSprite(const Table& t) {
    t.allowOnly({"blend", "stretch", "texture", "flipbook", "soft_distance"}, "[emitter.sprite]");
    SpriteDef def;
    if (auto v = t.find("blend")) {
        def.blend = v->choice<SpriteBlend>(
            {{"additive", SpriteBlend::Additive}, {"alpha", SpriteBlend::Alpha}, {"oit", SpriteBlend::WeightedOit}});
    }
    def.stretch = t.real("stretch", def.stretch, sprite_rules::kStretch);
    def.softDistance = t.real("soft_distance", def.softDistance, sprite_rules::kSoftDistance);
    if (auto v = t.find("texture")) {
        def.texture = readPngPath(*v);
    }
    if (auto flipbook = t.subTable("flipbook")) {
        def.flipbook = readFlipbook(*flipbook);
    }
    return def;
}

// A sub-emitter's parent: an emitter above this one in the file that stores
// its particles (the world creates emitters in file order).
SpawnOnDef readSpawnOn(const Table& t, const NameTable& names, const std::vector<EmitterDef>& earlier) {
    t.allowOnly({"parent", "event", "count", "inherit_velocity"}, "[emitter.spawn_on]");
    SpawnOnDef def;
    const Value parent = t.require("parent", "the name of an emitter defined above this one");
    const std::uint32_t index = names.resolve(parent);
    if (index >= earlier.size()) {
        parent.fail("an emitter cannot follow its own events; expected an emitter defined above this one");
    }
    if (earlier[index].stateless) {
        parent.fail(fmt::format("emitter '{}' is stateless: a closed form has no particle events to follow; "
                                "expected a state-preserving emitter",
                                earlier[index].name));
    }
    def.parent = {index + 1};
    if (auto v = t.find("event")) {
        def.event = v->choice<SpawnEvent>(
            {{"birth", SpawnEvent::Birth}, {"death", SpawnEvent::Death}, {"collision", SpawnEvent::Collision}});
    }
    def.count = t.whole<std::uint32_t>("count", def.count, emitter_rules::kSpawnCount);
    def.inheritVelocity = t.real("inherit_velocity", def.inheritVelocity, emitter_rules::kSpawnInherit);
    return def;
}

TrailDef readTrail(const Table& t) {
    t.allowOnly({"points", "width", "width_over_length", "color_over_length"}, "[emitter.trail]");
    TrailDef def;
    def.points = t.whole<std::uint32_t>("points", def.points, emitter_rules::kTrailPoints);
    def.width = t.real("width", def.width, emitter_rules::kTrailWidth);
    if (auto v = t.find("width_over_length")) {
        def.widthOverLength = readCurve(*v, false);
    }
    if (auto v = t.find("color_over_length")) {
        def.colorOverLength = readCurve(*v, true);
    }
    return def;
}

}  // namespace

EmitterDef parseEmitter(const Table& t, NameTable& names, const NameTable& forces,
                        const NameTable& colliders, const NameTable& bodies, const std::vector<EmitterDef>& earlier) {
    t.allowOnly(kEmitterKeys, "an emitter");
    EmitterDef def;
    def.name = names.add(t);
    readStatelessRules(t, def);
    readSpawning(t, def);
    if (auto shape = t.subTable("shape")) {
        def.shape = readShape(*shape);
    }
    if (auto body = t.find("body")) def.body = {bodies.resolve(*body) + 1};
    def.inheritVelocity = t.real("inherit_velocity", def.inheritVelocity, emitter_rules::kInheritVelocity);
    readParticleRanges(t, def);
    readDynamics(t, def, forces, colliders);
    if (auto sprite = t.subTable("sprite")) {
        def.sprite = readSprite(*sprite);
    }
    if (auto trail = t.subTable("trail")) {
        def.trail = readTrail(*trail);
    }
    if (auto on = t.subTable("spawn_on")) {
        def.spawnOn = readSpawnOn(*on, names, earlier);
        if (!t.find("rate")) {
            def.rate = 0.0f;  // a file's sub-emitter emits at its parent's events only, unless it says so
        }
    }
    validateAt(t, [&] { validateEmitterDef(def); });
    checkBurstCounts(t, def);
    return def;
}

}  // namespace spindrift::scene
