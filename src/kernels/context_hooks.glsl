// The few things a backend provides to the shared kernels: where the emitter's
// forces and colliders live and how fields are sampled. The CPU backend defines
// them in C++ over its arrays (src/particles/cpu_kernels.h); a compute shader
// defines them over buffers and samplers. Each backend defines
//
//   struct KernelContext { ... };
//   uint forceCount(KernelContext ctx);
//   ForceParams forceAt(KernelContext ctx, uint i);
//   uint colliderCount(KernelContext ctx);
//   ColliderParams colliderAt(KernelContext ctx, uint i);
//   uint integratorOf(EmitterParams e);                              // SD_INTEGRATE_*
//   vec3 sampleFlowField(KernelContext ctx, uint field, vec3 uvw);   // m/s
//   float sampleTerrainHeight(KernelContext ctx, uint map, vec2 uv); // m
//   vec4 sampleCubeMap(KernelContext ctx, uint map, vec3 direction); // normal, depth (m)
//   vec3 sampleCurlNoise(KernelContext ctx, ForceParams f, vec3 p);  // m/s, curlNoiseVelocity
//                                                                     // (noise.glsl) at the step's start time
//
// (integratorOf lets a compute pipeline fix the integrator as a specialization
// constant, so the driver compiles only the one it runs) before including integrate.glsl, collide.glsl or update.glsl. Normalised
// coordinates follow Vulkan's sampler convention: texel i of n covers
// [i / n, (i + 1) / n] and its centre is at (i + 0.5) / n; outside [0, 1] the
// edge texel is used (clamp to edge).
