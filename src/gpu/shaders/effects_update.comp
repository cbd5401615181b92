#version 450
// The passes of one emitter's step over structure-of-arrays storage buffers:
// the shared updateParticle and bornParticle of src/kernels/update.glsl. The
// physics lives only in src/kernels/*.glsl; this file only binds data to the
// hooks of context_hooks.glsl, keeps the spawn-mode slot lists and counts
// events. The pass is a specialization constant, one pipeline each:
//   0 recycle update: every slot (direct dispatch of the capacity);
//   1 spawn update: the current alive list (indirect dispatch); the dead go on
//     the dead stack, survivors on the next alive list;
//   2 spawn emit: birth k of the step's schedule pops a dead slot, or is clamped;
//   3 spawn finish: one thread writes the next step's indirect dispatch.
#include "types.glsl"

layout(constant_id = 0) const uint PASS = 0u;
const uint PASS_RECYCLE_UPDATE = 0u;
const uint PASS_SPAWN_UPDATE = 1u;
const uint PASS_SPAWN_EMIT = 2u;
const uint PASS_SPAWN_FINISH = 3u;

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Emitter { EmitterParams emitter; };
layout(std430, set = 0, binding = 1) readonly buffer Forces { uint forceTotal; uint pad0, pad1, pad2; ForceParams forces[]; };
layout(std430, set = 0, binding = 2) readonly buffer Colliders { uint colliderTotal; uint pad3, pad4, pad5; ColliderParams colliders[]; };
// vec3 arrays have a 16-byte stride in std430: positions and velocities are
// tightly packed floats instead, matching the CPU's glm::vec3 arrays. Only
// what changes after birth is stored (restoreDerived of update.glsl recomputes
// lifetime, angular velocity, colour and size): 20 B read and written per
// particle-step plus the 4 B birth serial read (written at birth only); see
// docs/performance.md.
layout(std430, set = 0, binding = 3) buffer Positions { float positions[]; };
layout(std430, set = 0, binding = 4) buffer Velocities { float velocities[]; };
layout(std430, set = 0, binding = 5) buffer Ages { float ages[]; };
layout(std430, set = 0, binding = 6) buffer Births { uint births[]; };
layout(std430, set = 0, binding = 7) buffer Rotations { float rotations[]; };
// Counts of the step, read by the CPU through a host-visible mapping once the
// step's fence has signalled (one copy per frame in flight).
layout(std430, set = 0, binding = 8) buffer Counters { uint born; uint died; uint clamped, pad7; uint hits[32]; };
// Collision and death events of the step, shared by every emitter of the world
// (one copy per frame in flight): at most eventCapacity are written; eventCount
// keeps counting beyond it, so the CPU knows how many were dropped.
layout(std430, set = 0, binding = 9) buffer Events {
    uint eventCount;
    uint eventCapacity;
    uint pad18, pad19;
    EventRecord events[];
};

// Spawn mode (set 1; recycle emitters bind a placeholder that is never read).
// The dead stack, its top at deadSlots[deadCount - 1], starts as the CPU's free
// list (slot 0 on top); the header's first three words are the indirect
// dispatch of the next update pass. popped: slots taken by the emit pass.
// nextSerial: serial of the emitter's next birth, kept here so that the CPU
// need not wait for a step's birth count before scheduling the next.
layout(std430, set = 1, binding = 0) buffer Dead {
    uint dispatchX, dispatchY, dispatchZ, deadCount;
    uint popped, nextSerial, pad9, pad10;
    uint deadSlots[];
};
// Slots alive at the start of the step, and those alive at its end; the CPU
// swaps the two between steps by binding the other descriptor set.
layout(std430, set = 1, binding = 1) buffer AliveIn { uint aliveInCount; uint pad11, pad12, pad13; uint aliveIn[]; };
layout(std430, set = 1, binding = 2) buffer AliveOut { uint aliveOutCount; uint pad14, pad15, pad16; uint aliveOut[]; };
// The step's births (BirthSchedule of src/effects/world_internal.h, written by
// the CPU): burst runs (end index, age) first, then the rate's births.
layout(std430, set = 1, binding = 3) readonly buffer Schedule {
    uint burstRuns;
    uint rateFirst;    // index of the rate's first birth
    uint pad17, pad20;
    float rateSpan;    // t1 - t0 (s)
    float rateCarry;
    float rate;        // 1/s
    float maxAge;      // dt (s)
    uvec2 runs[];      // x: end index (exclusive), y: floatBitsToUint(age)
};

// count: slots (recycle update), births owed (spawn emit and finish).
layout(push_constant) uniform Step { float dt; uint count; uint emitterIndex; uint pad; } step;

// Sampled fields of the world (set 2), bound by gpu_world.cpp: one linear,
// clamp-to-edge sampler, normalised coordinates, level 0, so texel i of n has
// its centre at (i + 0.5) / n as context_hooks.glsl requires. Array sizes are
// kMaxGpuFlowFields, kMaxGpuHeightMaps and kMaxGpuCubeMaps of gpu_world.h;
// unused elements show a placeholder.
layout(set = 2, binding = 0) uniform sampler3D flowFields[8];   // xyz velocity (m/s)
layout(set = 2, binding = 1) uniform sampler2D heightMaps[8];   // height (m)
layout(set = 2, binding = 2) uniform samplerCube cubeMaps[8];   // outward normal xyz, depth w (m)

// Field counts and the integrator are specialization constants of the
// pipeline (gpu_world.cpp keeps one pipeline per combination a world uses), for
// two reasons. lavapipe (Mesa 22.3) lacks shaderSampledImageArrayDynamicIndexing,
// so a sampler array may only be indexed by constants: the hooks below switch
// over literal indices. And llvmpipe compiles every inlined sample site of the
// kernels at pipeline creation (RK4's four accelerationAt, the sampled-collider
// march, bisection and normals): with all 8 elements of all 3 arrays live that
// took minutes per pipeline. The constants let the driver drop the elements a
// world does not use and the integrators an emitter does not run.
layout(constant_id = 1) const uint FLOW_FIELDS = 0u;   // flow fields of the world, 0..8
layout(constant_id = 2) const uint HEIGHT_MAPS = 0u;   // terrain height maps, 0..8
layout(constant_id = 3) const uint CUBE_MAPS = 0u;     // depth cube maps, 0..8
layout(constant_id = 4) const uint INTEGRATOR = 0xFFFFFFFFu;  // SD_INTEGRATE_*; all ones: the emitter's

struct KernelContext { uint unused; };
uint forceCount(KernelContext ctx) { return forceTotal; }
ForceParams forceAt(KernelContext ctx, uint i) { return forces[i]; }
uint colliderCount(KernelContext ctx) { return colliderTotal; }
ColliderParams colliderAt(KernelContext ctx, uint i) { return colliders[i]; }
uint integratorOf(EmitterParams e) { return INTEGRATOR == 0xFFFFFFFFu ? e.integrator : INTEGRATOR; }

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

#include "update.glsl"

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
}

// Atomics only where something happened: most slots in most steps have no
// event. speed: m/s at the start of the step (EventRecord).
void countEvents(Particle before, ParticleUpdate r, float speed) {
    if ((r.events & SD_EVENT_BORN) != 0u) {
        atomicAdd(born, 1u);
    }
    if ((r.events & SD_EVENT_DIED) != 0u) {
        atomicAdd(died, 1u);
    }
    for (uint mask = r.hitMask; mask != 0u; mask &= mask - 1u) {
        atomicAdd(hits[findLSB(mask)], 1u);
    }
    uint n = eventCapacity > 0u ? eventCountOf(r) : 0u;
    if (n > 0u) {
        uint first = atomicAdd(eventCount, n);
        for (uint k = 0u; k < n && first + k < eventCapacity; ++k) {
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
    if (i >= aliveInCount) {
        return;
    }
    uint slot = aliveIn[i];
    Particle p = loadParticle(slot);
    ParticleUpdate r = updateParticle(ctx, emitter, p, step.dt);
    storeParticle(slot, r.particle, r.events);
    countEvents(p, r, length(p.velocity));
    if ((r.events & SD_EVENT_DIED) != 0u) {
        deadSlots[atomicAdd(deadCount, 1u)] = slot;
    } else {
        aliveOut[atomicAdd(aliveOutCount, 1u)] = slot;
    }
}

// Age of birth k at the end of the step: BirthSchedule::ages() in float (the
// CPU works in double; the two agree to a few ulp).
float birthAge(uint k) {
    for (uint b = 0u; b < burstRuns; ++b) {
        if (k < runs[b].x) {
            return uintBitsToFloat(runs[b].y);
        }
    }
    float bornAfterStart = (float(k - rateFirst) + 1.0f - rateCarry) / rate;
    return clamp(rateSpan - bornAfterStart, 0.0f, maxAge);
}

// step.count births are owed; the dispatch covers at most the capacity of
// them (the rest cannot find a slot) and thread 0 counts the remainder.
void spawnEmit(KernelContext ctx, uint k) {
    uint dispatched = min(step.count, emitter.capacity);
    if (k == 0u && step.count > dispatched) {
        atomicAdd(clamped, step.count - dispatched);
    }
    if (k >= dispatched) {
        return;
    }
    if (k >= deadCount) {
        atomicAdd(clamped, 1u);  // no free slot: dropped, never over a live one
        return;
    }
    ParticleUpdate r = bornParticle(ctx, emitter, nextSerial + k, birthAge(k));
    float speed = length(r.particle.velocity);
    if (r.particle.age >= r.particle.lifetime) {
        // Killed at once by a collision: born and dead, its slot stays free.
        r.events = r.events | SD_EVENT_DIED;
        countEvents(r.particle, r, speed);
        return;
    }
    uint slot = deadSlots[deadCount - 1u - atomicAdd(popped, 1u)];
    storeParticle(slot, r.particle, r.events);
    aliveOut[atomicAdd(aliveOutCount, 1u)] = slot;
    countEvents(r.particle, r, speed);
}

// Births numbered this step: every one that found a free slot (as on the CPU,
// one killed at once by a collision still took a serial).
void spawnFinish() {
    nextSerial += min(min(step.count, emitter.capacity), deadCount);
    deadCount -= popped;
    popped = 0u;
    dispatchX = (aliveOutCount + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
    dispatchY = 1u;
    dispatchZ = 1u;
    aliveInCount = 0u;  // the next step's output list
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    KernelContext ctx;
    ctx.unused = 0u;
    if (PASS == PASS_RECYCLE_UPDATE) {
        recycleUpdate(ctx, i);
    } else if (PASS == PASS_SPAWN_UPDATE) {
        spawnUpdate(ctx, i);
    } else if (PASS == PASS_SPAWN_EMIT) {
        spawnEmit(ctx, i);
    } else if (i == 0u) {
        spawnFinish();
    }
}
