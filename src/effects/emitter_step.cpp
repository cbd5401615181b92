// One step of one state-preserving emitter on the CPU: a named list of passes.
#include "effects/emitter_step.h"

#include "effects/batch_update.h"

#include "core/saturating.h"
#include "kernels/trail.glsl"
#include "particles/birth_schedule.h"

#include <bit>
#include <cmath>

namespace spindrift {
namespace {

// Slots per chunk: fixed, so per-chunk results (deaths, counts) are the same
// for any thread count.
constexpr std::size_t kChunk = 4096;

struct ChunkResult {
    std::uint64_t born = 0;
    std::uint64_t died = 0;
    std::uint64_t nonFinite = 0;  // removed: a number became NaN or infinite
    std::uint64_t hits[32] = {};
    std::vector<std::uint32_t> dead;  // spawn mode: slots that died, ascending
    std::vector<kernels::EventRecord> events;
};

kernels::Particle loadParticle(const ParticleArrays& a, const kernels::EmitterParams& e, std::size_t i) {
    kernels::Particle p;
    p.position = a.position[i];
    p.velocity = a.velocity[i];
    p.color = a.color[i];
    p.age = a.age[i];
    p.lifetime = a.lifetime[i];
    p.size = a.size[i];
    p.rotation = a.rotation[i];
    p.angularVelocity = a.angularVelocity[i];
    p.mass = e.mass;
    p.birth = a.birth[i];
    p.alive = p.age >= 0.0f ? 1u : 0u;
    return p;
}

void storeParticle(ParticleArrays& a, std::size_t i, const kernels::Particle& p) {
    a.position[i] = p.position;
    a.velocity[i] = p.velocity;
    a.color[i] = p.color;
    a.age[i] = p.age;
    a.lifetime[i] = p.lifetime;
    a.size[i] = p.size;
    a.rotation[i] = p.rotation;
    a.angularVelocity[i] = p.angularVelocity;
    a.birth[i] = p.birth;
}

// Slot i's trail once the slot is stored (src/kernels/trail.glsl, as
// effects_update.comp's recordTrail).
void recordTrail(ParticleArrays& a, std::uint32_t points, std::uint32_t head, std::size_t i, bool born) {
    const auto slot = static_cast<std::uint32_t>(i);
    const std::uint32_t writes = kernels::trailWrites(points, a.age[i] >= 0.0f, born);
    for (std::uint32_t j = 0; j < writes; ++j) {
        a.trail[kernels::trailWriteIndex(slot, j, head, points, born)] = a.position[i];
    }
}

// Counts the update of `before` into r and, when events are recorded, keeps
// its events (speed: m/s at the start of the step).
void countUpdate(const kernels::Particle& before, const kernels::ParticleUpdate& r, std::uint32_t emitter,
                 float speed, bool recordEvents, ChunkResult& out) {
    out.born += (r.events & kernels::SD_EVENT_BORN) != 0u ? 1 : 0;
    out.died += (r.events & kernels::SD_EVENT_DIED) != 0u ? 1 : 0;
    out.nonFinite += (r.events & kernels::SD_EVENT_NON_FINITE) != 0u ? 1 : 0;
    for (std::uint32_t mask = r.hitMask; mask != 0u; mask &= mask - 1u) {
        out.hits[std::countr_zero(mask)] += 1;
    }
    const std::uint32_t n = recordEvents ? kernels::eventCountOf(r) : 0u;
    for (std::uint32_t k = 0; k < n; ++k) {
        out.events.push_back(kernels::updateEvent(k, before, r, emitter, speed));
    }
}

// The slot of an update is free again: its particle died or was removed.
bool slotFreed(const kernels::ParticleUpdate& r) {
    return (r.events & (kernels::SD_EVENT_DIED | kernels::SD_EVENT_NON_FINITE)) != 0u;
}

// Adds chunk results to the step's counts and events in chunk order
// (deterministic) and returns their dead slots to the free list.
void mergeChunks(std::vector<ChunkResult>& chunks, EmitterState& e, StepStats& stats, StepEvents& events,
                 std::uint64_t& born, std::uint64_t& died, std::uint64_t& nonFinite) {
    for (ChunkResult& c : chunks) {
        std::size_t room = events.capacity - std::min<std::size_t>(events.capacity, events.records.size());
        std::size_t kept = std::min(room, c.events.size());
        events.records.insert(events.records.end(), c.events.begin(), c.events.begin() + static_cast<std::ptrdiff_t>(kept));
        events.dropped += c.events.size() - kept;
        born += c.born;
        died += c.died;
        nonFinite += c.nonFinite;
        for (std::size_t k = 0; k < stats.colliderHits.size() && k < 32; ++k) {
            stats.colliderHits[k].hits += c.hits[k];
        }
        e.freeSlots.insert(e.freeSlots.end(), c.dead.begin(), c.dead.end());
    }
}

}  // namespace

void stepEmitter(WorkerPool& pool, const kernels::KernelContext& ctx, EmitterState& e, std::uint32_t index,
                 double time, float dt, StepStats& stats, StepEvents& events) {
    const bool recordEvents = events.capacity > 0;
    const kernels::EmitterParams& params = e.params;
    const bool spawnMode = e.def.lifecycle == Lifecycle::Spawn;
    ParticleArrays& a = e.particles;
    const std::uint32_t trailPoints = e.def.trail.points;
    std::vector<ChunkResult> chunks(WorkerPool::chunkCount(e.def.capacity, kChunk));

    // Update: age, forces, integration, collisions and over-life values of
    // every slot; recycle slots are born and re-born here.
    {
        // The vector update takes the common case, whole batches of slots at
        // a time (src/effects/batch_update.h); the scalar kernel the rest.
        const UpdateTarget target = updateTarget();
        const bool batches = target != UpdateTarget::Scalar && batchUpdateEligible(ctx, params);
        pool.forChunks(e.def.capacity, kChunk, [&](std::size_t c, std::size_t begin, std::size_t end) {
            ChunkResult& out = chunks[c];
            std::uint32_t finished = 0;
            for (std::size_t i = begin; i < end; ++i) {
                const std::size_t lane = (i - begin) % kBatchLanes;
                if (lane == 0) {
                    finished = batches && i + kBatchLanes <= end ? updateBatch(target, ctx, params, a, i, dt) : 0u;
                }
                if ((finished >> lane & 1u) != 0u) {
                    recordTrail(a, trailPoints, e.trailHead, i, false);
                    continue;  // done by the vector update: no events
                }
                if (spawnMode && a.age[i] < 0.0f) {
                    continue;  // free slot
                }
                kernels::Particle p = loadParticle(a, params, i);
                kernels::ParticleUpdate r = kernels::updateParticle(ctx, params, p, dt);
                storeParticle(a, i, r.particle);
                recordTrail(a, trailPoints, e.trailHead, i, (r.events & kernels::SD_EVENT_BORN) != 0u);
                countUpdate(p, r, index, glm::length(p.velocity), recordEvents, out);
                if (spawnMode && slotFreed(r)) {
                    out.dead.push_back(static_cast<std::uint32_t>(i));
                }
            }
        });
    }

    // Free the dead: their slots go on the free list in slot order.
    std::uint64_t born = 0, died = 0, nonFinite = 0;
    mergeChunks(chunks, e, stats, events, born, died, nonFinite);

    // Emission (spawn mode): births owed this step take free slots; beyond
    // capacity they are dropped and counted, never overwriting live particles.
    if (spawnMode) {
        const BirthSchedule schedule = scheduleBirths(e, time, dt);
        const std::vector<float> ages = schedule.ages(e.freeSlots.size());
        const std::size_t count = ages.size();
        stats.clamped = saturatingAdd(stats.clamped, saturatingAdd(schedule.total() - count, schedule.dropped));
        std::vector<std::uint32_t> slots(e.freeSlots.end() - static_cast<std::ptrdiff_t>(count), e.freeSlots.end());
        e.freeSlots.resize(e.freeSlots.size() - count);
        const std::uint32_t firstSerial = e.nextSerial;
        std::vector<ChunkResult> birthChunks(WorkerPool::chunkCount(count, kChunk));
        pool.forChunks(count, kChunk, [&](std::size_t c, std::size_t begin, std::size_t end) {
            for (std::size_t k = begin; k < end; ++k) {
                // The slot at the back of the free list is used first.
                std::uint32_t slot = slots[count - 1 - k];
                auto serial = firstSerial + static_cast<std::uint32_t>(k);
                kernels::ParticleUpdate r = kernels::bornParticle(ctx, params, serial, ages[k]);
                if (r.particle.age >= r.particle.lifetime) {
                    r.particle = kernels::deadParticle(r.particle);  // killed at once by a collision
                    r.events |= kernels::SD_EVENT_DIED;
                }
                storeParticle(a, slot, r.particle);
                recordTrail(a, trailPoints, e.trailHead, slot, true);
                countUpdate(r.particle, r, index, glm::length(r.particle.velocity), recordEvents, birthChunks[c]);
                if (slotFreed(r)) {
                    birthChunks[c].dead.push_back(slot);
                }
            }
        });
        e.nextSerial += static_cast<std::uint32_t>(count);
        mergeChunks(birthChunks, e, stats, events, born, died, nonFinite);
    }

    // Tally.
    e.alive = e.alive + born - died - nonFinite;
    stats.born += born;
    stats.died += died;
    stats.nonFinite += nonFinite;
}

}  // namespace spindrift
