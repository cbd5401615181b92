// Stateless emitters: the live particles at time t from the closed form, with
// nothing stored (GPU particle talk, "Stateless").
#include "effects/cpu_kernels.h"
#include "effects/params.h"

#include <spindrift/world.h>

#include <algorithm>
#include <cmath>

namespace spindrift {
namespace {

// Serials of burst particles live above the rate's: burst b, particle j.
constexpr std::uint32_t kBurstSerialBase = 0x80000000u;
constexpr std::uint32_t kBurstSerialStride = 1u << 20;

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

ParticleSnapshot evaluateStateless(const EmitterDef& def, std::uint32_t seed, std::uint32_t emitterIndex, float t) {
    kernels::EmitterParams e = makeEmitterParams(def, seed, emitterIndex, 0u, 0u);
    ParticleSnapshot s;
    // Rate: particle k is born at k / rate (while the emitter runs); only those
    // born within the longest lifetime before t can be alive.
    if (def.rate > 0.0f) {
        double rate = def.rate;
        double first = std::max(0.0, std::ceil((static_cast<double>(t) - def.lifetime.max) * rate));
        double last = std::floor(static_cast<double>(t) * rate);
        if (def.duration >= 0.0f) {
            last = std::min(last, std::ceil(def.duration * rate) - 1.0);  // born before the end
        }
        for (double k = first; k <= last && k < kBurstSerialBase; k += 1.0) {
            addIfAlive(s, e, static_cast<std::uint32_t>(k), k / rate, t, def.capacity);
        }
    }
    for (std::size_t b = 0; b < def.bursts.size(); ++b) {
        for (std::uint32_t j = 0; j < def.bursts[b].count; ++j) {
            auto serial = kBurstSerialBase + static_cast<std::uint32_t>(b) * kBurstSerialStride + j;
            addIfAlive(s, e, serial, def.bursts[b].time, t, def.capacity);
        }
    }
    return s;
}

}  // namespace spindrift
