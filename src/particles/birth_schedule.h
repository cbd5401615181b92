// The birth schedule of a spawn-mode emitter: how many particles each step
// owes and how old each is at the end of the step. The birth-age rule is the
// kernel's (src/kernels/birth_age.glsl), on the schedule's header in float:
// the CPU backend (src/effects/emitter_step.cpp) reads ages(); the Vulkan
// backend uploads header() and effects_update.comp calls the same rule per
// birth.
#pragma once

#include "particles/emitter_state.h"

#include "kernels/layout.glsl"

#include <cstdint>
#include <vector>

namespace spindrift {

/// The births a spawn emitter owes in the step [t0, t0 + dt): bursts first, in
/// definition order, then the rate's. Shared by both backends: birth k of the
/// step gets serial nextSerial + k and age ages()[k] (s, at the end of the step).
///
/// It holds at most the emitter's capacity of births: no step can place more
/// (a birth needs a free slot), so the rest are only counted, in `dropped`,
/// and nothing grows with dt or the rate (a rate of 1e12 once stored 1.7e10
/// ages a step). The births kept are the first ones, the same ones a step
/// would have placed from the whole list.
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
    /// Births owed beyond the capacity, left out of bursts and rateCount
    /// (saturates at the largest std::uint64_t).
    std::uint64_t dropped = 0;

    /// Births held: at most the capacity.
    std::uint64_t total() const;
    /// The schedule as the kernels read it (the burst runs follow it on the
    /// device).
    kernels::ScheduleHeader header() const;
    /// Age of the rate's j-th birth of the step.
    float rateAge(std::uint64_t j) const;
    /// The ages of the first min(total(), limit) births.
    std::vector<float> ages(std::uint64_t limit) const;
};

/// The schedule of emitter `e`'s step from t0; advances its emission carry.
BirthSchedule scheduleBirths(EmitterState& e, double t0, float dt);

}  // namespace spindrift
