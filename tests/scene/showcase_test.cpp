// The showcase level plays by itself (scenes/showcase.toml): within the
// render's 9 s the cannon puts out every fire, the burning crate and the box
// beside it leave the ledge and the gate swings open. These are the level's design goals, so the
// bounds are generous: any one failing means the level no longer plays.
#include <spindrift/fires.h>
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace spindrift {
namespace {

const BodySnapshot& named(const std::vector<BodySnapshot>& bodies, const std::string& name) {
    for (const BodySnapshot& b : bodies) {
        if (b.name == name) return b;
    }
    throw Error("no body " + name);
}

TEST(Showcase, PlaysByItself) {
    const SceneDef scene = loadScene(std::string(SPINDRIFT_SOURCE_DIR) + "/scenes/showcase.toml");
    const WorldId w = buildWorld(scene);
    ASSERT_EQ(fireCount(w), 3u);
    const auto steps = static_cast<int>(std::ceil(scene.render.seconds / scene.run.dt));
    float gateOpen = 0.0f;
    for (int i = 0; i < steps; ++i) {
        stepWorld(w, scene.run.dt);
        takeEvents(w);
        gateOpen = std::max(gateOpen, std::abs(named(readBodies(w), "gate").angle));
    }
    for (std::uint32_t f = 1; f <= 3; ++f) {
        EXPECT_EQ(fireStrength(w, FireId{f}), 0.0f) << "fire " << f << " still burns";
    }
    // The ledge spans x 5.0..6.2 with its top at y 1.1: both crates are off it.
    for (const char* name : {"crate", "box"}) {
        const BodySnapshot crate = named(readBodies(w), name);
        EXPECT_TRUE(crate.position.x > 6.3f || crate.position.y < 0.9f)
            << name << " at " << crate.position.x << ", " << crate.position.y;
    }
    EXPECT_GT(gateOpen, 0.5f) << "the gate never opened (rad)";
    // Nothing is flung out of the level: every body ends on or near the
    // ground (the ledge's top is at 1.1 m, the wall's at 2.5 m) and inside its
    // 11 m. A crate launched at 46 m/s by the fluid's resting-contact rows
    // (not merged; docs/fluid.md) ended 66 m up while the checks above passed.
    for (const BodySnapshot& b : readBodies(w)) {
        if (!b.dynamic) continue;
        EXPECT_TRUE(b.position.y < 3.0f && b.position.x > -1.0f && b.position.x < 11.0f)
            << b.name << " at " << b.position.x << ", " << b.position.y;
    }
    destroyWorld(w);
}

}  // namespace
}  // namespace spindrift
