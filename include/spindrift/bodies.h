// spindrift public API: 2D rigid bodies (Box2D 2.4 inside; no Box2D type in
// this header), two-way coupled to the world's 2D fluids: water pushes and
// lifts bodies, bodies push water. Units: metres, kilograms, seconds; angles in
// radians, counter-clockwise. Bodies live in the xy plane of a world and are
// stepped on the CPU once per stepWorld(), after the fluids.
//
// Mass in 2D: a body's density is areal (kg/m^2, as Box2D's), and a 2D fluid's
// FluidDef::density is too (default 1000 kg/m^2: water in a slab 1 m thick),
// so a body of density 500 floats half submerged in a default fluid.
//
// Each step: dynamic bodies get WorldDef::bodyGravity x dt, every 2D fluid
// solves its particle-body contacts against local copies of the bodies
// (their velocities answer each contact impulse at once), the summed
// impulses go to Box2D, and Box2D steps the bodies once by dt (body contacts,
// joints). Box2D rounds polygons by 1 cm and lets rounded shapes overlap by
// 5 mm, so bodies resting on bodies stand 1.5 cm apart; the fluid sees the
// exact shapes. World colliders (ColliderDef) act on particles only.
#pragma once

#include <spindrift/export.h>

#include <spindrift/effects.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace spindrift {

/// 1-based creation serial of a joint in its world; 0 is no joint.
struct JointId { std::uint32_t index = 0; };
/// 1-based creation serial of a grab in its world; 0 is no grab.
struct GrabId { std::uint32_t index = 0; };

enum class BodyType : std::uint32_t {
    Static = 0,     ///< never moves (walls, floors, tanks)
    Kinematic = 1,  ///< moves at the velocity it is given, pushes but is never pushed
    Dynamic = 2,    ///< has mass; moved by gravity, water, contacts and joints
};

enum class BodyShapeKind : std::uint32_t { Box = 0, Circle = 1, Polygon = 2, Edge = 3, Chain = 4 };

/// One shape (Box2D fixture) of a body, in the body's frame (m, rad).
struct BodyShapeDef {
    BodyShapeKind kind = BodyShapeKind::Box;
    glm::vec2 halfExtents{0.5f};  ///< Box: half width and height (m), each > 0
    float radius = 0.5f;          ///< Circle (m), > 0
    glm::vec2 offset{0.0f};       ///< Box and Circle: centre in the body frame (m)
    float angle = 0.0f;           ///< Box: rotation in the body frame (rad)
    /// Polygon: 3 to 8 corners of a convex polygon, either winding. Edge:
    /// exactly 2 points. Chain: 2 or more points (3 or more with `loop`).
    std::vector<glm::vec2> vertices;
    bool loop = false;            ///< Chain: joins the last point to the first
    /// Linear RGB this shape is drawn in, each channel >= 0 and finite;
    /// unset: the body's colour (BodyDef::colour). Drawing only, as Box2D
    /// v3's b2ShapeDef::customColor.
    std::optional<glm::vec3> colour;
};

SPINDRIFT_API BodyShapeDef boxShape(glm::vec2 halfExtents, glm::vec2 offset = glm::vec2(0.0f), float angle = 0.0f);
SPINDRIFT_API BodyShapeDef circleShape(float radius, glm::vec2 offset = glm::vec2(0.0f));
SPINDRIFT_API BodyShapeDef polygonShape(std::vector<glm::vec2> vertices);
SPINDRIFT_API BodyShapeDef edgeShape(glm::vec2 a, glm::vec2 b);
SPINDRIFT_API BodyShapeDef chainShape(std::vector<glm::vec2> points, bool loop);

/// Largest coordinate or length (m) a body may have: positions, vertices,
/// offsets, half extents and radii. Box2D computes in single precision and
/// resolves contacts to 5 mm; at 10 km a float's step is 1 mm, and a circle
/// of radius 1e18 m overflowed its inertia and fired Box2D's assertion.
inline constexpr float kBodyMaxLength = 1.0e4f;
/// Largest density (kg/m^2) of a dynamic body: with kBodyMaxLength, its mass
/// and inertia stay finite in single precision.
inline constexpr float kBodyMaxDensity = 1.0e6f;
/// Largest speed (m/s) and angular speed (rad/s) a body may be given.
inline constexpr float kBodyMaxSpeed = 1.0e4f;
/// Most points of a chain shape.
inline constexpr std::uint32_t kBodyMaxChainPoints = 4096;

struct BodyDef {
    std::string name;
    BodyType type = BodyType::Dynamic;
    glm::vec2 position{0.0f};        ///< m, the body's origin
    float angle = 0.0f;              ///< rad
    glm::vec2 linearVelocity{0.0f};  ///< m/s
    float angularVelocity = 0.0f;    ///< rad/s
    /// kg/m^2, in (0, kBodyMaxDensity] for a dynamic body (ignored for
    /// static and kinematic ones).
    float density = 1000.0f;
    float friction = 0.6f;           ///< Coulomb coefficient against bodies, >= 0
    float restitution = 0.0f;        ///< bounce against bodies, in [0, 1]
    bool fixedRotation = false;
    /// Linear RGB the renderer draws the body's shapes in (those without a
    /// colour of their own), each channel >= 0 and finite; unset: the
    /// renderer's default (wood for a dynamic body, grey for the others).
    /// Drawing only: it changes nothing in the simulation.
    std::optional<glm::vec3> colour;
    /// An image on every shape of the body, in the body's frame (drawing only).
    SurfaceTexture texture;
    /// At least one; edges and chains only on static and kinematic bodies
    /// (they have no area, so no mass).
    std::vector<BodyShapeDef> shapes;
};

enum class JointKind : std::uint32_t {
    Revolute = 0,   ///< a hinge at `anchor`
    Prismatic = 1,  ///< a slider through `anchor` along `axis`
    Weld = 2,       ///< glued at `anchor`
};

struct JointDef {
    std::string name;
    JointKind kind = JointKind::Revolute;
    BodyId bodyA;
    BodyId bodyB;
    glm::vec2 anchor{0.0f};        ///< m, world point at creation
    glm::vec2 axis{1.0f, 0.0f};    ///< Prismatic: world direction of travel, non-zero
    /// Revolute: angle range (rad) of B relative to A; Prismatic: travel (m)
    /// along the axis from the anchor; lower <= upper.
    bool enableLimit = false;
    float lower = 0.0f;
    float upper = 0.0f;
    /// Motor: target speed (rad/s or m/s) reached with at most maxMotor
    /// (N m of torque for Revolute, N of force for Prismatic), > 0.
    bool enableMotor = false;
    float motorSpeed = 0.0f;
    float maxMotor = 0.0f;
    bool collideConnected = false;
};

/// A hand on a dynamic body (Box2D's mouse joint): the body's point that was
/// at `point` when grabbed is pulled toward a target (moveGrab) by a damped
/// spring, as a mouse drags a body.
struct GrabDef {
    BodyId body;
    glm::vec2 point{0.0f};     ///< m, world point on the body held; the first target
    /// N, the most force the spring pulls with; 0: 1000 x the body's mass,
    /// as Box2D's testbed (lifts it against 100 g).
    float maxForce = 0.0f;
    float frequency = 5.0f;    ///< Hz of the spring with the body's mass, > 0
    float dampingRatio = 0.7f; ///< >= 0; 1 is critical
};

/// A shape as drawn, in world coordinates. Circle: centre and radius; Polygon:
/// vertices counter-clockwise; Edge: 2 vertices; Chain: vertices and loop flag.
struct BodyShapeView {
    enum class Kind : std::uint32_t { Circle = 0, Polygon = 1, Edge = 2, Chain = 3 } kind;
    glm::vec2 centre{0.0f};
    float radius = 0.0f;
    std::vector<glm::vec2> vertices;
    bool loop = false;
    /// The shape's colour (BodyShapeDef::colour), else its body's
    /// (BodyDef::colour); unset when neither is (the renderer's default).
    std::optional<glm::vec3> colour;
};

struct BodySnapshot {
    BodyId id;
    std::string name;
    bool dynamic = false;
    glm::vec2 position{0.0f};        ///< m, origin
    float angle = 0.0f;              ///< rad
    glm::vec2 linearVelocity{0.0f};  ///< m/s, of the centre of mass
    float angularVelocity = 0.0f;    ///< rad/s
    std::optional<glm::vec3> colour;  ///< BodyDef::colour, linear RGB
    SurfaceTexture texture;           ///< BodyDef::texture
    std::vector<BodyShapeView> shapes;
};

/// Throws FieldError, naming the field as a scene file spells it
/// ("shape[0].box[1]"), for a body createBody would reject.
SPINDRIFT_API void validateBodyDef(const BodyDef& def);
/// Throws FieldError for a joint createJoint would reject whatever the world
/// ("limits", "max_motor_torque"); createJoint also checks its bodies exist.
SPINDRIFT_API void validateJointDef(const JointDef& def);

/// Adds a body to the world (either backend: bodies always run on the CPU).
SPINDRIFT_API BodyId createBody(WorldId world, const BodyDef& def);
/// Removes a body and the joints attached to it.
SPINDRIFT_API void destroyBody(WorldId world, BodyId body);
/// Joins two existing bodies; throws Error for a bad definition.
SPINDRIFT_API JointId createJoint(WorldId world, const JointDef& def);
SPINDRIFT_API void destroyJoint(WorldId world, JointId joint);

/// Moves a body now (teleport; for kinematic bodies prefer setBodyVelocity).
SPINDRIFT_API void setBodyTransform(WorldId world, BodyId body, glm::vec2 position, float angle);
/// Sets the velocity of a body's centre of mass (m/s) and its spin (rad/s).
SPINDRIFT_API void setBodyVelocity(WorldId world, BodyId body, glm::vec2 linearVelocity, float angularVelocity);
/// Applies an impulse (N s) at a world point (m) to a dynamic body.
SPINDRIFT_API void applyBodyImpulse(WorldId world, BodyId body, glm::vec2 impulse, glm::vec2 point);
/// Mass (kg) of a body: 0 for static and kinematic ones.
SPINDRIFT_API float bodyMass(WorldId world, BodyId body);

/// Grabs a dynamic body; throws Error for a body that is not one or a bad
/// definition. Destroying the body lets go of it.
SPINDRIFT_API GrabId createGrab(WorldId world, const GrabDef& def);
/// Where the grab pulls its point to now (m, world).
SPINDRIFT_API void moveGrab(WorldId world, GrabId grab, glm::vec2 target);
/// Lets go; a grab whose body was destroyed is already gone and this does
/// nothing. Throws Error for an id never created.
SPINDRIFT_API void destroyGrab(WorldId world, GrabId grab);
/// The dynamic body with a shape over `point` (m, world), the last created
/// when several are; index 0 when none is.
SPINDRIFT_API BodyId bodyAt(WorldId world, glm::vec2 point);

/// Bodies that exist now (created and not destroyed).
SPINDRIFT_API std::uint32_t bodyCount(WorldId world);
/// Every existing body, in creation order.
SPINDRIFT_API std::vector<BodySnapshot> readBodies(WorldId world);

}  // namespace spindrift
