#version 450
// Build-time proof that stateless.glsl is valid GLSL (the effect update is
// compiled as src/gpu/shaders/effects_update.comp): evaluates the closed form
// of a stateless emitter for one serial per invocation, as the renderer's
// vertex stage will.
#include "stateless.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Emitter { EmitterParams emitter; };
layout(std430, set = 0, binding = 1) writeonly buffer Positions { vec4 positions[]; };

layout(push_constant) uniform Evaluate { float age; uint count; } evaluate;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= evaluate.count) {
        return;
    }
    Particle p = evaluateStatelessParticle(emitter, i, evaluate.age);
    positions[i] = vec4(p.position, p.alive != 0u ? p.size : 0.0f);
}
