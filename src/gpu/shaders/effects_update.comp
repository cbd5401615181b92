#version 450
// One step of every slot of one emitter: the shared updateParticle of
// src/kernels/update.glsl over structure-of-arrays storage buffers. The physics
// lives only in src/kernels/*.glsl; this file only binds data to the hooks of
// context_hooks.glsl and counts events.
#include "types.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Emitter { EmitterParams emitter; };
layout(std430, set = 0, binding = 1) readonly buffer Forces { uint forceTotal; uint pad0, pad1, pad2; ForceParams forces[]; };
layout(std430, set = 0, binding = 2) readonly buffer Colliders { uint colliderTotal; uint pad3, pad4, pad5; ColliderParams colliders[]; };
// vec3 arrays have a 16-byte stride in std430: positions and velocities are
// tightly packed floats instead, matching the CPU's glm::vec3 arrays.
layout(std430, set = 0, binding = 3) buffer Positions { float positions[]; };
layout(std430, set = 0, binding = 4) buffer Velocities { float velocities[]; };
layout(std430, set = 0, binding = 5) buffer Ages { float ages[]; };
layout(std430, set = 0, binding = 6) buffer Lifetimes { float lifetimes[]; };
layout(std430, set = 0, binding = 7) buffer Births { uint births[]; };
layout(std430, set = 0, binding = 8) buffer Sizes { float sizes[]; };
layout(std430, set = 0, binding = 9) buffer Rotations { vec2 rotations[]; };  // rotation, angular velocity
layout(std430, set = 0, binding = 10) buffer Colors { vec4 colors[]; };
// Events of the step, read by the CPU through a host-visible mapping.
layout(std430, set = 0, binding = 11) buffer Counters { uint born; uint died; uint pad6, pad7; uint hits[32]; };

layout(push_constant) uniform Step { float dt; uint count; } step;

// Flow fields, height maps and cube maps are refused when they are created in
// a Vulkan world (not supported yet), so no emitter here can reach the samplers.
struct KernelContext { uint unused; };
uint forceCount(KernelContext ctx) { return forceTotal; }
ForceParams forceAt(KernelContext ctx, uint i) { return forces[i]; }
uint colliderCount(KernelContext ctx) { return colliderTotal; }
ColliderParams colliderAt(KernelContext ctx, uint i) { return colliders[i]; }
vec3 sampleFlowField(KernelContext ctx, uint field, vec3 uvw) { return vec3(0.0f); }
float sampleTerrainHeight(KernelContext ctx, uint map, vec2 uv) { return 0.0f; }
vec4 sampleCubeMap(KernelContext ctx, uint map, vec3 direction) { return vec4(0.0f, 1.0f, 0.0f, 0.0f); }

#include "update.glsl"

Particle loadParticle(uint i) {
    Particle p;
    p.position = vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]);
    p.velocity = vec3(velocities[3u * i], velocities[3u * i + 1u], velocities[3u * i + 2u]);
    p.color = colors[i];
    p.age = ages[i];
    p.lifetime = lifetimes[i];
    p.size = sizes[i];
    p.rotation = rotations[i].x;
    p.angularVelocity = rotations[i].y;
    p.mass = emitter.mass;
    p.birth = births[i];
    p.alive = p.age >= 0.0f ? 1u : 0u;
    return p;
}

void storeParticle(uint i, Particle q) {
    positions[3u * i] = q.position.x;
    positions[3u * i + 1u] = q.position.y;
    positions[3u * i + 2u] = q.position.z;
    velocities[3u * i] = q.velocity.x;
    velocities[3u * i + 1u] = q.velocity.y;
    velocities[3u * i + 2u] = q.velocity.z;
    ages[i] = q.age;
    lifetimes[i] = q.lifetime;
    births[i] = q.birth;
    sizes[i] = q.size;
    rotations[i] = vec2(q.rotation, q.angularVelocity);
    colors[i] = q.color;
}

// Atomics only where something happened: most slots in most steps have no event.
void countEvents(ParticleUpdate r) {
    if ((r.events & SD_EVENT_BORN) != 0u) {
        atomicAdd(born, 1u);
    }
    if ((r.events & SD_EVENT_DIED) != 0u) {
        atomicAdd(died, 1u);
    }
    for (uint mask = r.hitMask; mask != 0u; mask &= mask - 1u) {
        atomicAdd(hits[findLSB(mask)], 1u);
    }
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= step.count) {
        return;
    }
    KernelContext ctx;
    ctx.unused = 0u;
    ParticleUpdate r = updateParticle(ctx, emitter, loadParticle(i), step.dt);
    storeParticle(i, r.particle);
    countEvents(r);
}
