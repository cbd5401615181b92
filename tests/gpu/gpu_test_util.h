// Shared fixture of the Vulkan backend tests: validation on for every GPU
// world, and a validation message of any severity >= warning fails the test.
#pragma once

#include "effects/effects_test_util.h"

#include "gpu/gpu_world.h"
#include "gpu/vulkan_device.h"

#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <memory>

namespace spindrift::test {

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override {
        // Only a machine with no Vulkan driver at all skips; CI and the dev
        // machines have lavapipe (mesa-vulkan-drivers).
        if (!gpu::vulkanAvailable()) {
            GTEST_SKIP() << "no Vulkan driver (install mesa-vulkan-drivers for lavapipe)";
        }
        gpu::setWorldValidation(true);
        gpu::worldDebugLog().clear();
    }
    void TearDown() override {
        gpu::DebugLog& log = gpu::worldDebugLog();
        EXPECT_EQ(log.total(), 0u) << log.text();
    }
};

/// GpuTest with one validated device and one thing made on it (`create`:
/// pipelines, which llvmpipe compiles at creation, so once per suite keeps it
/// fast), shared by the whole suite and destroyed after it.
template <class Part, std::unique_ptr<Part> (*create)(gpu::Device&)>
class GpuSuiteWith : public GpuTest {
protected:
    struct Shared {
        std::unique_ptr<gpu::Device> device;
        std::unique_ptr<Part> part;
    };
    static Shared& shared() {
        static Shared s;
        return s;
    }
    static void TearDownTestSuite() {
        Shared& s = shared();
        s.part.reset();
        if (s.device) {
            gpu::destroyDevice(*s.device);
            s.device.reset();
        }
    }
    void SetUp() override {
        GpuTest::SetUp();
        if (IsSkipped()) {
            return;
        }
        Shared& s = shared();
        if (!s.device) {
            s.device = gpu::createDevice({true, &gpu::worldDebugLog(), {}});
            s.part = create(*s.device);
        }
    }
};

/// A world owned by the test on the given backend (one CPU thread). One frame
/// in flight unless asked: every StepStats then counts its own step, so the
/// backends can be compared step by step.
struct BackendWorld : ScopedWorld {
    explicit BackendWorld(Backend backend, std::uint32_t seed = 7, std::uint32_t framesInFlight = 1)
        : ScopedWorld(1, seed, backend, framesInFlight) {}
};

}  // namespace spindrift::test
