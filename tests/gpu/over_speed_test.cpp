// Colour and size by speed on both backends: particles flying at constant
// speeds (no forces) through the over-speed curves. The CPU backend stores
// the colour and size its update computed; the Vulkan backend stores neither
// and recomputes them from the stored velocity (restoreDerived), so both
// paths of the shared kernel are read back.
#include "gpu_test_util.h"

#include <gtest/gtest.h>

namespace spindrift {
namespace {

using test::GpuTest;

class OverSpeed : public GpuTest {};

// Range [0, 10] m/s; colour factor from 1 at rest to 0 at 10 m/s, size factor
// from 1 to 3. At 5 m/s (t = 0.5) the start colour (2, 1, 0.5, 1) becomes
// (1, 0.5, 0.25, 0.5) and the size 0.1 m becomes 0.2 m; at 12 m/s (above the
// range, t = 1) the colour is 0 and the size 0.3 m. The speed is exact in
// float (0, 0, 5); the GPU's length() may be an ulp off: 1e-5.
TEST_F(OverSpeed, ColourAndSizeFollowTheSpeedOnBothBackends) {
    for (Backend backend : {Backend::Cpu, Backend::Vulkan}) {
        SCOPED_TRACE(backend == Backend::Cpu ? "cpu" : "vulkan");
        test::BackendWorld w(backend);
        EmitterId ids[2];
        const float speeds[2] = {5.0f, 12.0f};
        for (int k = 0; k < 2; ++k) {
            test::OneShot o;
            o.velocity = {0.0f, 0.0f, speeds[k]};
            o.size = 0.1f;
            EmitterDef def = test::oneShotEmitter(o);
            def.color = {glm::vec4(2.0f, 1.0f, 0.5f, 1.0f), glm::vec4(2.0f, 1.0f, 0.5f, 1.0f)};
            def.overSpeedRange = {0.0f, 10.0f};
            def.colorOverSpeed.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(0.0f)}};
            def.sizeOverSpeed.keys = {{0.0f, glm::vec4(1.0f)}, {1.0f, glm::vec4(3.0f)}};
            ids[k] = createEmitter(w.id, def);
        }
        for (int s = 0; s < 5; ++s) {
            stepWorld(w.id, 1.0f / 60.0f);
        }
        ParticleSnapshot slow = readParticles(w.id, ids[0]);
        ParticleSnapshot fast = readParticles(w.id, ids[1]);
        ASSERT_EQ(slow.count(), 1u);
        ASSERT_EQ(fast.count(), 1u);
        const glm::vec4 half(1.0f, 0.5f, 0.25f, 0.5f);
        for (int c = 0; c < 4; ++c) {
            EXPECT_NEAR(slow.color[0][c], half[c], 1e-5f) << c;
            EXPECT_NEAR(fast.color[0][c], 0.0f, 1e-5f) << c;
        }
        EXPECT_NEAR(slow.size[0], 0.2f, 1e-5f);
        EXPECT_NEAR(fast.size[0], 0.3f, 1e-5f);
    }
}

}  // namespace
}  // namespace spindrift
