// One step of one state-preserving emitter on the CPU: a named list of passes.
#include "effects/emitter_step.h"

#include "effects/batch_update.h"

#include "core/chunk_prefix.h"
#include "core/saturating.h"
#include "kernels/sub_emit.glsl"
#include "kernels/trail.glsl"
#include "particles/birth_schedule.h"
#include "particles/slots.h"

#include <bit>
#include <cassert>
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
    // Events counted but not built: the chunks before this one had already
    // offered the step's room (ChunkPrefix), so none of them could be kept.
    std::uint64_t eventsSkipped = 0;
    bool skipEvents = false;  // set while the update's chunks before this one fill the room
    std::vector<kernels::SpawnRequest> requests[kernels::SD_SPAWN_EVENT_KINDS];  // for sub-emitters
};

// What every update of one emitter's step shares.
struct StepScope {
    const kernels::KernelContext& ctx;
    EmitterState& e;
    std::uint32_t index;  // the emitter's, in its world
    std::uint32_t step;   // the world's step (low 32 bits; spawn requests)
    bool recordEvents;
};

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
// its events (speed: m/s at the start of the step) and the spawn requests its
// sub-emitters follow.
void countUpdate(const StepScope& scope, const kernels::Particle& before, const kernels::ParticleUpdate& r,
                 float speed, ChunkResult& out) {
    out.born += (r.events & kernels::SD_EVENT_BORN) != 0u ? 1 : 0;
    out.died += (r.events & kernels::SD_EVENT_DIED) != 0u ? 1 : 0;
    out.nonFinite += (r.events & kernels::SD_EVENT_NON_FINITE) != 0u ? 1 : 0;
    for (std::uint32_t mask = r.hitMask; mask != 0u; mask &= mask - 1u) {
        out.hits[std::countr_zero(mask)] += 1;
    }
    const std::uint32_t n = scope.recordEvents ? kernels::eventCountOf(r) : 0u;
    if (out.skipEvents) {
        out.eventsSkipped += n;
    }
    for (std::uint32_t k = 0; k < n && !out.skipEvents; ++k) {
        out.events.push_back(kernels::updateEvent(k, before, r, scope.index, speed));
    }
    for (std::uint32_t kinds = scope.e.requestKinds; kinds != 0u; kinds &= kinds - 1u) {
        const auto kind = static_cast<std::uint32_t>(std::countr_zero(kinds));
        const std::uint32_t count = kernels::spawnRequestCount(r, kind);
        for (std::uint32_t k = 0; k < count; ++k) {
            out.requests[kind].push_back(kernels::spawnRequest(k, before, r, kind, scope.step));
        }
    }
}

// countUpdate for slot i, updated by the vector update in a step in which it
// struck the colliders of `hitMask` and neither was born nor died: the update
// the scalar kernel would have returned is the stored particle with that
// mask. (`before` is read only for deaths, so the particle after serves;
// events and spawn requests read no colour or size.)
void countImpact(const StepScope& scope, const ParticleArrays& a, const kernels::EmitterParams& params,
                 std::size_t i, std::uint32_t hitMask, glm::vec3 startVelocity, ChunkResult& out) {
    kernels::ParticleUpdate r = kernels::quietUpdate(storedParticle(a, params, i));
    r.hitMask = hitMask;
    countUpdate(scope, r.particle, r, glm::length(startVelocity), out);
}

// countImpact for a struck lane of a batch the vector update finished, in a
// step that owes no spawn requests: the hits' counts and, when events are
// recorded and have room, their records (updateEvent: a hit's record reads
// the particle's position and birth serial, in collider order), built from
// those two arrays instead of a whole particle. Events past the room read
// neither: the birth serials are not in cache (the update does not read
// them), and a launch strikes the ground 50,000 times a step.
void countLaneImpact(const StepScope& scope, const ParticleArrays& a, const BatchResult& batch, std::size_t lane,
                     std::size_t i, ChunkResult& out) {
    const std::uint32_t hitMask = batch.hitMask[lane];
    for (std::uint32_t mask = hitMask; mask != 0u; mask &= mask - 1u) {
        out.hits[std::countr_zero(mask)] += 1;
    }
    if (!scope.recordEvents) {
        return;
    }
    if (out.skipEvents) {
        out.eventsSkipped += static_cast<std::uint64_t>(std::popcount(hitMask));
        return;
    }
    kernels::Particle hit{};
    hit.position = a.position[i];
    hit.birth = a.birth[i];
    const float speed = glm::length(batch.startVelocity[lane]);
    for (std::uint32_t mask = hitMask; mask != 0u; mask &= mask - 1u) {
        const auto collider = static_cast<std::uint32_t>(std::countr_zero(mask));
        out.events.push_back(
            kernels::eventRecord(kernels::SD_EVENT_KIND_COLLISION, collider + 1u, scope.index, hit, speed));
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
        events.dropped += c.events.size() - kept + c.eventsSkipped;
        assert(c.eventsSkipped == 0 || room == 0);  // only events past the room are skipped
        born += c.born;
        died += c.died;
        nonFinite += c.nonFinite;
        for (std::size_t k = 0; k < stats.colliderHits.size() && k < 32; ++k) {
            stats.colliderHits[k].hits += c.hits[k];
        }
        e.freeSlots.insert(e.freeSlots.end(), c.dead.begin(), c.dead.end());
        for (std::uint32_t kind = 0; kind < kernels::SD_SPAWN_EVENT_KINDS; ++kind) {
            // At most the capacity a step, as the device's request buffers.
            std::vector<kernels::SpawnRequest>& to = e.requests[kind];
            const std::size_t room = e.def.capacity - std::min<std::size_t>(e.def.capacity, to.size());
            const std::size_t take = std::min(room, c.requests[kind].size());
            to.insert(to.end(), c.requests[kind].begin(), c.requests[kind].begin() + static_cast<std::ptrdiff_t>(take));
            e.requestsDropped[kind] += c.requests[kind].size() - take;
        }
    }
}

// Places `count` births (spawn mode) on the back of the free list, the last
// free slot first: birth k is makeBirth(k), a particle born at once; one that
// a collision killed at once leaves its slot free. The births are chunked by
// index, so their results merge in the same order for any thread count.
template <class MakeBirth>
void placeBirths(WorkerPool& pool, const StepScope& scope, std::size_t count, MakeBirth makeBirth,
                 StepStats& stats, StepEvents& events, std::uint64_t& born, std::uint64_t& died,
                 std::uint64_t& nonFinite) {
    EmitterState& e = scope.e;
    ParticleArrays& a = e.particles;
    std::vector<std::uint32_t> slots(e.freeSlots.end() - static_cast<std::ptrdiff_t>(count), e.freeSlots.end());
    e.freeSlots.resize(e.freeSlots.size() - count);
    std::vector<ChunkResult> chunks(WorkerPool::chunkCount(count, kChunk));
    pool.forChunks(count, kChunk, [&](std::size_t c, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const std::uint32_t slot = slots[count - 1 - k];
            kernels::ParticleUpdate r = makeBirth(k);
            if (r.particle.age >= r.particle.lifetime) {
                r.particle = kernels::deadParticle(r.particle);  // killed at once by a collision
                r.events |= kernels::SD_EVENT_DIED;
            }
            storeParticle(a, slot, r.particle);
            recordTrail(a, e.def.trail.points, e.trailHead, slot, true);
            countUpdate(scope, r.particle, r, glm::length(r.particle.velocity), chunks[c]);
            if (slotFreed(r)) {
                chunks[c].dead.push_back(slot);
            }
        }
    });
    mergeChunks(chunks, e, stats, events, born, died, nonFinite);
}

}  // namespace

void stepEmitter(WorkerPool& pool, const kernels::KernelContext& ctx, EmitterState& e, std::uint32_t index,
                 std::uint64_t step, double time, float dt, const EmitterState* parent, StepStats& stats,
                 StepEvents& events) {
    const StepScope scope{ctx, e, index, static_cast<std::uint32_t>(step), events.capacity > 0};
    for (std::uint32_t kind = 0; kind < kernels::SD_SPAWN_EVENT_KINDS; ++kind) {
        e.requests[kind].clear();
        e.requestsDropped[kind] = 0;
    }
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
        const BatchConstants constants = batches ? batchConstants(ctx, params, dt) : BatchConstants{};
        const bool requests = scope.e.requestKinds != 0u;
        // The step keeps the first events in chunk order, as many as it has
        // room for: a chunk after a finished prefix that offered that many
        // only counts its own (a launch strikes the ground 50,000 times a
        // step, with room for 4,096).
        const std::size_t room = events.capacity - std::min<std::size_t>(events.capacity, events.records.size());
        ChunkPrefix offered(scope.recordEvents ? chunks.size() : 0u, room);
        pool.forChunks(e.def.capacity, kChunk, [&](std::size_t c, std::size_t begin, std::size_t end) {
            ChunkResult& out = chunks[c];
            for (std::size_t first = begin; first < end; first += kBatchLanes) {
                out.skipEvents = scope.recordEvents && offered.full();
                const std::size_t last = std::min(first + kBatchLanes, end);
                const BatchResult batch = batches && last - first == kBatchLanes
                                              ? updateBatch(target, ctx, params, constants, a, first, dt)
                                              : BatchResult{};
                // The lanes left to do, in slot order (events keep it): every
                // lane the vector update did not finish, and those it finished
                // that struck a collider or have a trail to record.
                const LaneMask lanes = kAllBatchLanes >> (kBatchLanes - (last - first));
                LaneMask work = trailPoints != 0u ? lanes : (lanes & ~batch.finished) | batch.struck;
                for (; work != 0u; work &= work - 1u) {
                    const auto lane = static_cast<std::size_t>(std::countr_zero(work));
                    const std::size_t i = first + lane;
                    if ((batch.finished >> lane & 1u) != 0u) {
                        recordTrail(a, trailPoints, e.trailHead, i, false);
                        if ((batch.struck >> lane & 1u) == 0u) {
                            continue;
                        }
                        if (requests) {  // spawn requests read the whole particle
                            countImpact(scope, a, params, i, batch.hitMask[lane], batch.startVelocity[lane], out);
                        } else {
                            countLaneImpact(scope, a, batch, lane, i, out);
                        }
                        continue;  // done by the vector update
                    }
                    if (spawnMode && a.age[i] < 0.0f) {
                        continue;  // free slot
                    }
                    kernels::Particle p = loadForUpdate(a, params, i);
                    kernels::ParticleUpdate r = kernels::updateParticle(ctx, params, p, dt);
                    storeParticle(a, i, r.particle);
                    recordTrail(a, trailPoints, e.trailHead, i, (r.events & kernels::SD_EVENT_BORN) != 0u);
                    countUpdate(scope, p, r, glm::length(p.velocity), out);
                    if (spawnMode && slotFreed(r)) {
                        out.dead.push_back(static_cast<std::uint32_t>(i));
                    }
                }
            }
            if (scope.recordEvents) {
                offered.finish(c, out.events.size() + out.eventsSkipped);
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
        const std::uint32_t firstSerial = e.nextSerial;
        placeBirths(
            pool, scope, count,
            [&](std::size_t k) {
                return kernels::bornParticle(ctx, params, firstSerial + static_cast<std::uint32_t>(k), ages[k]);
            },
            stats, events, born, died, nonFinite);
        e.nextSerial += static_cast<std::uint32_t>(count);
    }

    // Sub-emission: `count` births at each of the parent's requests of this
    // step (src/kernels/sub_emit.glsl), in request order, after the
    // emitter's own; beyond the free slots, and for requests the parent
    // could not keep, they are dropped and counted.
    if (parent != nullptr) {
        const SpawnOnDef& on = e.def.spawnOn;
        const auto kind = static_cast<std::uint32_t>(on.event);
        const std::vector<kernels::SpawnRequest>& requests = parent->requests[kind];
        const std::uint64_t owed = std::uint64_t{requests.size()} * on.count;
        const std::uint64_t owedAll = owed + parent->requestsDropped[kind] * on.count;
        const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(owed, e.freeSlots.size()));
        stats.clamped = saturatingAdd(stats.clamped, owedAll - count);
        placeBirths(
            pool, scope, count,
            [&](std::size_t k) {
                return kernels::childParticle(ctx, params, requests[k / on.count],
                                              static_cast<std::uint32_t>(k % on.count), on.inheritVelocity);
            },
            stats, events, born, died, nonFinite);
    }

    // Tally.
    e.alive = e.alive + born - died - nonFinite;
    stats.born += born;
    stats.died += died;
    stats.nonFinite += nonFinite;
}

}  // namespace spindrift
