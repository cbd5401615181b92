// Sub-emitters (EmitterDef::spawnOn, docs/scene-format.md "Sub-emitters"):
// a parent emitter's births, deaths or collisions become spawn requests, and
// each request gives its child emitter `count` particles there. Both
// backends make the requests from the same update results and the children
// from the same requests with these functions: the CPU in emitter order, the
// Vulkan backend through a request buffer per parent and event kind. The
// request itself (SpawnRequest) is in types.glsl.
#ifndef SPINDRIFT_KERNELS_SUB_EMIT
#define SPINDRIFT_KERNELS_SUB_EMIT
#include "update.glsl"
SD_BEGIN

// Requests of kind `kind` an update makes: its birth, its death, one per
// collider hit. A removed particle (non-finite numbers) makes none.
SD_FN uint spawnRequestCount(ParticleUpdate r, uint kind) {
    if ((r.events & SD_EVENT_NON_FINITE) != 0u) {
        return 0u;
    }
    if (kind == SD_SPAWN_ON_BIRTH) {
        return (r.events & SD_EVENT_BORN) != 0u ? 1u : 0u;
    }
    if (kind == SD_SPAWN_ON_DEATH) {
        return (r.events & SD_EVENT_DIED) != 0u ? 1u : 0u;
    }
    return uint(bitCount(r.hitMask));
}

SD_FN SpawnRequest makeSpawnRequest(Particle p, uint collider, uint step, uint kind) {
    SpawnRequest q;
    q.position = vec4(p.position, 0.0f);
    q.velocity = vec4(p.velocity, 0.0f);
    q.header = uvec4(p.birth, collider, step, kind);
    return q;
}

// Request n (< spawnRequestCount(r, kind)) of the update of `before` into r
// in world step `step`. A death is where the dying particle ended (in recycle
// mode r holds its successor: then `before`, at the start of the step); a
// birth and a hit are where the particle is at the end of the step, hits in
// collider order.
SD_FN SpawnRequest spawnRequest(uint n, Particle before, ParticleUpdate r, uint kind, uint step) {
    if (kind == SD_SPAWN_ON_DEATH) {
        Particle dying = r.particle.birth != before.birth ? before : r.particle;
        return makeSpawnRequest(dying, 0u, step, kind);
    }
    if (kind == SD_SPAWN_ON_BIRTH) {
        return makeSpawnRequest(r.particle, 0u, step, kind);
    }
    uint mask = r.hitMask;
    for (uint k = 0u; k < n && mask != 0u; ++k) {
        mask &= mask - 1u;
    }
    return makeSpawnRequest(r.particle, uint(findLSB(mask)) + 1u, step, kind);
}

// Serial of copy `copy` of a request's children: a function of the request
// alone, so both backends (and any order of requests) give every child the
// same serial and so the same random numbers.
SD_FN uint childSerial(SpawnRequest q, uint copy) {
    uint h = pcgHash(q.header.x ^ pcgHash(q.header.y + 0x9E3779B9u * q.header.w));
    h = pcgHash(h ^ pcgHash(q.header.z * 0x85EBCA6Bu + copy));
    return SD_SUB_SERIAL_BIT | (h & (SD_SUB_SERIAL_BIT - 1u));
}

// Copy `copy` of a request's children, born at the end of the step: the child
// emitter's own spawn (its shape centred on the event, its launch velocity)
// plus `inherit` of the parent particle's velocity.
SD_FN ParticleUpdate childParticle(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, SpawnRequest q, uint copy,
                                   float inherit) {
    Particle p = spawnParticle(e, childSerial(q, copy));
    p.position = p.position + vec3(q.position);
    p.velocity = p.velocity + vec3(q.velocity) * inherit;
    return startParticle(ctx, e, p, 0.0f);
}

SD_END

#endif
