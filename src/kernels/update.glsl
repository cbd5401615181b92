// One step of one particle (GPU particle talk, "State-Preserving PS"): process
// birth and death, update velocity and position, collide, then derive the
// over-life colour and size. Requires the hooks of context_hooks.glsl.
#ifndef SPINDRIFT_KERNELS_UPDATE
#define SPINDRIFT_KERNELS_UPDATE
#include "collide.glsl"
#include "derived.glsl"
#include "integrate.glsl"
SD_BEGIN

SD_CONST uint SD_EVENT_BORN = 1u;
SD_CONST uint SD_EVENT_DIED = 2u;
// The particle of the update was removed because a number of it became NaN or
// infinite (issue 14): not a death (no event, which would carry the NaN), but
// counted on its own (StepStats::nonFinite) and its slot freed like a death's.
SD_CONST uint SD_EVENT_NON_FINITE = 4u;

struct ParticleUpdate {
    Particle particle;
    uint events;   // SD_EVENT_* bits
    uint hitMask;  // bit i: hit collider i during the step
    uint pad0;
    uint pad1;
};

// A particle whose step produced no events and no hits.
SD_FN ParticleUpdate quietUpdate(Particle p) {
    ParticleUpdate r;
    r.particle = p;
    r.events = 0u;
    r.hitMask = 0u;
    r.pad0 = 0u;
    r.pad1 = 0u;
    return r;
}

// Largest finite float: |x| <= it is false for NaN and for both infinities
// (plain comparisons, which GLSL and C++ without -ffast-math both keep).
SD_CONST float SD_FLOAT_MAX = 3.40282347e38f;

SD_FN bool finite3(vec3 v) {
    return all(lessThanEqual(abs(v), vec3(SD_FLOAT_MAX)));
}

// Finite numbers, and a speed whose square is finite too: speeds, lengths
// and drag all square the velocity, which overflows above 1.8e19 m/s and
// would put infinity into events and statistics.
SD_FN bool finiteParticle(Particle p) {
    return finite3(p.position) && finite3(p.velocity) && dot(p.velocity, p.velocity) <= SD_FLOAT_MAX &&
           finite3(vec3(p.rotation, p.angularVelocity, p.size)) &&
           all(lessThanEqual(abs(p.color), vec4(SD_FLOAT_MAX)));
}

// A particle whose numbers left the finite range (an attractor 1e-7 m away
// with strength 1e30 throws it at 1.7e32 m/s; speeds near 3e38): removed where it arises, with zeros
// in place of its numbers so no buffer, snapshot or event ever holds NaN or
// infinity. Its hits are dropped with it (their positions are not finite).
SD_FN ParticleUpdate removedUpdate(ParticleUpdate r) {
    Particle p = r.particle;
    p.position = vec3(0.0f);
    p.velocity = vec3(0.0f);
    p.rotation = 0.0f;
    p.angularVelocity = 0.0f;
    p.size = 0.0f;
    p.color = vec4(0.0f);
    p.age = SD_DEAD_AGE;
    p.alive = 0u;
    r.particle = p;
    r.hitMask = 0u;
    r.events = r.events | SD_EVENT_NON_FINITE;
    return r;
}

// The response to a hit h on collider c of a step that began at velocity v0
// and ended at velocity v1: the velocity at the contact (v0 to v1, at the
// hit's fraction t) reflected by the collider's rule and the position put on the
// surface, a skin outside. impact = 1 when the particle approached faster
// than the rest speed (events, kills, life loss); a particle resting on the
// ground is pushed out every step but is not hitting it. Shared with the
// CPU's vector update (batch_update_body.inc).
struct Contact {
    Motion motion;
    uint impact;
};

SD_FN Contact contactResponse(SD_IN(ColliderParams) c, Hit h, vec3 v0, vec3 v1) {
    Contact k;
    vec3 contactVelocity = mix(v0, v1, h.t);
    k.motion.velocity = collisionVelocity(c, h.normal, contactVelocity);
    k.motion.position = h.point + h.normal * SD_COLLISION_SKIN;
    k.impact = -dot(contactVelocity, h.normal) > c.restSpeed ? 1u : 0u;
    return k;
}

// The age (s) of a particle of `lifetime` that struck a collider at `age`:
// its lifetime when collisions kill (it dies now; a recycle slot is re-born
// next step), else the emitter's share of the life it had left taken off.
// Branch-free (a select), so the CPU's lane loops vectorise it.
SD_FN float ageAfterImpact(SD_IN(EmitterParams) e, float age, float lifetime) {
    float lost = age + e.lifeLossOnCollision * max(lifetime - age, 0.0f);
    return selectf(lost, lifetime, (e.flags & SD_EMITTER_KILL_ON_COLLISION) != 0u);
}

// Motion, damping, collisions and spin over dt for a live particle; one whose
// numbers became non-finite comes back removed (SD_EVENT_NON_FINITE).
SD_FN ParticleUpdate simulateParticle(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, Particle p, float dt) {
    ParticleUpdate r = quietUpdate(p);
    vec3 start = p.position;
    Motion m = integrateMotion(ctx, e, p.position, p.velocity, p.mass, 0.5f * p.size, dt);
    m.velocity = applySpeedRelaxation(ctx, e, m.position, m.velocity, dt);
    if ((e.flags & SD_EMITTER_COLLISIONS) != 0u) {
        uint n = colliderCount(ctx);
        for (uint i = 0u; i < n; ++i) {
            if ((e.colliderMask & (1u << i)) == 0u) {
                continue;
            }
            SD_LET(ColliderParams) c = colliderAt(ctx, i);
            Hit h = intersectCollider(ctx, c, start, m.position);
            if (h.hit == 0u) {
                continue;
            }
            Contact k = contactResponse(c, h, p.velocity, m.velocity);
            m = k.motion;
            if (k.impact != 0u) {
                r.hitMask = r.hitMask | (1u << i);
            }
        }
    }
    p.position = m.position;
    p.velocity = m.velocity;
    p.rotation = p.rotation + p.angularVelocity * dt;
    if (r.hitMask != 0u) {
        p.age = ageAfterImpact(e, p.age, p.lifetime);
    }
    r.particle = applyOverLife(e, p);
    return finiteParticle(r.particle) ? r : removedUpdate(r);
}

// A spawned particle p (spawnParticle) that has lived `age` seconds of this
// step: simulated over them, marked born.
SD_FN ParticleUpdate startParticle(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, Particle p, float age) {
    p.age = min(age, p.lifetime * 0.999f);
    ParticleUpdate r = simulateParticle(ctx, e, p, p.age);
    r.events = r.events | SD_EVENT_BORN;
    return r;
}

// A fresh particle with serial `serial` that has lived `age` seconds of this step.
SD_FN ParticleUpdate bornParticle(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, uint serial, float age) {
    return startParticle(ctx, e, spawnParticle(e, serial), age);
}

SD_FN Particle deadParticle(Particle p) {
    p.age = SD_DEAD_AGE;
    p.alive = 0u;
    return p;
}

// The whole step of one slot. Recycle slots are born when their (initially
// negative, phase-staggered) age reaches 0 and re-born when it reaches the
// lifetime, keeping the remainder so emission stays evenly phased; the serial
// advances by the capacity so every life of every slot has its own key.
SD_FN ParticleUpdate updateParticle(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, Particle p, float dt) {
    bool recycle = (e.flags & SD_EMITTER_RECYCLE) != 0u;
    float age = p.age + dt;
    if (p.age < 0.0f) {
        if (age < 0.0f || !recycle) {
            p.age = recycle ? age : SD_DEAD_AGE;
            return quietUpdate(p);
        }
        return bornParticle(ctx, e, p.birth, age);
    }
    if (age >= p.lifetime) {
        if (recycle) {
            ParticleUpdate r = bornParticle(ctx, e, p.birth + e.capacity, age - p.lifetime);
            r.events = r.events | SD_EVENT_DIED;
            return r;
        }
        ParticleUpdate r = quietUpdate(deadParticle(p));
        r.events = SD_EVENT_DIED;
        return r;
    }
    p.age = age;
    ParticleUpdate r = simulateParticle(ctx, e, p, dt);
    if (!recycle && r.particle.age >= r.particle.lifetime) {
        // Killed by a collision or its life used up by hits: dies this step.
        r.particle = deadParticle(r.particle);
        r.events = r.events | SD_EVENT_DIED;
    }
    return r;
}

// Events of an update (GPU -> CPU feedback, for impact sounds, hit counters,
// fires put out by water): one collision per collider hit, then one death.
SD_FN uint eventCountOf(ParticleUpdate r) {
    return uint(bitCount(r.hitMask)) + ((r.events & SD_EVENT_DIED) != 0u ? 1u : 0u);
}

SD_FN EventRecord eventRecord(uint kind, uint colliderPlusOne, uint emitter, Particle p, float speed) {
    EventRecord e;
    e.positionSpeed = vec4(p.position, speed);
    e.header = uvec4(kind, colliderPlusOne, emitter, p.birth);
    return e;
}

// Event n (< eventCountOf(r)) of the update of `before` into r; speed: m/s at
// the start of the step. Hits come in collider order, at the particle's end
// position. The death names the particle that died (in recycle mode r holds
// its successor: then `before`, where it was at the start of the step) and the
// first collider hit in the step, the killer when collisions kill, or none.
SD_FN EventRecord updateEvent(uint n, Particle before, ParticleUpdate r, uint emitter, float speed) {
    uint mask = r.hitMask;
    for (uint k = 0u; k < n && mask != 0u; ++k) {
        mask &= mask - 1u;
    }
    if (mask != 0u) {
        return eventRecord(SD_EVENT_KIND_COLLISION, uint(findLSB(mask)) + 1u, emitter, r.particle, speed);
    }
    uint killer = r.hitMask != 0u ? uint(findLSB(r.hitMask)) + 1u : 0u;
    Particle dying = r.particle.birth != before.birth ? before : r.particle;
    return eventRecord(SD_EVENT_KIND_DEATH, killer, emitter, dying, speed);
}

SD_END
#endif
