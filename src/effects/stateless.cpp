// Stateless emitters: the live particles at time t from the closed form, with
// nothing stored (GPU particle talk, "Stateless").
#include "particles/cpu_kernels.h"
#include "particles/params.h"
#include "effects/stateless.h"

#include <spindrift/world.h>

#include <algorithm>
#include <cmath>

namespace spindrift {
namespace {

constexpr std::uint32_t kBurstSerialBase = kernels::SD_BURST_SERIAL_BASE;
constexpr std::uint32_t kBurstSerialStride = kernels::SD_BURST_SERIAL_STRIDE;

void append(ParticleSnapshot& s, const kernels::Particle& p) {
    s.position.push_back(p.position);
    s.velocity.push_back(p.velocity);
    s.age.push_back(p.age);
    s.lifetime.push_back(p.lifetime);
    s.size.push_back(p.size);
    s.rotation.push_back(p.rotation);
    s.color.push_back(p.color);
    s.birth.push_back(p.birth);
    s.slot.push_back(static_cast<std::uint32_t>(s.slot.size()));
}

void addIfAlive(ParticleSnapshot& s, const kernels::EmitterParams& e, std::uint32_t serial, double bornAt,
                double t, std::uint32_t capacity) {
    double age = t - bornAt;
    if (age < 0.0 || s.count() >= capacity) {
        return;
    }
    kernels::Particle p = kernels::evaluateStatelessParticle(e, serial, static_cast<float>(age));
    if (p.alive != 0u) {
        append(s, p);
    }
}

}  // namespace

std::vector<StatelessRun> statelessRuns(const EmitterDef& def, double t) {
    std::vector<StatelessRun> runs;
    // Rate: particle k is born at k / rate (while the emitter runs); only those
    // born within the longest lifetime before t can be alive.
    if (def.rate > 0.0f) {
        double rate = def.rate;
        double first = std::max(0.0, std::ceil((t - def.lifetime.max) * rate));
        double last = std::floor(t * rate);
        if (def.duration >= 0.0f) {
            last = std::min(last, std::ceil(def.duration * rate) - 1.0);  // born before the end
        }
        last = std::min(last, static_cast<double>(kBurstSerialBase) - 1.0);
        // At most `capacity` of them, the newest (the likeliest alive): a
        // rate of 3e38 would otherwise hand 2^30 candidates to the walk and
        // to the sprite draw.
        first = std::max(first, last - static_cast<double>(def.capacity) + 1.0);
        if (last >= first) {
            runs.push_back({static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(last - first + 1.0), rate, 0.0});
        }
    }
    for (std::size_t b = 0; b < def.bursts.size(); ++b) {
        const BurstDef& burst = def.bursts[b];
        if (t >= burst.time && t - burst.time < def.lifetime.max && burst.count > 0) {
            runs.push_back({kBurstSerialBase + static_cast<std::uint32_t>(b) * kBurstSerialStride, burst.count, 0.0,
                            burst.time});
        }
    }
    return runs;
}

ParticleSnapshot evaluateStateless(const EmitterDef& def, std::uint32_t seed, std::uint32_t emitterIndex, float t) {
    kernels::EmitterParams e = makeEmitterParams(def, seed, emitterIndex, 0u, 0u);
    ParticleSnapshot s;
    for (const StatelessRun& run : statelessRuns(def, static_cast<double>(t))) {
        // A full snapshot takes no more: the rest of a run is not walked.
        for (std::uint32_t j = 0; j < run.count && s.count() < def.capacity; ++j) {
            addIfAlive(s, e, run.firstSerial + j, run.bornAt(j), t, def.capacity);
        }
    }
    return s;
}

}  // namespace spindrift
