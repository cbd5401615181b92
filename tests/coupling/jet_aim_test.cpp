// Jets that aim on a schedule and ride on bodies (FluidJetDef::aim, ::body):
// the direction follows the keys, the nozzle moves and turns with its body,
// and the body takes the recoil.
#include "coupling/coupling_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

namespace spindrift {
namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr float kQuarterTurn = 1.5707963f;

/// A 2D fluid of one jet and no gravity. At 5 mm spacing (h = 1.5 cm) and one
/// particle per step at 1 m/s the particles are 1.7 cm apart: they never
/// interact, so each keeps the velocity it was born with.
FluidDef lonelyJet(const FluidJetDef& jet) {
    FluidDef def;
    def.name = "jet";
    def.dimension = 2;
    def.spacing = 0.005f;
    def.gravity = glm::vec3(0.0f);
    def.capacity = 1000;
    def.jets.push_back(jet);
    return def;
}

// aimFluidJet replaces the keys: every particle born after the call leaves
// at the given angle (round-off of cos and sin); releasing the aim returns
// to the schedule. The nozzle of a jet on no body is its own position.
TEST(CouplingJetAim, AimOverridesTheKeysUntilReleased) {
    test::BodyTestWorld w(1, {0.0f, 0.0f});
    FluidJetDef jet;
    jet.position = {0.3f, 0.2f, 0.0f};
    jet.speed = 1.0f;
    jet.rate = 60.0f;
    jet.aim = {{0.0f, 0.0f}};  // +x by the schedule
    const FluidId f = createFluid(w.id, lonelyJet(jet));
    const FluidJetPose pose = fluidJetPose(w.id, f, 0);
    EXPECT_EQ(pose.nozzle, glm::vec2(0.3f, 0.2f));
    EXPECT_EQ(pose.frameAngle, 0.0f);
    for (int i = 0; i < 10; ++i) stepWorld(w.id, kDt);
    aimFluidJet(w.id, f, 0, 1.0f);
    for (int i = 0; i < 10; ++i) stepWorld(w.id, kDt);
    releaseFluidJetAim(w.id, f, 0);
    for (int i = 0; i < 10; ++i) stepWorld(w.id, kDt);
    FluidSnapshot s = readFluid(w.id, f);
    ASSERT_EQ(s.count(), 30u);
    for (std::size_t k = 0; k < s.count(); ++k) {
        const std::uint32_t serial = s.id[k];  // 0..9 keys, 10..19 aimed, 20..29 keys again
        const float angle = serial >= 10 && serial < 20 ? 1.0f : 0.0f;
        EXPECT_NEAR(s.velocity[k].x, std::cos(angle), 1e-6f) << "particle " << serial;
        EXPECT_NEAR(s.velocity[k].y, std::sin(angle), 1e-6f) << "particle " << serial;
    }
    EXPECT_THROW(aimFluidJet(w.id, f, 1, 0.0f), Error);
    EXPECT_THROW(aimFluidJet(w.id, f, 0, std::nanf("")), Error);
}

TEST(CouplingJetAim, SweepsOnItsSchedule) {
    test::BodyTestWorld w(1, {0.0f, 0.0f});
    FluidJetDef jet;
    jet.speed = 1.0f;
    jet.rate = 60.0f;
    jet.aim = {{0.0f, 0.0f}, {1.0f, kQuarterTurn}};  // +x to +y over 1 s, then held
    const FluidId f = createFluid(w.id, lonelyJet(jet));
    for (int i = 0; i < 75; ++i) stepWorld(w.id, kDt);
    const FluidSnapshot s = readFluid(w.id, f);
    ASSERT_EQ(s.count(), 75u);
    for (std::size_t k = 0; k < s.count(); ++k) {
        // Particle k is born at (k + 1) / 60 s; its direction is the aim then.
        // 1e-4 rad: float rounding of the angle, its cosine and sine.
        const float born = static_cast<float>(k + 1) / 60.0f;
        const float expected = kQuarterTurn * std::min(born, 1.0f);
        EXPECT_NEAR(std::atan2(s.velocity[k].y, s.velocity[k].x), expected, 1e-4f) << "particle " << k;
        EXPECT_NEAR(glm::length(s.velocity[k]), 1.0f, 1e-5f);
    }
}

TEST(CouplingJetAim, RidesAMovingTurnedBody) {
    test::BodyTestWorld w(1, {0.0f, 0.0f});
    BodyDef truck;
    truck.name = "truck";
    truck.type = BodyType::Kinematic;
    truck.angle = kQuarterTurn;          // body x axis = world +y
    truck.linearVelocity = {1.0f, 0.0f};
    truck.shapes.push_back(boxShape({0.05f, 0.05f}));
    const BodyId id = createBody(w.id, truck);
    FluidJetDef jet;
    jet.position = glm::vec3(0.2f, 0.0f, 0.0f);   // body frame: 0.2 m up in the world
    jet.direction = glm::vec3(1.0f, 0.0f, 0.0f);  // body frame: up in the world
    jet.speed = 1.0f;
    jet.rate = 60.0f;
    jet.body = id;
    const FluidId f = createFluid(w.id, lonelyJet(jet));
    for (int i = 0; i < 30; ++i) stepWorld(w.id, kDt);
    const FluidSnapshot s = readFluid(w.id, f);
    ASSERT_EQ(s.count(), 30u);
    for (std::size_t k = 0; k < s.count(); ++k) {
        // Up at 1 m/s plus the truck's 1 m/s along x (rounding: 1e-5).
        EXPECT_NEAR(s.velocity[k].x, 1.0f, 1e-5f);
        EXPECT_NEAR(s.velocity[k].y, 1.0f, 1e-5f);
    }
    // The newest particle left the nozzle during the last step: within a
    // step's travel (1.7 cm per axis) of the nozzle, 0.2 m above the truck.
    const BodySnapshot b = test::findBody(w.id, id);
    EXPECT_NEAR(s.position.back().x, b.position.x, 0.02f);
    EXPECT_NEAR(s.position.back().y, b.position.y + 0.2f, 0.02f);
}

TEST(CouplingJetAim, TheBodyTakesTheRecoil) {
    test::BodyTestWorld w(1, {0.0f, 0.0f});
    const BodyId id = createBody(w.id, test::crate("boat", {0.0f, 0.0f}, {0.1f, 0.1f}, 1000.0f));
    FluidJetDef jet;
    jet.position = glm::vec3(0.15f, 0.0f, 0.0f);
    jet.direction = glm::vec3(1.0f, 0.0f, 0.0f);
    jet.speed = 2.0f;
    jet.rate = 120.0f;
    jet.body = id;
    FluidDef def = test::waterBlock(0.02f, {5.0f, 5.0f}, {5.02f, 5.02f});  // one particle, far away
    def.gravity = glm::vec3(0.0f);
    def.jets.push_back(jet);
    def.capacity = 1000;
    const FluidId f = createFluid(w.id, def);
    for (int i = 0; i < 15; ++i) stepWorld(w.id, kDt);
    const std::size_t emitted = readFluid(w.id, f).count() - 1;
    ASSERT_GT(emitted, 20u);
    // Each particle of 0.4 kg leaves at 2 m/s relative to the nozzle; the
    // boat (40 kg) takes the opposite impulse. The particles fly away from
    // it, so no contact adds to it: 1e-4 relative for float rounding.
    const float mp = def.density * def.spacing * def.spacing;
    const float expected = -static_cast<float>(emitted) * mp * jet.speed / bodyMass(w.id, id);
    EXPECT_NEAR(test::findBody(w.id, id).linearVelocity.x, expected, 1e-4f * std::abs(expected));
}

TEST(CouplingJetAim, BadAimsAreRejected) {
    test::BodyTestWorld w;
    FluidJetDef jet;
    jet.aim = {{1.0f, 0.0f}, {0.5f, 1.0f}};  // time runs backwards
    EXPECT_THROW(createFluid(w.id, lonelyJet(jet)), Error);
    FluidJetDef orphan;
    orphan.body = {7};  // no such body
    EXPECT_THROW(createFluid(w.id, lonelyJet(orphan)), Error);
}

}  // namespace
}  // namespace spindrift
