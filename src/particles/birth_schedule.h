// The birth schedule of a spawn-mode emitter: how many particles each step
// owes and how old each is at the end of the step. The one birth-age rule,
// shared by both backends: the CPU backend (src/effects/emitter_step.cpp)
// reads ages(); the Vulkan backend uploads the schedule and
// effects_update.comp evaluates the same rule per birth (scheduleAge there
// mirrors rateAge here; tests/gpu check the two agree).
#pragma once

#include "particles/emitter_state.h"

#include <cstdint>
#include <vector>

namespace spindrift {

/// The births a spawn emitter owes in the step [t0, t0 + dt): bursts first, in
/// definition order, then the rate's. Shared by both backends: birth k of the
/// step gets serial nextSerial + k and age ages()[k] (s, at the end of the step).
struct BirthSchedule {
    struct BurstRun {
        std::uint32_t count;
        float age;
    };
    std::vector<BurstRun> bursts;
    std::uint64_t rateCount = 0;
    double t0 = 0.0, t1 = 0.0, dt = 0.0;
    double rate = 0.0;
    double carry = 0.0;  // the rate's carry before this step

    std::uint64_t total() const;
    /// Age of the rate's j-th birth of the step.
    float rateAge(std::uint64_t j) const;
    std::vector<float> ages() const;
};

/// The schedule of emitter `e`'s step from t0; advances its emission carry.
BirthSchedule scheduleBirths(EmitterState& e, double t0, float dt);

}  // namespace spindrift
