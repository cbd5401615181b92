// [[body]] and [[joint]]: rigid bodies with their shapes, and joints between
// bodies named in the scene.
//
// Values are read with type checks only; their ranges are validateBodyDef's
// and validateJointDef's rules (src/coupling/body_rules.h), checked once
// through validateAt. What is checked here is what only a file says: which
// keys go with which shape or joint kind, and that a motor has both its keys.
#include "coupling/body_rules.h"
#include "scene/parse_internal.h"

#include <fmt/format.h>

namespace spindrift::scene {

namespace {

glm::vec2 vec2(const Value& v) {
    const std::vector<float> xy = v.numbers(2);
    return {xy[0], xy[1]};
}

// Any number of points: how many a shape needs is validateBodyDef's rule.
std::vector<glm::vec2> points(const Value& list) {
    const std::size_t n = list.array().size();
    std::vector<glm::vec2> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(vec2(list.element(i)));
    return out;
}

BodyShapeDef parseShape(const Table& t) {
    t.allowOnly({"box", "circle", "polygon", "edge", "chain", "offset", "angle", "loop", "color"}, "a body shape");
    const std::vector<std::string_view> kinds = {"box", "circle", "polygon", "edge", "chain"};
    std::string_view kind;
    for (std::string_view k : kinds) {
        if (!t.has(k)) continue;
        if (!kind.empty()) {
            t.failAtKey(k, fmt::format("a shape is one of box, circle, polygon, edge or chain; this one already "
                                       "has \"{}\"",
                                       kind));
        }
        kind = k;
    }
    if (kind.empty()) t.fail("a shape needs one of box = [hx, hy], circle = r, polygon, edge or chain");
    BodyShapeDef s;
    const Value v = *t.find(kind);
    if (kind == "box") {
        s.kind = BodyShapeKind::Box;
        s.halfExtents = vec2(v);
    } else if (kind == "circle") {
        s.kind = BodyShapeKind::Circle;
        s.radius = v.real(body_rules::kSize);
    } else if (kind == "polygon") {
        s.kind = BodyShapeKind::Polygon;
        s.vertices = points(v);
    } else if (kind == "edge") {
        s.kind = BodyShapeKind::Edge;
        s.vertices = points(v);
    } else {
        s.kind = BodyShapeKind::Chain;
        s.vertices = points(v);
    }
    const bool placed = s.kind == BodyShapeKind::Box || s.kind == BodyShapeKind::Circle;
    if (t.has("offset") && !placed) t.failAtKey("offset", "offset applies to box and circle shapes only");
    if (t.has("angle") && s.kind != BodyShapeKind::Box) t.failAtKey("angle", "angle applies to box shapes only");
    if (t.has("loop") && s.kind != BodyShapeKind::Chain) t.failAtKey("loop", "loop applies to chain shapes only");
    if (auto o = t.find("offset")) s.offset = vec2(*o);
    s.angle = t.real("angle", s.angle, body_rules::kAngle);
    s.loop = t.boolean("loop", s.loop);
    // Type only: that each channel is >= 0 is validateBodyDef's rule.
    if (auto v = t.find("color")) s.colour = v->vec3();
    return s;
}

}  // namespace

BodyDef parseBody(const Table& t, NameTable& names) {
    t.allowOnly({"name", "type", "position", "angle", "velocity", "angular_velocity", "density", "friction",
                 "restitution", "fixed_rotation", "color", "texture", "texture_scale", "shape"},
                "a [[body]]");
    BodyDef def;
    def.name = names.add(t);
    if (auto v = t.find("type")) {
        def.type = v->choice<BodyType>(
            {{"static", BodyType::Static}, {"kinematic", BodyType::Kinematic}, {"dynamic", BodyType::Dynamic}});
    }
    if (auto v = t.find("position")) def.position = vec2(*v);
    def.angle = t.real("angle", def.angle, body_rules::kAngle);
    if (auto v = t.find("velocity")) def.linearVelocity = vec2(*v);
    def.angularVelocity = t.real("angular_velocity", def.angularVelocity, body_rules::kAngularVelocity);
    def.density = t.real("density", def.density, body_rules::kDensity);
    def.friction = t.real("friction", def.friction, body_rules::kFriction);
    def.restitution = t.real("restitution", def.restitution, body_rules::kRestitution);
    def.fixedRotation = t.boolean("fixed_rotation", def.fixedRotation);
    if (auto v = t.find("color")) def.colour = v->vec3();
    def.texture = readSurfaceTexture(t);
    for (const Table& s : tableArray(t, "shape")) def.shapes.push_back(parseShape(s));
    validateAt(t, [&] { validateBodyDef(def); });
    return def;
}

JointDef parseJoint(const Table& t, NameTable& names, const NameTable& bodies) {
    t.allowOnly({"name", "kind", "body_a", "body_b", "anchor", "axis", "limits", "motor_speed", "max_motor_torque",
                 "max_motor_force", "collide_connected"},
                "a [[joint]]");
    JointDef def;
    def.name = names.add(t);
    def.kind = t.require("kind", "\"revolute\", \"prismatic\" or \"weld\"")
                   .choice<JointKind>({{"revolute", JointKind::Revolute},
                                       {"prismatic", JointKind::Prismatic},
                                       {"weld", JointKind::Weld}});
    const Value a = t.require("body_a", "the name of a [[body]]");
    const Value b = t.require("body_b", "the name of a [[body]]");
    def.bodyA = {bodies.resolve(a) + 1};
    def.bodyB = {bodies.resolve(b) + 1};
    def.anchor = vec2(t.require("anchor", "[x, y] (m), the joint's world point"));
    const bool revolute = def.kind == JointKind::Revolute;
    const bool prismatic = def.kind == JointKind::Prismatic;
    if (auto v = t.find("axis")) {
        if (!prismatic) t.failAtKey("axis", "axis applies to prismatic joints only");
        def.axis = vec2(*v);
    }
    if (auto v = t.find("limits")) {
        if (!revolute && !prismatic) t.failAtKey("limits", "a weld joint has no limits");
        const std::vector<float> range = v->numbers(2);
        def.enableLimit = true;
        def.lower = range[0];
        def.upper = range[1];
    }
    const std::string_view maxKey = revolute ? "max_motor_torque" : "max_motor_force";
    const std::string_view otherKey = revolute ? "max_motor_force" : "max_motor_torque";
    if (t.has(otherKey) || (def.kind == JointKind::Weld && (t.has("max_motor_torque") || t.has("motor_speed")))) {
        t.failAtKey(t.has(otherKey) ? otherKey : "motor_speed",
                    revolute ? "a revolute joint's motor takes max_motor_torque (N m)"
                    : prismatic ? "a prismatic joint's motor takes max_motor_force (N)"
                                : "a weld joint has no motor");
    }
    if (t.has("motor_speed") != t.has(maxKey)) {
        t.fail(fmt::format("a motor needs both motor_speed and {}", maxKey));
    }
    if (t.has(maxKey)) {
        def.enableMotor = true;
        def.motorSpeed = t.real("motor_speed", 0.0f);
        def.maxMotor = t.real(maxKey, 0.0f, body_rules::kMaxMotor);
    }
    def.collideConnected = t.boolean("collide_connected", def.collideConnected);
    validateAt(t, [&] { validateJointDef(def); });
    return def;
}

}  // namespace spindrift::scene
