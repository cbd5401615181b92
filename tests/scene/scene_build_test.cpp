// buildWorld(): every shipped scene builds and runs, ids follow the scene's
// order, and each example scene does what its comment promises.
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

namespace {

using namespace spindrift;

const std::filesystem::path kScenes = std::filesystem::path(SPINDRIFT_SOURCE_DIR) / "scenes";

// Owns a world built from a scene file.
class SceneWorld {
public:
    explicit SceneWorld(const std::string& file)
        : scene_(loadScene((kScenes / file).string())), world_(buildWorld(scene_)) {}
    ~SceneWorld() { destroyWorld(world_); }
    SceneWorld(const SceneWorld&) = delete;
    SceneWorld& operator=(const SceneWorld&) = delete;

    /// Steps n times at the scene's dt; returns the summed stats.
    StepStats run(std::uint32_t n) {
        StepStats total;
        for (std::uint32_t i = 0; i < n; ++i) {
            const StepStats s = stepWorld(world_, scene_.run.dt);
            total.born += s.born;
            total.died += s.died;
            total.collisions += s.collisions;
            total.alive = s.alive;
        }
        return total;
    }

    ParticleSnapshot particles(const std::string& emitterName) const {
        for (std::size_t i = 0; i < scene_.emitters.size(); ++i) {
            if (scene_.emitters[i].name == emitterName) {
                return readParticles(world_, EmitterId{static_cast<std::uint32_t>(i + 1)});
            }
        }
        ADD_FAILURE() << "no emitter " << emitterName;
        return {};
    }

    const SceneDef& scene() const { return scene_; }
    WorldId world() const { return world_; }

private:
    SceneDef scene_;
    WorldId world_;
};

TEST(SceneBuild, EverySceneBuildsAndRuns) {
    for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
        if (entry.path().extension() != ".toml") {
            continue;
        }
        SCOPED_TRACE(entry.path().string());
        SceneWorld w(entry.path().filename().string());
        EXPECT_EQ(emitterCount(w.world()), w.scene().emitters.size());
        EXPECT_EQ(colliderCount(w.world()), w.scene().colliders.size());
        const StepStats s = w.run(120);
        EXPECT_NEAR(worldTime(w.world()), 120.0 * w.scene().run.dt, 1e-3);
        std::size_t visible = s.alive;
        for (const EmitterDef& e : w.scene().emitters) {
            visible += e.stateless ? w.particles(e.name).count() : 0;
        }
        for (std::uint32_t f = 1; f <= fluidCount(w.world()); ++f) {
            visible += readFluid(w.world(), FluidId{f}).count();
        }
        EXPECT_GT(visible, 0u) << "nothing to see after 2 s";
    }
}

TEST(SceneBuild, IdsFollowTheOrderOfTheScene) {
    const SceneDef scene = parseScene(R"(
[[emitter]]
name = "first"
forces = ["b"]
[[emitter]]
name = "second"
capacity = 7
[[force]]
name = "a"
kind = "gravity"
[[force]]
name = "b"
kind = "damping"
[[collider]]
name = "floor"
kind = "plane"
)",
                                      "ids.toml");
    const WorldId world = buildWorld(scene);
    EXPECT_EQ(emitterCount(world), 2u);
    EXPECT_EQ(emitterDef(world, EmitterId{2}).name, "second");
    EXPECT_EQ(emitterDef(world, EmitterId{2}).capacity, 7u);
    ASSERT_EQ(emitterDef(world, EmitterId{1}).forces.size(), 1u);
    EXPECT_EQ(emitterDef(world, EmitterId{1}).forces[0].index, 2u);
    EXPECT_EQ(colliderCount(world), 1u);
    destroyWorld(world);
}

TEST(SceneBuild, FountainDropsBounceAndStayAboveTheGround) {
    SceneWorld w("fountain.toml");
    const StepStats s = w.run(180);  // 3 s: the first drops have landed
    EXPECT_GT(s.collisions, 0u);
    const ParticleSnapshot p = w.particles("fountain");
    ASSERT_GT(p.count(), 1000u);
    float lowest = 1e9f;
    float highest = -1e9f;
    for (const glm::vec3& x : p.position) {
        lowest = std::min(lowest, x.y);
        highest = std::max(highest, x.y);
    }
    EXPECT_GE(lowest, -1e-3f);
    // Launched at most 7.5 m/s straight up from 0.2 m: at most 0.2 + 7.5^2 / (2 g).
    EXPECT_LE(highest, 0.2f + 7.5f * 7.5f / (2.0f * 9.81f) + 0.05f);
    EXPECT_GT(highest, 1.5f);
}

TEST(SceneBuild, SparksBurstOnSchedule) {
    SceneWorld w("sparks.toml");
    w.run(6);  // t = 0.1 s: only the burst of 800 at t = 0, none dead yet (lifetime >= 0.6 s)
    EXPECT_EQ(w.particles("sparks").count(), 800u);
    w.run(90);  // t = 1.6 s: the first burst is dead (lifetime <= 1.4 s), the second is alive
    EXPECT_EQ(w.particles("sparks").count(), 800u);
}

TEST(SceneBuild, BeesKeepSwarmingAroundTheHive) {
    SceneWorld w("bees.toml");
    w.run(300);  // 5 s, past the mean lifetime of 4 s
    const ParticleSnapshot p = w.particles("bees");
    // Recycle: slot i is first born at i / n of the mean lifetime, and re-born
    // as soon as it dies, so after one mean lifetime every slot is alive.
    ASSERT_EQ(p.count(), 400u);
    double meanSpeed = 0.0;
    float farthest = 0.0f;
    for (std::size_t i = 0; i < p.count(); ++i) {
        meanSpeed += glm::length(p.velocity[i]);
        farthest = std::max(farthest, glm::length(p.position[i] - glm::vec3(0.0f, 1.5f, 0.0f)));
    }
    meanSpeed /= static_cast<double>(p.count());
    EXPECT_GT(meanSpeed, 1.5);  // undamping keeps them flying near 2.5 m/s
    EXPECT_LT(meanSpeed, 4.0);
    EXPECT_LT(farthest, 8.0f);  // the hive's spring holds the swarm together
}

TEST(SceneBuild, SmokeRises) {
    SceneWorld w("smoke.toml");
    w.run(180);
    const ParticleSnapshot p = w.particles("smoke");
    ASSERT_GT(p.count(), 100u);
    double meanHeight = 0.0;
    for (const glm::vec3& x : p.position) {
        meanHeight += x.y;
    }
    EXPECT_GT(meanHeight / static_cast<double>(p.count()), 0.2 + 0.5);
}

TEST(SceneBuild, RainDiesWhereItLands) {
    SceneWorld w("rain.toml");
    // 1.9 s: drops live at least 2 s, so every death so far is a hit on the hills.
    const StepStats s = w.run(114);
    EXPECT_GT(s.collisions, 0u);
    EXPECT_GT(s.died, 0u);
    for (const glm::vec3& x : w.particles("rain").position) {
        ASSERT_GT(x.y, -1.0f - 1.5f - 0.05f);  // never below the lowest valley
    }
}

TEST(SceneBuild, SnowStaysOutsideTheStatue) {
    SceneWorld w("cubemap.toml");
    w.run(240);
    const ParticleSnapshot p = w.particles("snow");
    ASSERT_GT(p.count(), 500u);
    // Signed distances to the statue's shapes (cubemap.toml). The cube map
    // samples the surface at 48 texels per face (about 4 cm at 1 m), so allow
    // a few centimetres of sampling error.
    const auto outsideBox = [](glm::vec3 x, glm::vec3 c, glm::vec3 h) {
        const glm::vec3 q = glm::abs(x - c) - h;
        return std::max({q.x, q.y, q.z});
    };
    std::size_t inside = 0;
    for (const glm::vec3& x : p.position) {
        // Distance to the union: the nearest of the three (negative inside).
        const float nearest = std::min({outsideBox(x, {0, 0.6f, 0}, {0.8f, 0.6f, 0.8f}),
                                        glm::length(x - glm::vec3(0, 1.6f, 0)) - 0.7f,
                                        outsideBox(x, {0, 2.5f, 0}, {0.1f, 0.5f, 0.1f})});
        inside += nearest < -0.06f ? 1 : 0;
    }
    EXPECT_EQ(inside, 0u);
}

}  // namespace
