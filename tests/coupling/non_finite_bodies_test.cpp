// A rigid body whose velocity becomes infinite (issue 14): an impulse of
// 3e38 N s, finite and so accepted by applyBodyImpulse, on a body of a few
// grams gives it 3e38 / m > 3.4e38 m/s. Box2D's broad phase asserts on the
// NaN bounds that would follow, so the body is frozen before Box2D steps:
// reported in that step's StepStats, put back where it was, static with zero
// velocity; the other body falls on as if nothing happened.
#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

BodyDef smallBall(const char* name, glm::vec2 at) {
    BodyDef b;
    b.name = name;
    b.position = at;
    b.density = 1.0f;  // kg/m^2: a 5 cm circle is 7.9 g
    b.shapes.push_back(circleShape(0.05f));
    return b;
}

TEST(NonFiniteBodies, AnInfiniteVelocityFreezesThatBodyOnly) {
    WorldDef def;
    def.threads = 1;
    def.bodyGravity = glm::vec2(0.0f, -10.0f);
    const WorldId w = createWorld(def);
    const BodyId hit = createBody(w, smallBall("hit", {0.0f, 0.0f}));
    const BodyId other = createBody(w, smallBall("other", {5.0f, 0.0f}));
    const float dt = 0.01f;
    StepStats s = stepWorld(w, dt);
    EXPECT_TRUE(s.frozenBodies.empty());
    const glm::vec2 before = readBodies(w)[0].position;
    applyBodyImpulse(w, hit, glm::vec2(3.0e38f, 0.0f), before);
    s = stepWorld(w, dt);
    ASSERT_EQ(s.frozenBodies.size(), 1u);
    EXPECT_EQ(s.frozenBodies[0].index, hit.index);
    for (int i = 0; i < 8; ++i) {
        s = stepWorld(w, dt);
        EXPECT_TRUE(s.frozenBodies.empty());  // reported once, when it froze
    }
    const std::vector<BodySnapshot> bodies = readBodies(w);
    ASSERT_EQ(bodies.size(), 2u);
    EXPECT_FALSE(bodies[0].dynamic);
    EXPECT_EQ(bodies[0].position, before);
    EXPECT_EQ(bodies[0].linearVelocity, glm::vec2(0.0f));
    // The other body: 10 steps of free fall, v = g t exactly up to float
    // rounding of 10 additions of 0.1 m/s (1e-5 m/s allows it).
    EXPECT_EQ(bodies[1].id.index, other.index);
    EXPECT_NEAR(bodies[1].linearVelocity.y, -10.0f * 10.0f * dt, 1e-5f);
    EXPECT_TRUE(std::isfinite(bodies[1].position.y));
    destroyWorld(w);
}

}  // namespace
}  // namespace spindrift
