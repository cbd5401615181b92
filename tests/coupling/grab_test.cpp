// Grabs (createGrab, bodies.h): Box2D's mouse joint as a damped spring that
// holds a body at a target, and bodyAt, which finds the body to grab.
#include "coupling/coupling_test_util.h"

#include <spindrift/bodies.h>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

namespace {

using namespace spindrift;
using spindrift::test::BodyTestWorld;

constexpr float kDt = 1.0f / 60.0f;

BodyId crate(WorldId world, glm::vec2 at) {
    BodyDef def;
    def.name = "crate";
    def.position = at;
    def.density = 500.0f;
    def.shapes.push_back(boxShape({0.1f, 0.1f}));
    return createBody(world, def);
}

BodySnapshot bodyOf(WorldId world, BodyId id) {
    for (const BodySnapshot& b : readBodies(world)) {
        if (b.id.index == id.index) return b;
    }
    ADD_FAILURE() << "no body " << id.index;
    return {};
}

// Without gravity the spring has nothing to hold against: after 2 s (ten
// periods of 5 Hz, the envelope e^(-0.7 x 2 pi 5 x 2) ~ 1e-19) the body sits
// on the target; let go, it stays there.
TEST(Grab, PullsABodyOntoItsTarget) {
    BodyTestWorld w(1, {0.0f, 0.0f});
    const BodyId body = crate(w.id, {0.0f, 0.0f});
    GrabDef def;
    def.body = body;
    def.point = {0.0f, 0.0f};
    const GrabId grab = createGrab(w.id, def);
    moveGrab(w.id, grab, {1.0f, 0.5f});
    for (int i = 0; i < 120; ++i) stepWorld(w.id, kDt);
    EXPECT_NEAR(bodyOf(w.id, body).position.x, 1.0f, 1e-3f);
    EXPECT_NEAR(bodyOf(w.id, body).position.y, 0.5f, 1e-3f);
    destroyGrab(w.id, grab);
    for (int i = 0; i < 60; ++i) stepWorld(w.id, kDt);
    EXPECT_NEAR(bodyOf(w.id, body).position.x, 1.0f, 2e-3f);
}

// Under gravity a spring of frequency f holds the body below its target by
// m g / k = g / (2 pi f)^2: 9.9 mm at 5 Hz, 2.5 mm at 10 Hz.
TEST(Grab, HoldsABodyUnderGravitySaggingByGOverOmegaSquared) {
    for (const float frequency : {5.0f, 10.0f}) {
        BodyTestWorld w;
        const BodyId body = crate(w.id, {0.0f, 1.0f});
        GrabDef def;
        def.body = body;
        def.point = {0.0f, 1.0f};
        def.frequency = frequency;
        createGrab(w.id, def);
        for (int i = 0; i < 180; ++i) stepWorld(w.id, kDt);
        const float omega = 2.0f * glm::pi<float>() * frequency;
        const float sag = 9.81f / (omega * omega);
        EXPECT_NEAR(1.0f - bodyOf(w.id, body).position.y, sag, 0.1f * sag) << frequency << " Hz";
    }
}

TEST(Grab, BodyAtFindsTheDynamicBodyUnderAPoint) {
    BodyTestWorld w;
    BodyDef floor;
    floor.type = BodyType::Static;
    floor.shapes.push_back(boxShape({2.0f, 0.1f}));
    createBody(w.id, floor);
    const BodyId body = crate(w.id, {1.0f, 1.0f});
    EXPECT_EQ(bodyAt(w.id, {1.05f, 0.95f}).index, body.index);
    EXPECT_EQ(bodyAt(w.id, {1.15f, 1.0f}).index, 0u);  // beyond its 0.1 m half width
    EXPECT_EQ(bodyAt(w.id, {0.0f, 0.0f}).index, 0u);    // the static floor is not grabbed
}

TEST(Grab, DestroyingTheBodyLetsGoAndBadGrabsAreRefused) {
    BodyTestWorld w;
    BodyDef wall;
    wall.type = BodyType::Static;
    wall.shapes.push_back(boxShape({0.1f, 1.0f}));
    const BodyId fixed = createBody(w.id, wall);
    const BodyId body = crate(w.id, {1.0f, 1.0f});
    GrabDef def;
    def.body = fixed;
    EXPECT_THROW(createGrab(w.id, def), Error);
    def.body = body;
    def.frequency = 0.0f;
    EXPECT_THROW(createGrab(w.id, def), Error);
    def.frequency = 5.0f;
    const GrabId grab = createGrab(w.id, def);
    destroyBody(w.id, body);
    EXPECT_NO_THROW(moveGrab(w.id, grab, {2.0f, 2.0f}));
    EXPECT_NO_THROW(destroyGrab(w.id, grab));
    EXPECT_NO_THROW(stepWorld(w.id, kDt));
    EXPECT_THROW(destroyGrab(w.id, GrabId{7}), Error);
}

}  // namespace
