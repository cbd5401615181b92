// Water striking bodies as collision events, and fires put out by them.
// Expected values are closed forms: free fall, the counting rule of a fire
// (strength = start - douse x strikes) and the emitters it drives.
#include <spindrift/fires.h>
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

struct OwnedWorld {
    explicit OwnedWorld(WorldDef def = {}) : id(createWorld(def)) {}
    ~OwnedWorld() { destroyWorld(id); }
    WorldId id;
};

BodyId staticSlab(WorldId w, glm::vec2 centre, glm::vec2 half) {
    BodyDef slab;
    slab.type = BodyType::Static;
    slab.position = centre;
    slab.shapes = {boxShape(half)};
    return createBody(w, slab);
}

// One particle dropped 1 m onto a static slab strikes it once, at the free
// fall speed sqrt(2 g h) = 4.43 m/s. Tolerance g dt (0.16 m/s): the event
// reports the speed at the start of the substep in which it lands.
TEST(FluidStrikes, OneDropStrikesOnceAtFreeFallSpeed) {
    OwnedWorld w;
    const BodyId slab = staticSlab(w.id, {0.0f, -0.1f}, {1.0f, 0.1f});
    FluidDef fluid;
    fluid.spacing = 0.02f;
    // One particle at (0.01, 1.01): its surface (radius 0.01) is 1 m up.
    fluid.blocks = {FluidBlockDef{{0.0f, 1.0f, 0.0f}, {0.02f, 1.02f, 0.0f}, glm::vec3(0.0f)}};
    const FluidId f = createFluid(w.id, fluid);
    ASSERT_EQ(readFluid(w.id, f).count(), 1u);
    const float dt = 1.0f / 60.0f;
    std::vector<ParticleEvent> strikes;
    for (int i = 0; i < 60; ++i) {
        stepWorld(w.id, dt);
        for (const ParticleEvent& e : takeEvents(w.id).events) strikes.push_back(e);
    }
    ASSERT_EQ(strikes.size(), 1u);
    const ParticleEvent& e = strikes[0];
    EXPECT_EQ(e.kind, ParticleEventKind::Collision);
    EXPECT_EQ(e.fluid.index, f.index);
    EXPECT_EQ(e.body.index, slab.index);
    EXPECT_EQ(e.emitter.index, 0u);
    EXPECT_NEAR(e.speed, std::sqrt(2.0f * 9.81f * 1.0f), 9.81f * dt);
    // Where: on the slab's top within a particle radius plus the last step's travel.
    EXPECT_NEAR(e.position.y, 0.01f, 0.01f + 4.5f * dt);
}

/// A 2D fluid jet at 3 m/s from (0.2, 0.3) toward the post of the tests below
/// (x 0.9 to 1.1): `rate` particles/s through a nozzle of `radius` (m).
void aimJetAtThePost(WorldId world, float rate, float radius) {
    FluidDef fluid;
    fluid.spacing = 0.02f;
    FluidJetDef jet;
    jet.position = {0.2f, 0.3f, 0.0f};
    jet.direction = {1.0f, 0.0f, 0.0f};
    jet.speed = 3.0f;
    jet.rate = rate;
    jet.radius = radius;
    fluid.jets = {jet};
    createFluid(world, fluid);
}

// A jet on a burning post: each strike takes dousePerStrike; the flames'
// rate is the emitter's own times the strength; steam is born at the
// strikes' mean position at steamPerStrike per strike.
TEST(Fires, StrikesDouseTheFireAndMakeSteam) {
    OwnedWorld w;
    const BodyId post = staticSlab(w.id, {1.0f, 0.3f}, {0.1f, 0.3f});
    EmitterDef flames;
    flames.name = "flames";
    flames.rate = 200.0f;
    flames.capacity = 1000;
    flames.shape.center = {1.0f, 0.7f, 0.0f};
    EmitterDef steam = flames;
    steam.name = "steam";
    const EmitterId flamesId = createEmitter(w.id, flames);
    const EmitterId steamId = createEmitter(w.id, steam);
    aimJetAtThePost(w.id, 300.0f, 0.03f);
    FireDef fire;
    fire.name = "post";
    fire.body = post;
    fire.flames = flamesId;
    fire.steam = steamId;
    fire.dousePerStrike = 0.01f;
    fire.steamPerStrike = 0.5f;
    const FireId id = createFire(w.id, fire);
    const float dt = 1.0f / 60.0f;
    std::uint64_t strikes = 0;
    bool sawSteam = false;
    for (int i = 0; i < 90; ++i) {
        stepWorld(w.id, dt);
        std::uint64_t now = 0;
        glm::vec3 sum(0.0f);
        for (const ParticleEvent& e : takeEvents(w.id).events) {
            if (e.body.index == post.index) {
                ++now;
                sum += e.position;
            }
        }
        strikes += now;
        ASSERT_EQ(fireStrikes(w.id, id), strikes);
        const float strength = std::max(0.0f, 1.0f - 0.01f * static_cast<float>(strikes));
        ASSERT_NEAR(fireStrength(w.id, id), strength, 1e-5f);
        ASSERT_NEAR(emitterDef(w.id, flamesId).rate, 200.0f * fireStrength(w.id, id), 1e-3f);
        ASSERT_NEAR(emitterDef(w.id, steamId).rate, 0.5f * static_cast<float>(now) / dt, 1e-2f);
        if (now > 0) {
            sawSteam = true;
            const glm::vec3 mean = sum / static_cast<float>(now);
            ASSERT_NEAR(glm::length(emitterDef(w.id, steamId).shape.center - mean), 0.0f, 1e-5f);
        }
    }
    EXPECT_TRUE(sawSteam);
    EXPECT_GE(strikes, 100u) << "the jet should have put the fire out";
    EXPECT_EQ(fireStrength(w.id, id), 0.0f);
    EXPECT_EQ(emitterDef(w.id, flamesId).rate, 0.0f);
}

// A fire of strength 1 dousing 0.002 per strike goes out at its 500th strike,
// not one later: taken off step by step in float, 500 strikes left 6.5e-7 (five
// a step) and the showcase's bonfire burned on, or 5.8e-6 (one a step, here).
TEST(Fires, GoesOutAtTheStrikeItsDouseAllowsFor) {
    OwnedWorld w;
    const BodyId post = staticSlab(w.id, {1.0f, 0.3f}, {0.1f, 0.3f});
    aimJetAtThePost(w.id, 60.0f, 0.01f);  // a particle a step
    FireDef fire;
    fire.name = "post";
    fire.body = post;
    fire.dousePerStrike = 0.002f;
    const FireId id = createFire(w.id, fire);
    for (int i = 0; i < 900 && fireStrikes(w.id, id) < 520; ++i) {
        stepWorld(w.id, 1.0f / 60.0f);
        if (fireStrikes(w.id, id) < 500) {
            ASSERT_GT(fireStrength(w.id, id), 0.0f) << "out after " << fireStrikes(w.id, id) << " strikes";
        } else {
            ASSERT_EQ(fireStrength(w.id, id), 0.0f) << "burning after " << fireStrikes(w.id, id) << " strikes";
        }
    }
    EXPECT_GE(fireStrikes(w.id, id), 500u) << "the jet should have put the fire out";
}

// A fire counts every strike on its body, whatever the world keeps for
// takeEvents: WorldDef::eventCapacity bounds the application's events, not
// the fires' (with 0, "no events recorded", a fire never went out). The
// reference is the same run with room for every event, whose strikes the
// test above checks against the events one by one.
TEST(Fires, CountEveryStrikeWhateverTheEventCapacity) {
    std::vector<std::uint64_t> strikes;
    for (std::uint32_t capacity : {4096u, 2u, 0u}) {
        WorldDef def;
        def.eventCapacity = capacity;
        OwnedWorld w(def);
        const BodyId post = staticSlab(w.id, {1.0f, 0.3f}, {0.1f, 0.3f});
        aimJetAtThePost(w.id, 300.0f, 0.03f);  // several strikes a step
        FireDef fire;
        fire.name = "post";
        fire.body = post;
        fire.dousePerStrike = 0.001f;
        const FireId id = createFire(w.id, fire);
        std::uint64_t taken = 0;
        for (int i = 0; i < 60; ++i) {
            stepWorld(w.id, 1.0f / 60.0f);
            taken += takeEvents(w.id).events.size();
        }
        EXPECT_LE(taken, 60u * capacity);
        strikes.push_back(fireStrikes(w.id, id));
    }
    EXPECT_GT(strikes[0], 60u);  // not vacuous: steps with more strikes than a capacity of 2
    EXPECT_EQ(strikes[1], strikes[0]);
    EXPECT_EQ(strikes[2], strikes[0]);
}

// Flames ride on their body: the spawn centre keeps its offset in the body's
// frame as the body moves and turns.
TEST(Fires, FlamesFollowTheirBody) {
    WorldDef def;
    def.bodyGravity = glm::vec2(0.0f);
    OwnedWorld w(def);
    BodyDef cart;
    cart.type = BodyType::Kinematic;
    cart.position = {0.0f, 0.0f};
    cart.linearVelocity = {1.0f, 0.0f};
    cart.angularVelocity = 0.5f;
    cart.shapes = {boxShape({0.2f, 0.1f})};
    const BodyId body = createBody(w.id, cart);
    EmitterDef flames;
    flames.name = "flames";
    flames.shape.center = {0.0f, 0.3f, 0.0f};
    const EmitterId e = createEmitter(w.id, flames);
    FireDef fire;
    fire.body = body;
    fire.flames = e;
    createFire(w.id, fire);
    for (int i = 0; i < 30; ++i) stepWorld(w.id, 1.0f / 60.0f);
    const BodySnapshot b = readBodies(w.id)[0];
    const glm::vec2 expected = b.position + glm::vec2(-std::sin(b.angle), std::cos(b.angle)) * 0.3f;
    EXPECT_NEAR(emitterDef(w.id, e).shape.center.x, expected.x, 1e-5f);
    EXPECT_NEAR(emitterDef(w.id, e).shape.center.y, expected.y, 1e-5f);
    EXPECT_GT(b.position.x, 0.4f);  // it did move
}

TEST(FireScene, ParsesAndNamesWhatItDrives) {
    const std::string text = R"(
[[emitter]]
name = "flames"
[[emitter]]
name = "steam"
[[body]]
name = "crate"
shape = [{ box = [0.2, 0.2] }]
[[fire]]
name = "crate fire"
body = "crate"
flames = "flames"
steam = "steam"
douse_per_strike = 0.01
)";
    const SceneDef s = parseScene(text, "fire.toml");
    ASSERT_EQ(s.fires.size(), 1u);
    EXPECT_EQ(s.fires[0].body.index, 1u);
    EXPECT_EQ(s.fires[0].flames.index, 1u);
    EXPECT_EQ(s.fires[0].steam.index, 2u);
    EXPECT_EQ(s.fires[0].smoke.index, 0u);
    EXPECT_FLOAT_EQ(s.fires[0].dousePerStrike, 0.01f);
    const WorldId w = buildWorld(s);
    EXPECT_EQ(fireCount(w), 1u);
    destroyWorld(w);
    try {
        parseScene(text + "[[fire]]\nname = \"b\"\nbody = \"barrel\"\n", "fire.toml");
        FAIL() << "an unknown body must be rejected";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.line(), 17);  // body = "barrel"
        EXPECT_NE(e.message().find("barrel"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace spindrift
