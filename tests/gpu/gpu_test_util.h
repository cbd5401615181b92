// Shared fixture of the Vulkan backend tests: validation on for every GPU
// world, and a validation message of any severity >= warning fails the test.
#pragma once

#include "effects/effects_test_util.h"

#include "gpu/gpu_world.h"
#include "gpu/vulkan_device.h"

#include <spindrift/world.h>

#include <gtest/gtest.h>

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

/// A world owned by the test on the given backend (one CPU thread). One frame
/// in flight unless asked: every StepStats then counts its own step, so the
/// backends can be compared step by step.
struct BackendWorld : ScopedWorld {
    explicit BackendWorld(Backend backend, std::uint32_t seed = 7, std::uint32_t framesInFlight = 1)
        : ScopedWorld(1, seed, backend, framesInFlight) {}
};

}  // namespace spindrift::test
