#version 450
// The passes of one emitter's step over structure-of-arrays storage buffers:
// the shared updateParticle and bornParticle of src/kernels/update.glsl. The
// physics lives only in src/kernels/*.glsl; this file only binds data to the
// hooks of context_hooks.glsl, keeps the spawn-mode slot lists and counts
// events. Each pass is a module of its own (glslc -DSD_PASS_<NAME>_MODULE,
// CMakeLists.txt), so a module holds only its pass's functions and a driver
// parses and optimises no other pass's code when it builds the pipeline
// (lavapipe built the spawn-finish pass, one thread's bookkeeping, in as long
// as an update when one module held every pass):
//   recycle update: every slot (direct dispatch of the capacity);
//   spawn update: the current alive list (indirect dispatch); the dead go on
//     the dead stack, survivors on the next alive list;
//   spawn emit: birth k of the step's schedule pops a dead slot, or is clamped;
//   spawn finish: one thread writes the next step's indirect dispatch;
//   sub-emit: a sub-emitter's births from its parent's spawn requests
//     (sub_emit.glsl), after the emit pass, one thread per birth.
#include "layout.glsl"
#include "noise.glsl"

layout(local_size_x = SD_UPDATE_WORKGROUP) in;

layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_EMITTER) readonly buffer Emitter { EmitterParams emitter; };
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_FORCES) readonly buffer Forces {
    TableHeader forceTable;
    ForceParams forces[];
};
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_COLLIDERS) readonly buffer Colliders {
    TableHeader colliderTable;
    ColliderParams colliders[];
};
// vec3 arrays have a 16-byte stride in std430: positions and velocities are
// tightly packed floats instead, matching the CPU's glm::vec3 arrays. Only
// what changes after birth is stored (restoreDerived of update.glsl recomputes
// lifetime, angular velocity, colour and size): 20 B read and written per
// particle-step plus the 4 B birth serial read (written at birth only); see
// docs/performance.md.
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_POSITIONS) buffer Positions { float positions[]; };
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_VELOCITIES) buffer Velocities { float velocities[]; };
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_AGES) buffer Ages { float ages[]; };
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_BIRTHS) buffer Births { uint births[]; };
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_ROTATIONS) buffer Rotations { float rotations[]; };
// The trail's positions (trail.glsl): float triples, step.trailPoints per slot.
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_TRAILS) buffer Trails { float trails[]; };
// Counts of the step (one copy per frame in flight; StepCounters in layout.glsl).
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_COUNTERS) buffer Counters { StepCounters counters; };
// Collision and death events of the step, shared by every emitter of the world
// (one copy per frame in flight; EventsHeader in layout.glsl).
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_EVENTS) buffer Events {
    EventsHeader eventHeader;
    EventRecord events[];
};

// This step's spawn requests of the emitter's particles, one buffer per event
// kind (sub_emit.glsl), written where some sub-emitter follows the kind
// (step.requestKinds); count goes on past capacity, so the excess is known.
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_BIRTH_REQUESTS) buffer BirthRequests {
    EventsHeader birthHeader;
    SpawnRequest birthRequests[];
};
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_DEATH_REQUESTS) buffer DeathRequests {
    EventsHeader deathHeader;
    SpawnRequest deathRequests[];
};
layout(std430, set = SD_SET_EMITTER, binding = SD_BINDING_COLLISION_REQUESTS) buffer CollisionRequests {
    EventsHeader collisionHeader;
    SpawnRequest collisionRequests[];
};

// Spawn mode (set 1; recycle emitters bind a placeholder that is never read).
// The dead stack (DeadHeader in layout.glsl) starts as the CPU's free list
// (slot 0 on top).
layout(std430, set = SD_SET_LISTS, binding = SD_BINDING_DEAD) buffer Dead {
    DeadHeader dead;
    uint deadSlots[];
};
// Slots alive at the start of the step, and those alive at its end; the CPU
// swaps the two between steps by binding the other descriptor set.
layout(std430, set = SD_SET_LISTS, binding = SD_BINDING_ALIVE_IN) buffer AliveIn {
    TableHeader aliveInTable;
    uint aliveIn[];
};
layout(std430, set = SD_SET_LISTS, binding = SD_BINDING_ALIVE_OUT) buffer AliveOut {
    TableHeader aliveOutTable;
    uint aliveOut[];
};
// A sub-emitter's parent's requests of the kind it follows.
layout(std430, set = SD_SET_LISTS, binding = SD_BINDING_PARENT_REQUESTS) readonly buffer ParentRequests {
    EventsHeader parentHeader;
    SpawnRequest parentRequests[];
};
// The step's births (ScheduleHeader in layout.glsl, written by the CPU).
layout(std430, set = SD_SET_LISTS, binding = SD_BINDING_SCHEDULE) readonly buffer Schedule {
    ScheduleHeader schedule;
    uvec2 runs[];  // x: end index (exclusive), y: floatBitsToUint(age)
};

layout(push_constant) uniform Step { StepPush step; };

// Sampled fields of the world (set 2), bound by src/gpu: one linear,
// clamp-to-edge sampler, normalised coordinates, level 0, so texel i of n has
// its centre at (i + 0.5) / n as context_hooks.glsl requires. Unused elements
// show a placeholder.
layout(set = SD_SET_FIELDS, binding = SD_BINDING_FLOW_FIELDS) uniform sampler3D flowFields[SD_MAX_FLOW_FIELDS];
layout(set = SD_SET_FIELDS, binding = SD_BINDING_HEIGHT_MAPS) uniform sampler2D heightMaps[SD_MAX_HEIGHT_MAPS];
layout(set = SD_SET_FIELDS, binding = SD_BINDING_CUBE_MAPS) uniform samplerCube cubeMaps[SD_MAX_CUBE_MAPS];

// Field counts and the integrator are specialization constants of the
// pipeline (src/gpu keeps one pipeline per combination a world uses), for
// two reasons. lavapipe (Mesa 22.3) lacks shaderSampledImageArrayDynamicIndexing,
// so a sampler array may only be indexed by constants: the hooks below switch
// over literal indices. And llvmpipe compiles every inlined sample site of the
// kernels at pipeline creation (RK4's four forcingAt, the sampled-collider
// march, bisection and normals): with all 8 elements of all 3 arrays live that
// took minutes per pipeline. The constants let the driver drop the elements a
// world does not use and the integrators an emitter does not run.
layout(constant_id = SD_SPEC_FLOW_FIELDS) const uint FLOW_FIELDS = 0u;
layout(constant_id = SD_SPEC_HEIGHT_MAPS) const uint HEIGHT_MAPS = 0u;
layout(constant_id = SD_SPEC_CUBE_MAPS) const uint CUBE_MAPS = 0u;
layout(constant_id = SD_SPEC_INTEGRATOR) const uint INTEGRATOR = SD_ANY_INTEGRATOR;
layout(constant_id = SD_SPEC_CURL_NOISE) const uint CURL_NOISE = 0u;

struct KernelContext { uint unused; };
uint forceCount(KernelContext ctx) { return forceTable.count; }
ForceParams forceAt(KernelContext ctx, uint i) { return forces[i]; }
uint colliderCount(KernelContext ctx) { return colliderTable.count; }
ColliderParams colliderAt(KernelContext ctx, uint i) { return colliders[i]; }
uint integratorOf(EmitterParams e) { return INTEGRATOR == SD_ANY_INTEGRATOR ? e.integrator : INTEGRATOR; }

// One case per element, each live only below the world's count.
#define SD_SAMPLE_CASE(array, count, i, coord) \
    case i: if (i < count) { return textureLod(array[i], coord, 0.0f); } break;
#define SD_SAMPLE_SWITCH(array, count, index, coord) \
    switch (index) { \
        SD_SAMPLE_CASE(array, count, 0u, coord) SD_SAMPLE_CASE(array, count, 1u, coord) \
        SD_SAMPLE_CASE(array, count, 2u, coord) SD_SAMPLE_CASE(array, count, 3u, coord) \
        SD_SAMPLE_CASE(array, count, 4u, coord) SD_SAMPLE_CASE(array, count, 5u, coord) \
        SD_SAMPLE_CASE(array, count, 6u, coord) SD_SAMPLE_CASE(array, count, 7u, coord) \
        default: break; \
    }

vec4 sampleFlowImage(uint field, vec3 uvw) {
    SD_SAMPLE_SWITCH(flowFields, FLOW_FIELDS, field, uvw)
    return vec4(0.0f);
}
vec4 sampleHeightImage(uint map, vec2 uv) {
    SD_SAMPLE_SWITCH(heightMaps, HEIGHT_MAPS, map, uv)
    return vec4(0.0f);
}
vec4 sampleCubeImage(uint map, vec3 direction) {
    SD_SAMPLE_SWITCH(cubeMaps, CUBE_MAPS, map, direction)
    return vec4(0.0f, 1.0f, 0.0f, 0.0f);
}
vec3 sampleFlowField(KernelContext ctx, uint field, vec3 uvw) { return sampleFlowImage(field, uvw).xyz; }
float sampleTerrainHeight(KernelContext ctx, uint map, vec2 uv) { return sampleHeightImage(map, uv).x; }
vec4 sampleCubeMap(KernelContext ctx, uint map, vec3 direction) { return sampleCubeImage(map, direction); }
// The noise's code is live only in pipelines of emitters that use it: llvmpipe
// compiles every inlined copy (one per forcingAt) at pipeline creation.
vec3 sampleCurlNoise(KernelContext ctx, ForceParams f, vec3 p) {
    if (CURL_NOISE != 0u) {
        return curlNoiseVelocity(f, p, step.time);
    }
    return vec3(0.0f);
}

#include "update.glsl"
#include "birth_age.glsl"
#include "sub_emit.glsl"
#include "trail.glsl"

Particle loadParticle(uint i) {
    Particle p;
    p.position = vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]);
    p.velocity = vec3(velocities[3u * i], velocities[3u * i + 1u], velocities[3u * i + 2u]);
    p.age = ages[i];
    p.rotation = rotations[i];
    p.mass = emitter.mass;
    p.birth = births[i];
    p.alive = p.age >= 0.0f ? 1u : 0u;
    return restoreDerived(emitter, p);
}

void storeTrailPoint(uint index, vec3 p) {
    trails[3u * index] = p.x;
    trails[3u * index + 1u] = p.y;
    trails[3u * index + 2u] = p.z;
}

// A stored slot's trail (trail.glsl, as the CPU's recordTrail in
// src/effects/emitter_step.cpp).
void recordTrail(uint i, Particle q, uint events) {
    bool born = (events & SD_EVENT_BORN) != 0u;
    uint writes = trailWrites(step.trailPoints, q.age >= 0.0f, born);
    for (uint j = 0u; j < writes; ++j) {
        storeTrailPoint(trailWriteIndex(i, j, step.trailHead, step.trailPoints, born), q.position);
    }
}

// The birth serial changes only when the slot gets a new particle.
void storeParticle(uint i, Particle q, uint events) {
    positions[3u * i] = q.position.x;
    positions[3u * i + 1u] = q.position.y;
    positions[3u * i + 2u] = q.position.z;
    velocities[3u * i] = q.velocity.x;
    velocities[3u * i + 1u] = q.velocity.y;
    velocities[3u * i + 2u] = q.velocity.z;
    ages[i] = q.age;
    rotations[i] = q.rotation;
    if ((events & SD_EVENT_BORN) != 0u) {
        births[i] = q.birth;
    }
    recordTrail(i, q, events);
}

void appendRequest(uint kind, SpawnRequest q) {
    if (kind == SD_SPAWN_ON_BIRTH) {
        uint i = atomicAdd(birthHeader.count, 1u);
        if (i < birthHeader.capacity) {
            birthRequests[i] = q;
        }
    } else if (kind == SD_SPAWN_ON_DEATH) {
        uint i = atomicAdd(deathHeader.count, 1u);
        if (i < deathHeader.capacity) {
            deathRequests[i] = q;
        }
    } else {
        uint i = atomicAdd(collisionHeader.count, 1u);
        if (i < collisionHeader.capacity) {
            collisionRequests[i] = q;
        }
    }
}

// The spawn requests of the update of `before` into r, for the kinds some
// sub-emitter follows. Their order in the buffers varies run to run; what a
// child makes of one does not (childSerial).
void writeRequests(Particle before, ParticleUpdate r) {
    for (uint kinds = step.requestKinds; kinds != 0u; kinds &= kinds - 1u) {
        uint kind = uint(findLSB(kinds));
        uint n = spawnRequestCount(r, kind);
        for (uint k = 0u; k < n; ++k) {
            appendRequest(kind, spawnRequest(k, before, r, kind, step.step));
        }
    }
}

// Atomics only where something happened: most slots in most steps have no
// event. speed: m/s at the start of the step (EventRecord).
void countEvents(Particle before, ParticleUpdate r, float speed) {
    writeRequests(before, r);
    if ((r.events & SD_EVENT_BORN) != 0u) {
        atomicAdd(counters.born, 1u);
    }
    if ((r.events & SD_EVENT_DIED) != 0u) {
        atomicAdd(counters.died, 1u);
    }
    if ((r.events & SD_EVENT_NON_FINITE) != 0u) {
        atomicAdd(counters.nonFinite, 1u);
    }
    for (uint mask = r.hitMask; mask != 0u; mask &= mask - 1u) {
        atomicAdd(counters.hits[findLSB(mask)], 1u);
    }
    uint n = eventHeader.capacity > 0u ? eventCountOf(r) : 0u;
    if (n > 0u) {
        uint first = atomicAdd(eventHeader.count, n);
        for (uint k = 0u; k < n && first + k < eventHeader.capacity; ++k) {
            events[first + k] = updateEvent(k, before, r, step.emitterIndex, speed);
        }
    }
}

void recycleUpdate(KernelContext ctx, uint i) {
    if (i >= step.count) {
        return;
    }
    Particle p = loadParticle(i);
    ParticleUpdate r = updateParticle(ctx, emitter, p, step.dt);
    storeParticle(i, r.particle, r.events);
    countEvents(p, r, length(p.velocity));
}

void spawnUpdate(KernelContext ctx, uint i) {
    if (i >= aliveInTable.count) {
        return;
    }
    uint slot = aliveIn[i];
    Particle p = loadParticle(slot);
    ParticleUpdate r = updateParticle(ctx, emitter, p, step.dt);
    storeParticle(slot, r.particle, r.events);
    countEvents(p, r, length(p.velocity));
    if ((r.events & (SD_EVENT_DIED | SD_EVENT_NON_FINITE)) != 0u) {
        deadSlots[atomicAdd(dead.deadCount, 1u)] = slot;
    } else {
        aliveOut[atomicAdd(aliveOutTable.count, 1u)] = slot;
    }
}

// Age of birth k at the end of the step: BirthSchedule::ages().
float birthAge(uint k) {
    for (uint b = 0u; b < schedule.burstRuns; ++b) {
        if (k < runs[b].x) {
            return uintBitsToFloat(runs[b].y);
        }
    }
    return rateBirthAge(float(k - schedule.rateFirst), schedule.rateCarry, schedule.rate, schedule.rateSpan,
                        schedule.maxAge);
}

// step.count births are owed; the dispatch covers at most the capacity of
// them (the rest cannot find a slot) and thread 0 counts the remainder.
void spawnEmit(KernelContext ctx, uint k) {
    uint dispatched = min(step.count, emitter.capacity);
    if (k == 0u && step.count > dispatched) {
        atomicAdd(counters.clamped, step.count - dispatched);
    }
    if (k >= dispatched) {
        return;
    }
    if (k >= dead.deadCount) {
        atomicAdd(counters.clamped, 1u);  // no free slot: dropped, never over a live one
        return;
    }
    ParticleUpdate r = bornParticle(ctx, emitter, dead.nextSerial + k, birthAge(k));
    float speed = length(r.particle.velocity);
    if ((r.events & SD_EVENT_NON_FINITE) != 0u) {
        // Removed at once (a number became NaN or infinite): its slot stays free.
        countEvents(r.particle, r, 0.0f);
        return;
    }
    if (r.particle.age >= r.particle.lifetime) {
        // Killed at once by a collision: born and dead, its slot stays free.
        r.events = r.events | SD_EVENT_DIED;
        countEvents(r.particle, r, speed);
        return;
    }
    uint slot = deadSlots[dead.deadCount - 1u - atomicAdd(dead.popped, 1u)];
    storeParticle(slot, r.particle, r.events);
    aliveOut[atomicAdd(aliveOutTable.count, 1u)] = slot;
    countEvents(r.particle, r, speed);
}

// Sub-emitted birth k: copy k % step.count of the parent's request k /
// step.count, into the slots the emit pass left free (the popped count is
// fixed by then; this pass counts its own). Births beyond the capacity or
// the free slots, and those of requests the parent could not keep, are
// dropped and counted, as the CPU's stepEmitter does.
uint saturatingProduct(uint a, uint b) {
    return a > 0u && b > 0xFFFFFFFFu / a ? 0xFFFFFFFFu : a * b;
}

void subEmit(KernelContext ctx, uint k) {
    uint requests = min(parentHeader.count, parentHeader.capacity);
    uint copies = step.count;
    uint owed = saturatingProduct(requests, copies);
    // With the requests the parent could not keep (beyond its capacity).
    uint owedAll = saturatingProduct(parentHeader.count, copies);
    uint dispatched = min(owed, emitter.capacity);
    if (k == 0u && owedAll > dispatched) {
        atomicAdd(counters.clamped, owedAll - dispatched);
    }
    if (k >= dispatched) {
        return;
    }
    uint free = dead.deadCount - dead.popped;
    if (k >= free) {
        atomicAdd(counters.clamped, 1u);
        return;
    }
    ParticleUpdate r = childParticle(ctx, emitter, parentRequests[k / copies], k % copies, step.inherit);
    atomicAdd(counters.subBorn, 1u);
    float speed = length(r.particle.velocity);
    if ((r.events & SD_EVENT_NON_FINITE) != 0u) {
        countEvents(r.particle, r, 0.0f);
        return;
    }
    if (r.particle.age >= r.particle.lifetime) {
        r.events = r.events | SD_EVENT_DIED;
        countEvents(r.particle, r, speed);
        return;
    }
    uint slot = deadSlots[dead.deadCount - 1u - dead.popped - atomicAdd(dead.subPopped, 1u)];
    storeParticle(slot, r.particle, r.events);
    aliveOut[atomicAdd(aliveOutTable.count, 1u)] = slot;
    countEvents(r.particle, r, speed);
}

// Births numbered this step: every one that found a free slot (as on the CPU,
// one killed at once by a collision still took a serial).
void spawnFinish() {
    dead.nextSerial += min(min(step.count, emitter.capacity), dead.deadCount);
    dead.deadCount -= dead.popped + dead.subPopped;
    dead.popped = 0u;
    dead.subPopped = 0u;
    dead.dispatchX = (aliveOutTable.count + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
    dead.dispatchY = 1u;
    dead.dispatchZ = 1u;
    aliveInTable.count = 0u;  // the next step's output list
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    KernelContext ctx;
    ctx.unused = 0u;
#if defined(SD_PASS_RECYCLE_UPDATE_MODULE)
    recycleUpdate(ctx, i);
#elif defined(SD_PASS_SPAWN_UPDATE_MODULE)
    spawnUpdate(ctx, i);
#elif defined(SD_PASS_SPAWN_EMIT_MODULE)
    spawnEmit(ctx, i);
#elif defined(SD_PASS_SUB_EMIT_MODULE)
    subEmit(ctx, i);
#elif defined(SD_PASS_SPAWN_FINISH_MODULE)
    if (i == 0u) {
        spawnFinish();
    }
#else
#error "effects_update.comp is compiled once per pass, with -DSD_PASS_<NAME>_MODULE (CMakeLists.txt)"
#endif
}
