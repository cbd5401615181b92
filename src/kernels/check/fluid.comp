#version 450
// Build-time proof that fluid.glsl is valid GLSL: one solver visit per
// invocation over precomputed neighbour rates, and the contact of each particle
// with one collider and one polygon, as the GPU fluid will do them.
#include "fluid.glsl"

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) readonly buffer Colliders { ColliderParams collider; FluidPolygon polygon; FluidBodyShape bodyShape; };
layout(std430, set = 0, binding = 1) buffer Velocities { vec4 velocities[]; };
layout(std430, set = 0, binding = 2) buffer Constraints { vec4 constraints[]; };  // density, rate, 1/A, accumulated

layout(push_constant) uniform Step { float restDensity; float baumgarte; float h; float invDt; float radius; uint count; } step;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= step.count) {
        return;
    }
    vec4 c = constraints[i];
    float w = fluidWeight(c.x * c.x, 1.0f / (step.h * step.h));
    float bias = fluidBias(c.x + w, step.restDensity, step.baumgarte, step.h, step.invDt);
    FluidImpulse r = fluidSolveImpulse(c.y, bias, c.z, c.w);
    constraints[i] = vec4(c.x, c.y, c.z, r.accumulated);
    vec3 v = vec3(velocities[i]);
    vec3 p = vec3(velocities[i].w, 0.0f, 0.0f);
    v = fluidContactVelocity(v, fluidColliderSurface(collider, p), step.radius, step.invDt, 0.2f, 0.0f);
    v = fluidContactVelocity(v, fluidPolygonSurface(polygon, p), step.radius, step.invDt, 0.2f, 0.1f);
    FluidSurface b = fluidBodyShapeSurface(bodyShape, p);
    vec2 n = vec2(b.normal.x, b.normal.y);
    vec2 rb = vec2(p.x, p.y) - n * b.distance - vec2(bodyShape.geometry.x, bodyShape.geometry.y);
    float mass = fluidBodyNormalMass(1.0f, 0.5f, 0.25f, rb, n);
    vec2 vb = fluidBodyPointVelocity(vec2(0.1f, 0.0f), 0.5f, rb);
    FluidImpulse bn = fluidBodyNormalImpulse(dot(vec2(v.x, v.y) - vb, n), -b.distance * step.invDt, mass, 0.0f);
    FluidImpulse bt = fluidBodyFrictionImpulse(0.1f, mass, 0.0f, 0.2f * bn.accumulated);
    v += vec3(n * bn.delta + vec2(-n.y, n.x) * bt.delta, 0.0f);
    velocities[i] = vec4(v, r.delta);
}
