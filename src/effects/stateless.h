// Which serials of a stateless emitter can be alive at time t: one run for
// the rate's window and one per burst. evaluateStateless walks them on the
// CPU; the renderer hands them to the sprite vertex stage.
#pragma once

#include <spindrift/effects.h>

#include <cstdint>
#include <vector>

namespace spindrift {

struct StatelessRun {
    std::uint32_t firstSerial = 0;
    std::uint32_t count = 0;
    /// Rate runs: serial k is born at k / rate. Bursts: rate 0, all born at burstTime.
    double rate = 0.0;
    double burstTime = 0.0;
    double bornAt(std::uint32_t j) const {
        return rate > 0.0 ? static_cast<double>(firstSerial + j) / rate : burstTime;
    }
};

/// Candidates alive at `t` (s): those born before t within the longest
/// lifetime; each may still have died younger (its own lifetime). The rate's
/// run holds at most the emitter's capacity of them, the newest.
std::vector<StatelessRun> statelessRuns(const EmitterDef& def, double t);

}  // namespace spindrift
