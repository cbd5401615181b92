#version 450
// Build-time proof that the shared kernels are valid GLSL: the effect update as
// a compute shader over structure-of-arrays buffers. The Vulkan backend grows
// from this file; the physics lives only in ../*.glsl.
#include "types.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Emitter { EmitterParams emitter; };
layout(std430, set = 0, binding = 1) readonly buffer Forces { uint forceTotal; uint pad0, pad1, pad2; ForceParams forces[]; };
layout(std430, set = 0, binding = 2) readonly buffer Colliders { uint colliderTotal; uint pad3, pad4, pad5; ColliderParams colliders[]; };
layout(std430, set = 0, binding = 3) buffer Positions { float positions[]; };
layout(std430, set = 0, binding = 4) buffer Velocities { float velocities[]; };
layout(std430, set = 0, binding = 5) buffer Ages { float ages[]; };
layout(std430, set = 0, binding = 6) buffer Lifetimes { float lifetimes[]; };
layout(std430, set = 0, binding = 7) buffer Births { uint births[]; };
layout(std430, set = 0, binding = 8) buffer Sizes { float sizes[]; };
layout(std430, set = 0, binding = 9) buffer Rotations { vec2 rotations[]; };
layout(std430, set = 0, binding = 10) buffer Colors { vec4 colors[]; };
layout(set = 0, binding = 11) uniform sampler3D flowFields[4];
layout(set = 0, binding = 12) uniform sampler2D heightMaps[4];
layout(set = 0, binding = 13) uniform samplerCube cubeMaps[4];

layout(push_constant) uniform Step { float dt; uint count; } step;

struct KernelContext { uint unused; };
uint forceCount(KernelContext ctx) { return forceTotal; }
ForceParams forceAt(KernelContext ctx, uint i) { return forces[i]; }
uint colliderCount(KernelContext ctx) { return colliderTotal; }
ColliderParams colliderAt(KernelContext ctx, uint i) { return colliders[i]; }
vec3 sampleFlowField(KernelContext ctx, uint field, vec3 uvw) { return texture(flowFields[field], uvw).xyz; }
float sampleTerrainHeight(KernelContext ctx, uint map, vec2 uv) { return texture(heightMaps[map], uv).x; }
vec4 sampleCubeMap(KernelContext ctx, uint map, vec3 direction) { return texture(cubeMaps[map], direction); }

#include "update.glsl"
#include "stateless.glsl"


void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= step.count) {
        return;
    }
    KernelContext ctx;
    ctx.unused = 0u;
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
    ParticleUpdate r = updateParticle(ctx, emitter, p, step.dt);
    Particle q = r.particle;
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
    if (i == 0u) {
        Particle s = evaluateStatelessParticle(emitter, 0u, step.dt);
        colors[0] = s.color;
    }
}
