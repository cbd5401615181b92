// Emitters riding bodies (EmitterDef::body, issue 18 item 5), on both
// backends. Expected values are the rigid-body closed form: a point fixed in
// a body at offset o from its origin is at x + R(theta) o and moves at
// v + omega x (x + R(theta) o - c); a direction d fixed in it points along
// R(theta) d. The world places the emitter from the body's pose at the start
// of each step, so each step's births use that pose (read with readBodies
// before the step).
#include "gpu/gpu_test_util.h"

#include <spindrift/bodies.h>
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace spindrift {
namespace {

using test::GpuTest;

glm::dvec2 turn(glm::dvec2 v, double angle) {
    return {std::cos(angle) * v.x - std::sin(angle) * v.y, std::sin(angle) * v.x + std::cos(angle) * v.y};
}

// A kinematic wheel at (1, 2) moving at (0.5, 0) m/s and turning at pi rad/s
// (half a turn per second); a sparks emitter on its rim, 0.5 m out along the
// body's x axis, launching along that axis at 2 m/s and inheriting half of
// the rim's velocity. No forces: a particle keeps its birth velocity.
void checkRimEmitter(Backend backend) {
    test::ScopedWorld w(1, 7, backend);
    BodyDef wheel;
    wheel.type = BodyType::Kinematic;
    wheel.position = {1.0f, 2.0f};
    wheel.linearVelocity = {0.5f, 0.0f};
    wheel.angularVelocity = std::numbers::pi_v<float>;
    wheel.shapes = {circleShape(0.5f)};
    const BodyId body = createBody(w.id, wheel);
    EmitterDef sparks;
    sparks.name = "sparks";
    sparks.capacity = 200;
    sparks.rate = 60.0f;  // one birth a step
    sparks.lifetime = {10.0f, 10.0f};
    sparks.speed = {2.0f, 2.0f};
    sparks.shape.kind = SpawnShapeKind::Sphere;
    sparks.shape.radius = 0.0f;  // a point
    sparks.shape.center = {0.5f, 0.0f, 0.25f};
    sparks.shape.direction = {1.0f, 0.0f, 0.0f};
    sparks.shape.spreadAngle = 0.0f;
    sparks.body = body;
    sparks.inheritVelocity = 0.5f;
    const EmitterId e = createEmitter(w.id, sparks);
    const float dt = 1.0f / 60.0f;
    int checked = 0;
    for (int step = 0; step < 24; ++step) {  // 0.4 s: 72 degrees of turn
        const BodySnapshot pose = readBodies(w.id).front();
        stepWorld(w.id, dt);
        const ParticleSnapshot p = readParticles(w.id, e);
        if (p.count() == 0) continue;
        const std::size_t newest =
            static_cast<std::size_t>(std::max_element(p.birth.begin(), p.birth.end()) - p.birth.begin());
        // The rim point and its velocity (the wheel's centre of mass is its origin).
        const glm::dvec2 r = turn({0.5, 0.0}, pose.angle);
        const glm::dvec2 rim = glm::dvec2(pose.position) + r;
        const glm::dvec2 rimVelocity =
            glm::dvec2(pose.linearVelocity) + static_cast<double>(pose.angularVelocity) * glm::dvec2(-r.y, r.x);
        const glm::dvec2 launch = turn({2.0, 0.0}, pose.angle) + 0.5 * rimVelocity;
        // Velocity: float arithmetic of sines, cosines and a few products,
        // 1e-4 m/s on values of about 2.5 m/s.
        EXPECT_NEAR(p.velocity[newest].x, launch.x, 1e-4) << "step " << step;
        EXPECT_NEAR(p.velocity[newest].y, launch.y, 1e-4) << "step " << step;
        EXPECT_EQ(p.velocity[newest].z, 0.0f);
        // Position: born at the rim point some time in the step, so within
        // |v| dt of it (plus 1e-5 m of rounding); z from the offset.
        const double travelled = glm::length(glm::dvec2(p.position[newest]) - rim);
        EXPECT_LE(travelled, glm::length(launch) * dt + 1e-5) << "step " << step;
        EXPECT_NEAR(p.position[newest].z, 0.25, 1e-6);
        ++checked;
    }
    EXPECT_GE(checked, 20);
}

TEST(EmitterOnBody, FollowsTheBodysPoseAndInheritsItsVelocityOnTheCpu) { checkRimEmitter(Backend::Cpu); }

class EmitterOnBodyGpu : public GpuTest {};

TEST_F(EmitterOnBodyGpu, FollowsTheBodysPoseAndInheritsItsVelocityOnVulkan) { checkRimEmitter(Backend::Vulkan); }

// Bad definitions are refused where they enter: a body the world does not
// have, a stateless emitter on a body, a share outside [0, 1]; in a scene
// file at the key, with the line.
TEST(EmitterOnBody, BadDefinitionsAreRefused) {
    test::ScopedWorld w;
    EmitterDef e;
    e.body = BodyId{3};
    EXPECT_THROW(createEmitter(w.id, e), Error);  // no bodies at all
    BodyDef post;
    post.type = BodyType::Static;
    post.shapes = {boxShape({0.1f, 0.5f})};
    createBody(w.id, post);
    EXPECT_THROW(createEmitter(w.id, e), Error);  // body 3 does not exist
    e.body = BodyId{1};
    e.inheritVelocity = 1.5f;
    EXPECT_THROW(createEmitter(w.id, e), FieldError);
    e.inheritVelocity = 1.0f;
    e.stateless = true;
    EXPECT_THROW(createEmitter(w.id, e), FieldError);
    const std::string body = "[[body]]\nname = \"post\"\ntype = \"static\"\nshape = [{ box = [0.1, 0.5] }]\n";
    try {
        parseScene(body + "[[emitter]]\nname = \"e\"\nbody = \"pots\"\n", "bad.toml");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& error) {
        EXPECT_EQ(error.line(), 7);
        EXPECT_NE(std::string(error.what()).find("post"), std::string::npos) << error.what();  // did you mean
    }
    try {
        parseScene(body + "[[emitter]]\nname = \"e\"\nbody = \"post\"\ninherit_velocity = -0.5\n", "bad.toml");
        FAIL() << "expected a SceneError";
    } catch (const SceneError& error) {
        EXPECT_EQ(error.line(), 8);
    }
    const SceneDef ok = parseScene(body + "[[emitter]]\nname = \"e\"\nbody = \"post\"\ninherit_velocity = 0.5\n",
                                   "ok.toml");
    ASSERT_EQ(ok.emitters.size(), 1u);
    EXPECT_EQ(ok.emitters[0].body.index, 1u);
    EXPECT_EQ(ok.emitters[0].inheritVelocity, 0.5f);
}

}  // namespace
}  // namespace spindrift
