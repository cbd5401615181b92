// Rigid bodies on the Box2D side: the Box2D world, creating and destroying
// bodies and joints, reading them back, the Box2D step, and the jets' mounts.
// The public API by world id over these is src/world/body_api.cpp.
// About 500 lines, kept whole on purpose: every call into Box2D's bodies and
// joints is in this file (and the broad-phase query in fluid_link.cpp), so the
// Box2D conventions (b2Vec2, body user data as our slot) live in one place.
#include "coupling/body_world.h"

#include "coupling/body_rules.h"
#include "core/field_rules.h"

#include "kernels/fluid.glsl"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace spindrift {

namespace coupling {
namespace {

/// Box2D's solver iterations per step (its recommended 8 and 3).
constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;
bool finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
b2Vec2 toB2(glm::vec2 v) { return b2Vec2(v.x, v.y); }
glm::vec2 fromB2(b2Vec2 v) { return glm::vec2(v.x, v.y); }

/// Twice the signed area of a closed polygon (m^2): > 0 counter-clockwise.
double twiceArea(const std::vector<glm::vec2>& v) {
    double area = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
        const glm::vec2 a = v[i];
        const glm::vec2 b = v[(i + 1) % v.size()];
        area += static_cast<double>(a.x) * b.y - static_cast<double>(b.x) * a.y;
    }
    return area;
}

FieldCheck bodyCheck(const BodyDef& def) { return FieldCheck(objectLabel("body", def.name)); }

/// "shape[0].box": a shape's key as a scene file spells it; `index` 0-based.
std::string shapeField(std::size_t index, const BodyShapeDef& s) {
    switch (s.kind) {
    case BodyShapeKind::Box: return fieldPath("shape", index, "box");
    case BodyShapeKind::Circle: return fieldPath("shape", index, "circle");
    case BodyShapeKind::Polygon: return fieldPath("shape", index, "polygon");
    case BodyShapeKind::Edge: return fieldPath("shape", index, "edge");
    case BodyShapeKind::Chain: return fieldPath("shape", index, "chain");
    }
    return fieldPath("shape", index);
}

/// "3 to 8 [x, y] corners".
std::string counted(const FieldRule& rule, std::string_view what) {
    return fmt::format("{} to {} {}", rule.bounds.min, rule.bounds.max, what);
}

std::string pointText(glm::vec2 p) { return fmt::format("[{}, {}]", p.x, p.y); }

/// The corners counter-clockwise; throws FieldError if they are not a convex
/// polygon Box2D accepts. `index` is the shape's, 0-based.
std::vector<glm::vec2> convexPolygon(const BodyDef& def, std::size_t index, const std::vector<glm::vec2>& v) {
    const FieldCheck check = bodyCheck(def);
    const std::string field = fieldPath("shape", index, "polygon");
    const std::size_t n = v.size();
    check.expect(body_rules::kPolygonCorners.bounds.contains(static_cast<double>(n)), field,
                 counted(body_rules::kPolygonCorners, "[x, y] corners"), fmt::format("{}", n));
    const double area = twiceArea(v);
    check.expect(std::abs(area) > 0.0, field, "corners that enclose an area", "none");
    std::vector<glm::vec2> ccw(v);
    if (area < 0.0) ccw.assign(v.rbegin(), v.rend());
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = ccw[i], b = ccw[(i + 1) % n], c = ccw[(i + 2) % n];
        check.expect(glm::length(b - a) >= body_rules::kMinGap, field,
                     fmt::format("corners at least {} m apart", body_rules::kMinGap),
                     fmt::format("{} and {}", pointText(ccw[i]), pointText(ccw[(i + 1) % n])));
        check.expect((b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x) > 0.0, field, "a strictly convex polygon",
                     fmt::format("a corner at {} that is not", pointText(ccw[(i + 1) % n])));
    }
    return ccw;
}

void coordinates(const FieldCheck& check, std::string_view field, glm::vec2 p) {
    check.number(fmt::format("{}[0]", field), p.x, body_rules::kCoordinate);
    check.number(fmt::format("{}[1]", field), p.y, body_rules::kCoordinate);
}

void validateShape(const BodyDef& def, std::size_t index, const BodyShapeDef& s) {
    namespace rules = body_rules;
    const FieldCheck check = bodyCheck(def);
    const std::string field = shapeField(index, s);
    for (std::size_t i = 0; i < s.vertices.size(); ++i) coordinates(check, fieldPath(field, i), s.vertices[i]);
    coordinates(check, fieldPath("shape", index, "offset"), s.offset);
    check.number(fieldPath("shape", index, "angle"), s.angle, rules::kAngle);
    if (s.colour) check.colour(fieldPath("shape", index, "color"), *s.colour);
    switch (s.kind) {
    case BodyShapeKind::Box:
        check.number(field + "[0]", s.halfExtents.x, rules::kSize);
        check.number(field + "[1]", s.halfExtents.y, rules::kSize);
        break;
    case BodyShapeKind::Circle: check.number(field, s.radius, rules::kSize); break;
    case BodyShapeKind::Polygon: convexPolygon(def, index, s.vertices); break;
    case BodyShapeKind::Edge:
    case BodyShapeKind::Chain: {
        const bool edge = s.kind == BodyShapeKind::Edge;
        const std::size_t n = s.vertices.size();
        if (edge) {
            check.expect(n == 2, field, "exactly 2 [x, y] points", fmt::format("{}", n));
        } else {
            check.expect(rules::kChainPoints.bounds.contains(static_cast<double>(n)), field,
                         counted(rules::kChainPoints, "[x, y] points"), fmt::format("{}", n));
            check.expect(!s.loop || n >= 3, field, "at least 3 points in a loop", fmt::format("{}", n));
        }
        for (std::size_t i = 1; i < n; ++i) {
            check.expect(glm::length(s.vertices[i] - s.vertices[i - 1]) >= rules::kMinGap, field,
                         fmt::format("points at least {} m apart", rules::kMinGap),
                         fmt::format("{} and {}", pointText(s.vertices[i - 1]), pointText(s.vertices[i])));
        }
        check.expect(def.type != BodyType::Dynamic, field,
                     "a static or kinematic body (an edge or chain has no area, so no mass)", "a dynamic body");
        break;
    }
    default: check.fail(fieldPath("shape", index), "expected a known shape kind");
    }
}

glm::vec2 rotate(float angle, glm::vec2 v) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

std::vector<glm::vec2> boxCorners(const BodyShapeDef& s) {
    const glm::vec2 h = s.halfExtents;
    std::vector<glm::vec2> v = {{-h.x, -h.y}, {h.x, -h.y}, {h.x, h.y}, {-h.x, h.y}};
    for (glm::vec2& p : v) p = s.offset + rotate(s.angle, p);
    return v;
}

/// Fluid shapes of a body in its frame: boxes are polygons, chains segments.
std::vector<LocalShape> fluidShapes(const BodyDef& def) {
    std::vector<LocalShape> out;
    for (std::size_t i = 0; i < def.shapes.size(); ++i) {
        const BodyShapeDef& s = def.shapes[i];
        switch (s.kind) {
        case BodyShapeKind::Box: out.push_back({kernels::SD_BODY_SHAPE_POLYGON, boxCorners(s), 0.0f}); break;
        case BodyShapeKind::Circle: out.push_back({kernels::SD_BODY_SHAPE_CIRCLE, {s.offset}, s.radius}); break;
        case BodyShapeKind::Polygon:
            out.push_back({kernels::SD_BODY_SHAPE_POLYGON, convexPolygon(def, i, s.vertices), 0.0f});
            break;
        case BodyShapeKind::Edge:
        case BodyShapeKind::Chain: {
            const std::size_t n = s.vertices.size();
            const std::size_t segments = s.loop && s.kind == BodyShapeKind::Chain ? n : n - 1;
            for (std::size_t k = 0; k < segments; ++k) {
                out.push_back({kernels::SD_BODY_SHAPE_SEGMENT, {s.vertices[k], s.vertices[(k + 1) % n]}, 0.0f});
            }
            break;
        }
        }
    }
    return out;
}

void addFixture(b2Body* body, const BodyDef& def, const BodyShapeDef& s, std::size_t index) {
    b2FixtureDef fd;
    fd.density = def.type == BodyType::Dynamic ? def.density : 0.0f;
    fd.friction = def.friction;
    fd.restitution = def.restitution;
    b2PolygonShape polygon;
    b2CircleShape circle;
    b2EdgeShape edge;
    b2ChainShape chain;
    std::vector<b2Vec2> points;
    switch (s.kind) {
    case BodyShapeKind::Box:
        polygon.SetAsBox(s.halfExtents.x, s.halfExtents.y, toB2(s.offset), s.angle);
        fd.shape = &polygon;
        break;
    case BodyShapeKind::Circle:
        circle.m_p = toB2(s.offset);
        circle.m_radius = s.radius;
        fd.shape = &circle;
        break;
    case BodyShapeKind::Polygon: {
        for (glm::vec2 p : convexPolygon(def, index, s.vertices)) points.push_back(toB2(p));
        polygon.Set(points.data(), static_cast<int32>(points.size()));
        fd.shape = &polygon;
        break;
    }
    case BodyShapeKind::Edge:
        edge.SetTwoSided(toB2(s.vertices[0]), toB2(s.vertices[1]));
        fd.shape = &edge;
        break;
    case BodyShapeKind::Chain: {
        for (glm::vec2 p : s.vertices) points.push_back(toB2(p));
        const auto n = static_cast<int32>(points.size());
        if (s.loop) {
            chain.CreateLoop(points.data(), n);
        } else {
            // Ghost vertices: the chain's own ends (no neighbouring chain).
            chain.CreateChain(points.data(), n, points.front(), points.back());
        }
        fd.shape = &chain;
        break;
    }
    }
    body->CreateFixture(&fd);
}

JointSlot& jointFromId(BodyWorld& b, JointId id) {
    if (id.index == 0 || id.index > b.joints.size() || b.joints[id.index - 1].joint == nullptr) {
        throw Error(fmt::format("joint id {} does not exist in this world", id.index));
    }
    return b.joints[id.index - 1];
}

BodyShapeView view(const BodyShapeDef& s, const b2Transform& xf) {
    auto toWorld = [&](glm::vec2 p) { return fromB2(b2Mul(xf, toB2(p))); };
    BodyShapeView v;
    switch (s.kind) {
    case BodyShapeKind::Circle:
        v.kind = BodyShapeView::Kind::Circle;
        v.centre = toWorld(s.offset);
        v.radius = s.radius;
        return v;
    case BodyShapeKind::Box:
    case BodyShapeKind::Polygon: {
        v.kind = BodyShapeView::Kind::Polygon;
        std::vector<glm::vec2> local = s.kind == BodyShapeKind::Box ? boxCorners(s) : s.vertices;
        if (twiceArea(local) < 0.0) std::reverse(local.begin(), local.end());
        for (glm::vec2 p : local) v.vertices.push_back(toWorld(p));
        break;
    }
    case BodyShapeKind::Edge:
    case BodyShapeKind::Chain:
        v.kind = s.kind == BodyShapeKind::Edge ? BodyShapeView::Kind::Edge : BodyShapeView::Kind::Chain;
        v.loop = s.kind == BodyShapeKind::Chain && s.loop;
        for (glm::vec2 p : s.vertices) v.vertices.push_back(toWorld(p));
        break;
    }
    glm::vec2 sum(0.0f);
    for (glm::vec2 p : v.vertices) sum += p;
    v.centre = v.vertices.empty() ? v.centre : sum / static_cast<float>(v.vertices.size());
    return v;
}

}  // namespace

BodyWorld::BodyWorld(glm::vec2 g) : gravity(g) {
    // Bodies in water are rarely still, and a sleeping body would not feel the
    // gravity added outside Box2D; the fluid wakes what it touches anyway.
    world.SetAllowSleeping(false);
}

BodySlot& bodyFromId(BodyWorld& b, BodyId id) {
    if (id.index == 0 || id.index > b.bodies.size() || b.bodies[id.index - 1].body == nullptr) {
        throw Error(fmt::format("body id {} does not exist in this world", id.index));
    }
    return b.bodies[id.index - 1];
}

void beginBodyStep(BodyWorld& b, float dt) {
    const b2Vec2 dv = toB2(b.gravity * dt);
    for (BodySlot& s : b.bodies) {
        if (s.body != nullptr && s.body->GetType() == b2_dynamicBody) {
            s.body->SetLinearVelocity(s.body->GetLinearVelocity() + dv);
        }
    }
}

namespace {

bool finiteBody(const b2Body& body) {
    return finite(fromB2(body.GetPosition())) && std::isfinite(body.GetAngle()) &&
           finite(fromB2(body.GetLinearVelocity())) && std::isfinite(body.GetAngularVelocity());
}

/// Freezes the bodies that are no longer finite (before Box2D sees them: its
/// broad phase asserts on a NaN bound) and records the others' poses.
void freezeNonFinite(BodyWorld& b, std::vector<BodyId>& frozen) {
    for (std::size_t i = 0; i < b.bodies.size(); ++i) {
        BodySlot& s = b.bodies[i];
        if (s.body == nullptr) continue;
        if (finiteBody(*s.body)) {
            s.lastPosition = s.body->GetPosition();
            s.lastAngle = s.body->GetAngle();
            continue;
        }
        s.body->SetTransform(s.lastPosition, s.lastAngle);
        s.body->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
        s.body->SetAngularVelocity(0.0f);
        s.body->SetType(b2_staticBody);
        frozen.push_back(BodyId{static_cast<std::uint32_t>(i + 1)});
    }
}

}  // namespace

std::vector<BodyId> stepBodies(BodyWorld& b, float dt) {
    std::vector<BodyId> frozen;
    freezeNonFinite(b, frozen);
    b.world.Step(dt, kVelocityIterations, kPositionIterations);
    freezeNonFinite(b, frozen);
    return frozen;
}

fluid::JetMount jetMount(const BodyWorld* bodies, BodyId id) {
    fluid::JetMount m;
    if (id.index == 0) return m;
    if (bodies == nullptr || id.index > bodies->bodies.size() || bodies->bodies[id.index - 1].body == nullptr) {
        m.active = false;
        return m;
    }
    const b2Body& body = *bodies->bodies[id.index - 1].body;
    m.origin = fromB2(body.GetPosition());
    m.angle = body.GetAngle();
    m.centre = fromB2(body.GetWorldCenter());
    m.velocity = fromB2(body.GetLinearVelocity());
    m.angularVelocity = body.GetAngularVelocity();
    return m;
}

void applyRecoil(BodyWorld* bodies, BodyId id, const fluid::JetMount& m) {
    if (id.index == 0 || !m.active || (m.recoil.x == 0.0f && m.recoil.y == 0.0f)) return;
    b2Body* body = bodies->bodies[id.index - 1].body;
    if (body->GetType() == b2_dynamicBody) body->ApplyLinearImpulse(toB2(m.recoil), toB2(m.nozzle), true);
}

void checkJetBody(BodyWorld* bodies, const FluidJetDef& jet) {
    if (jet.body.index == 0) return;
    if (bodies == nullptr) {
        throw Error(fmt::format("a jet rides body id {}, but the world has no bodies", jet.body.index));
    }
    bodyFromId(*bodies, jet.body);
}

}  // namespace coupling


BodyShapeDef boxShape(glm::vec2 halfExtents, glm::vec2 offset, float angle) {
    BodyShapeDef s;
    s.kind = BodyShapeKind::Box;
    s.halfExtents = halfExtents;
    s.offset = offset;
    s.angle = angle;
    return s;
}

BodyShapeDef circleShape(float radius, glm::vec2 offset) {
    BodyShapeDef s;
    s.kind = BodyShapeKind::Circle;
    s.radius = radius;
    s.offset = offset;
    return s;
}

BodyShapeDef polygonShape(std::vector<glm::vec2> vertices) {
    BodyShapeDef s;
    s.kind = BodyShapeKind::Polygon;
    s.vertices = std::move(vertices);
    return s;
}

BodyShapeDef edgeShape(glm::vec2 a, glm::vec2 b) {
    BodyShapeDef s;
    s.kind = BodyShapeKind::Edge;
    s.vertices = {a, b};
    return s;
}

BodyShapeDef chainShape(std::vector<glm::vec2> points, bool loop) {
    BodyShapeDef s;
    s.kind = BodyShapeKind::Chain;
    s.vertices = std::move(points);
    s.loop = loop;
    return s;
}

void validateBodyDef(const BodyDef& def) {
    // Each field against its rule (body_rules.h), named as a scene file
    // spells its key.
    namespace rules = body_rules;
    const FieldCheck check = coupling::bodyCheck(def);
    check.expect(def.type == BodyType::Static || def.type == BodyType::Kinematic || def.type == BodyType::Dynamic,
                 "type", "\"static\", \"kinematic\" or \"dynamic\"",
                 fmt::format("{}", static_cast<std::uint32_t>(def.type)));
    coupling::coordinates(check, "position", def.position);
    check.number("angle", def.angle, rules::kAngle);
    check.finite("velocity", def.linearVelocity);
    check.expect(glm::length(def.linearVelocity) <= kBodyMaxSpeed, "velocity",
                 fmt::format("a speed of at most {} m/s", kBodyMaxSpeed),
                 coupling::pointText(def.linearVelocity));
    check.number("angular_velocity", def.angularVelocity, rules::kAngularVelocity);
    if (def.type == BodyType::Dynamic) check.number("density", def.density, rules::kDensity);
    check.number("friction", def.friction, rules::kFriction);
    check.number("restitution", def.restitution, rules::kRestitution);
    if (def.colour) check.colour("color", *def.colour);
    check.number("texture_scale", def.texture.scale, kTextureScale);
    check.expect(!def.shapes.empty(), "shape", "at least one shape", "none");
    for (std::size_t i = 0; i < def.shapes.size(); ++i) coupling::validateShape(def, i, def.shapes[i]);
}

void validateJointDef(const JointDef& def) {
    namespace rules = body_rules;
    const FieldCheck check(objectLabel("joint", def.name));
    const bool revolute = def.kind == JointKind::Revolute;
    const bool prismatic = def.kind == JointKind::Prismatic;
    check.expect(revolute || prismatic || def.kind == JointKind::Weld, "kind",
                 "\"revolute\", \"prismatic\" or \"weld\"", fmt::format("{}", static_cast<std::uint32_t>(def.kind)));
    check.expect(def.bodyA.index != def.bodyB.index, "body_b", "a body other than body_a", "the same body");
    check.finite("anchor", def.anchor);
    check.finite("axis", def.axis);
    if (prismatic) {
        check.expect(glm::length(def.axis) > 0.0f, "axis", "a non-zero [x, y] direction",
                     coupling::pointText(def.axis));
    }
    if (def.enableLimit) {
        check.range("limits", {def.lower, def.upper}, FieldRule::number(Bounds::any()));
    }
    if (def.enableMotor) {
        check.number("motor_speed", def.motorSpeed, FieldRule::number(Bounds::any()));
        check.number(revolute ? "max_motor_torque" : "max_motor_force", def.maxMotor, rules::kMaxMotor);
    }
}

namespace coupling {

BodyId createBody(BodyWorld& b, const BodyDef& def) {
    b2BodyDef bd;
    bd.type = def.type == BodyType::Static ? b2_staticBody : def.type == BodyType::Kinematic ? b2_kinematicBody
                                                                                               : b2_dynamicBody;
    bd.position = coupling::toB2(def.position);
    bd.angle = def.angle;
    bd.linearVelocity = coupling::toB2(def.linearVelocity);
    bd.angularVelocity = def.angularVelocity;
    bd.fixedRotation = def.fixedRotation;
    // The 1-based slot, to map Box2D's broad-phase answers back to our bodies.
    bd.userData.pointer = static_cast<uintptr_t>(b.bodies.size() + 1);
    b2Body* body = b.world.CreateBody(&bd);
    for (std::size_t i = 0; i < def.shapes.size(); ++i) coupling::addFixture(body, def, def.shapes[i], i);
    b.bodies.push_back({body, def, coupling::fluidShapes(def), bd.position, bd.angle});
    b.alive += 1;
    return {static_cast<std::uint32_t>(b.bodies.size())};
}

void destroyBody(BodyWorld* bodies, BodyId bodyId) {
    if (!bodies) throw Error(fmt::format("body id {} does not exist in this world", bodyId.index));
    coupling::BodySlot& slot = coupling::bodyFromId(*bodies, bodyId);
    // Box2D destroys the body's joints with it; forget them first.
    for (coupling::JointSlot& j : bodies->joints) {
        if (j.joint != nullptr && (j.joint->GetBodyA() == slot.body || j.joint->GetBodyB() == slot.body)) {
            j.joint = nullptr;
        }
    }
    for (b2MouseJoint*& grab : bodies->grabs) {
        if (grab != nullptr && grab->GetBodyB() == slot.body) grab = nullptr;
    }
    bodies->world.DestroyBody(slot.body);
    slot.body = nullptr;
    bodies->alive -= 1;
}

GrabId createGrab(BodyWorld* bodies, const GrabDef& def) {
    if (!bodies) throw Error(fmt::format("grab: body id {} does not exist in this world", def.body.index));
    b2Body* body = coupling::bodyFromId(*bodies, def.body).body;
    if (body->GetType() != b2_dynamicBody) throw Error(fmt::format("grab: body id {} is not dynamic", def.body.index));
    if (!std::isfinite(def.point.x) || !std::isfinite(def.point.y) || !(def.maxForce >= 0.0f) ||
        !std::isfinite(def.maxForce) || !(def.frequency > 0.0f) || !std::isfinite(def.frequency) ||
        !(def.dampingRatio >= 0.0f) || !std::isfinite(def.dampingRatio)) {
        throw Error("grab: expected a finite point, max_force >= 0, frequency > 0 and damping_ratio >= 0");
    }
    if (bodies->ground == nullptr) {
        b2BodyDef ground;
        bodies->ground = bodies->world.CreateBody(&ground);
    }
    b2MouseJointDef jd;
    jd.bodyA = bodies->ground;
    jd.bodyB = body;
    jd.target = coupling::toB2(def.point);
    // Box2D's testbed pulls with 1000 times the mass: strong enough to lift
    // and swing a body against gravity, bounded so a heavy one lags.
    jd.maxForce = def.maxForce > 0.0f ? def.maxForce : 1000.0f * body->GetMass();
    b2LinearStiffness(jd.stiffness, jd.damping, def.frequency, def.dampingRatio, jd.bodyA, jd.bodyB);
    body->SetAwake(true);
    bodies->grabs.push_back(static_cast<b2MouseJoint*>(bodies->world.CreateJoint(&jd)));
    return {static_cast<std::uint32_t>(bodies->grabs.size())};
}

namespace {
b2MouseJoint* grabFromId(BodyWorld* bodies, GrabId id) {
    if (!bodies || id.index == 0 || id.index > bodies->grabs.size()) {
        throw Error(fmt::format("grab id {} does not exist in this world", id.index));
    }
    return bodies->grabs[id.index - 1];  // null: gone with its body
}
}  // namespace

void moveGrab(BodyWorld* bodies, GrabId id, glm::vec2 target) {
    if (!std::isfinite(target.x) || !std::isfinite(target.y)) throw Error("grab: the target is not finite");
    if (b2MouseJoint* grab = grabFromId(bodies, id)) grab->SetTarget(coupling::toB2(target));
}

void destroyGrab(BodyWorld* bodies, GrabId id) {
    if (b2MouseJoint* grab = grabFromId(bodies, id)) {
        bodies->world.DestroyJoint(grab);
        bodies->grabs[id.index - 1] = nullptr;
    }
}

BodyId bodyAt(const BodyWorld* bodies, glm::vec2 point) {
    if (!bodies) return {};
    // The last created first: of bodies that overlap, the one made later is
    // usually the one placed on top.
    for (std::size_t i = bodies->bodies.size(); i-- > 0;) {
        const b2Body* body = bodies->bodies[i].body;
        if (body == nullptr || body->GetType() != b2_dynamicBody) continue;
        for (const b2Fixture* f = body->GetFixtureList(); f != nullptr; f = f->GetNext()) {
            if (f->TestPoint(coupling::toB2(point))) return {static_cast<std::uint32_t>(i + 1)};
        }
    }
    return {};
}

JointId createJoint(BodyWorld* bodies, const JointDef& def) {
    const std::string name = fmt::format("joint '{}'", def.name);
    if (!bodies) throw Error(fmt::format("{}: the world has no bodies", name));
    validateJointDef(def);
    b2Body* a = coupling::bodyFromId(*bodies, def.bodyA).body;
    b2Body* b = coupling::bodyFromId(*bodies, def.bodyB).body;
    b2Joint* joint = nullptr;
    switch (def.kind) {
    case JointKind::Revolute: {
        b2RevoluteJointDef jd;
        jd.Initialize(a, b, coupling::toB2(def.anchor));
        jd.enableLimit = def.enableLimit;
        jd.lowerAngle = def.lower;
        jd.upperAngle = def.upper;
        jd.enableMotor = def.enableMotor;
        jd.motorSpeed = def.motorSpeed;
        jd.maxMotorTorque = def.maxMotor;
        jd.collideConnected = def.collideConnected;
        joint = bodies->world.CreateJoint(&jd);
        break;
    }
    case JointKind::Prismatic: {
        b2PrismaticJointDef jd;
        jd.Initialize(a, b, coupling::toB2(def.anchor), coupling::toB2(glm::normalize(def.axis)));
        jd.enableLimit = def.enableLimit;
        jd.lowerTranslation = def.lower;
        jd.upperTranslation = def.upper;
        jd.enableMotor = def.enableMotor;
        jd.motorSpeed = def.motorSpeed;
        jd.maxMotorForce = def.maxMotor;
        jd.collideConnected = def.collideConnected;
        joint = bodies->world.CreateJoint(&jd);
        break;
    }
    case JointKind::Weld: {
        b2WeldJointDef jd;
        jd.Initialize(a, b, coupling::toB2(def.anchor));
        jd.collideConnected = def.collideConnected;
        joint = bodies->world.CreateJoint(&jd);
        break;
    }
    default: throw Error(fmt::format("{}: unknown joint kind", name));
    }
    bodies->joints.push_back({joint, def});
    return {static_cast<std::uint32_t>(bodies->joints.size())};
}

void destroyJoint(BodyWorld* bodies, JointId jointId) {
    if (!bodies) throw Error(fmt::format("joint id {} does not exist in this world", jointId.index));
    coupling::JointSlot& j = coupling::jointFromId(*bodies, jointId);
    bodies->world.DestroyJoint(j.joint);
    j.joint = nullptr;
}

namespace {
b2Body& liveBody(BodyWorld* bodies, BodyId bodyId) {
    if (!bodies) throw Error(fmt::format("body id {} does not exist in this world", bodyId.index));
    return *coupling::bodyFromId(*bodies, bodyId).body;
}
}  // namespace

void setBodyTransform(BodyWorld* bodies, BodyId bodyId, glm::vec2 position, float angle) {
    if (!coupling::finite(position) || !std::isfinite(angle)) throw Error("setBodyTransform: not finite");
    liveBody(bodies, bodyId).SetTransform(coupling::toB2(position), angle);
}

void setBodyVelocity(BodyWorld* bodies, BodyId bodyId, glm::vec2 linearVelocity, float angularVelocity) {
    if (!coupling::finite(linearVelocity) || !std::isfinite(angularVelocity)) {
        throw Error("setBodyVelocity: not finite");
    }
    b2Body& body = liveBody(bodies, bodyId);
    body.SetLinearVelocity(coupling::toB2(linearVelocity));
    body.SetAngularVelocity(angularVelocity);
}

void applyBodyImpulse(BodyWorld* bodies, BodyId bodyId, glm::vec2 impulse, glm::vec2 point) {
    if (!coupling::finite(impulse) || !coupling::finite(point)) throw Error("applyBodyImpulse: not finite");
    liveBody(bodies, bodyId).ApplyLinearImpulse(coupling::toB2(impulse), coupling::toB2(point), true);
}

float bodyMass(BodyWorld* bodies, BodyId bodyId) { return liveBody(bodies, bodyId).GetMass(); }

std::uint32_t bodyCount(const BodyWorld* bodies) {
    return bodies ? bodies->alive : 0u;
}

std::vector<BodySnapshot> readBodies(const BodyWorld* bodies) {
    std::vector<BodySnapshot> out;
    if (!bodies) return out;
    for (std::size_t i = 0; i < bodies->bodies.size(); ++i) {
        const coupling::BodySlot& slot = bodies->bodies[i];
        if (slot.body == nullptr) continue;
        BodySnapshot s;
        s.id = {static_cast<std::uint32_t>(i + 1)};
        s.name = slot.def.name;
        s.dynamic = slot.body->GetType() == b2_dynamicBody;
        s.position = coupling::fromB2(slot.body->GetPosition());
        s.angle = slot.body->GetAngle();
        s.linearVelocity = coupling::fromB2(slot.body->GetLinearVelocity());
        s.angularVelocity = slot.body->GetAngularVelocity();
        s.colour = slot.def.colour;
        s.texture = slot.def.texture;
        for (const BodyShapeDef& shape : slot.def.shapes) {
            BodyShapeView v = coupling::view(shape, slot.body->GetTransform());
            v.colour = shape.colour ? shape.colour : slot.def.colour;  // a shape's own colour wins
            s.shapes.push_back(std::move(v));
        }
        out.push_back(std::move(s));
    }
    return out;
}

}  // namespace coupling

}  // namespace spindrift
