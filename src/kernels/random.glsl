// Counter-based random numbers: a value is a pure function of a key, so the same
// particle gets the same numbers on every backend, thread count and run.
// PCG hash from Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 9(3), 2020.
#ifndef SPINDRIFT_KERNELS_RANDOM
#define SPINDRIFT_KERNELS_RANDOM
#include "prelude.glsl"
SD_BEGIN

SD_FN uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Per-emitter part of the particle keys, computed once per emitter.
SD_FN uint emitterKeyBase(uint seed, uint emitter) {
    return pcgHash(seed ^ pcgHash(emitter * 0x9E3779B9u + 0x7F4A7C15u));
}

// Key of one particle: (scene seed, emitter index, birth serial). One hash per
// particle: the emitter's part is folded into keyBase beforehand.
SD_FN uint particleKey(uint keyBase, uint serial) {
    return pcgHash(serial ^ keyBase);
}

// The n-th uniform number in [0, 1) of a key: 24 random bits, so the float is
// exact and identical in GLSL and C++.
SD_FN float randomUnit(uint key, uint n) {
    uint h = pcgHash(key ^ pcgHash(n + 0x632BE5ABu));
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

SD_FN float randomRange(uint key, uint n, float lo, float hi) {
    return mix(lo, hi, randomUnit(key, n));
}

SD_END
#endif
