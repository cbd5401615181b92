// The birth schedule of a spawn emitter's step (see birth_schedule.h).
#include "particles/birth_schedule.h"

#include "core/saturating.h"
#include "kernels/birth_age.glsl"

#include <algorithm>
#include <cmath>

namespace spindrift {

// Bursts whose time falls in [t0, t1) in definition order, then the rate's
// particles, each born at the moment the running count crosses an integer (so
// emission does not band into one sheet per frame).
BirthSchedule scheduleBirths(EmitterState& e, double t0, float dt) {
    BirthSchedule s;
    s.t0 = t0;
    s.t1 = t0 + dt;
    s.dt = dt;
    s.rate = e.def.rate;
    s.carry = e.emissionCarry;
    const std::uint64_t capacity = e.def.capacity;
    std::uint64_t room = capacity;  // births the schedule may still hold
    for (const BurstDef& b : e.def.bursts) {
        if (b.time >= s.t0 && b.time < s.t1) {
            const std::uint64_t kept = std::min<std::uint64_t>(b.count, room);
            if (kept > 0) {
                s.bursts.push_back({static_cast<std::uint32_t>(kept), static_cast<float>(s.t1 - b.time)});
            }
            s.dropped += b.count - kept;
            room -= kept;
        }
    }
    double activeEnd = e.def.duration >= 0.0f ? std::min<double>(s.t1, e.def.duration) : s.t1;
    double activeDt = std::max(0.0, activeEnd - t0);
    if (e.def.rate > 0.0f && activeDt > 0.0) {
        // In double: owed may be far beyond any integer type (rate 3e38).
        const double owed = e.emissionCarry + e.def.rate * activeDt;
        const double whole = std::floor(owed);
        e.emissionCarry = owed - whole;
        s.rateCount = whole < static_cast<double>(room) ? static_cast<std::uint64_t>(whole) : room;
        s.dropped = saturatingAdd(s.dropped, saturatingCount(whole - static_cast<double>(s.rateCount)));
    }
    return s;
}

std::uint64_t BirthSchedule::total() const {
    std::uint64_t n = rateCount;
    for (const BurstRun& b : bursts) {
        n += b.count;
    }
    return n;
}

kernels::ScheduleHeader BirthSchedule::header() const {
    kernels::ScheduleHeader h{};
    h.burstRuns = static_cast<std::uint32_t>(bursts.size());
    std::uint64_t first = 0;
    for (const BurstRun& b : bursts) {
        first += b.count;
    }
    h.rateFirst = static_cast<std::uint32_t>(first);  // at most the capacity (< 2^32)
    h.rateSpan = static_cast<float>(t1 - t0);
    h.rateCarry = static_cast<float>(carry);
    h.rate = static_cast<float>(rate);
    h.maxAge = static_cast<float>(dt);
    return h;
}

float BirthSchedule::rateAge(std::uint64_t j) const {
    // The kernel's rule on the header's floats, as the Vulkan backend
    // evaluates it. j < capacity <= 2^24, exact in a float.
    const kernels::ScheduleHeader h = header();
    return kernels::rateBirthAge(static_cast<float>(j), h.rateCarry, h.rate, h.rateSpan, h.maxAge);
}

std::vector<float> BirthSchedule::ages(std::uint64_t limit) const {
    const std::uint64_t n = std::min(total(), limit);
    std::vector<float> out;
    out.reserve(n);
    for (const BurstRun& b : bursts) {
        out.insert(out.end(), std::min<std::uint64_t>(b.count, n - out.size()), b.age);
    }
    for (std::uint64_t j = 0; out.size() < n; ++j) {
        out.push_back(rateAge(j));
    }
    return out;
}

}  // namespace spindrift
