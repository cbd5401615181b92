// The CPU backend's side of the shared kernels: the KernelContext hooks of
// src/kernels/context_hooks.glsl over plain arrays, then the kernels themselves,
// compiled as C++.
#pragma once

#include "particles/fields.h"
#include "kernels/noise.glsl"
#include "kernels/types.glsl"

namespace spindrift::kernels {

struct KernelContext {
    const ForceParams* forces;
    uint forceTotal;
    const ColliderParams* colliders;
    uint colliderTotal;
    const FieldSet* fields;
    float time;  // s, the world time at the start of the step
};

inline uint forceCount(const KernelContext& ctx) { return ctx.forceTotal; }
inline const ForceParams& forceAt(const KernelContext& ctx, uint i) { return ctx.forces[i]; }
inline uint colliderCount(const KernelContext& ctx) { return ctx.colliderTotal; }
inline const ColliderParams& colliderAt(const KernelContext& ctx, uint i) { return ctx.colliders[i]; }
inline uint integratorOf(const EmitterParams& e) { return e.integrator; }
inline vec3 sampleFlowField(const KernelContext& ctx, uint field, vec3 uvw) {
    return sampleFlow(ctx.fields->flows[field], uvw);
}
inline float sampleTerrainHeight(const KernelContext& ctx, uint map, vec2 uv) {
    return sampleHeight(ctx.fields->heights[map], uv);
}
inline vec4 sampleCubeMap(const KernelContext& ctx, uint map, vec3 direction) {
    return sampleCube(ctx.fields->cubes[map], direction);
}
inline vec3 sampleCurlNoise(const KernelContext& ctx, const ForceParams& f, vec3 p) {
    return curlNoiseVelocity(f, p, ctx.time);
}

}  // namespace spindrift::kernels

#include "kernels/stateless.glsl"
#include "kernels/update.glsl"
