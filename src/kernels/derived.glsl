// What a slot need not store, recomputed from what it does (the GPU backend's
// update, readParticles and the renderer's sprite vertex stage share it).
#ifndef SPINDRIFT_KERNELS_DERIVED
#define SPINDRIFT_KERNELS_DERIVED
#include "curves.glsl"
#include "spawn.glsl"
SD_BEGIN

// Colour and size over life: start values (re-derived from the key) times the
// curves at normalised age.
SD_FN Particle applyOverLife(SD_IN(EmitterParams) e, Particle p) {
    if (e.colorOverLife.count == 0u && e.sizeOverLife.count == 0u) {
        return p;
    }
    uint key = particleKey(e.keyBase, p.birth);
    float t = clamp(p.age / p.lifetime, 0.0f, 1.0f);
    p.color = startColor(e, key) * evaluateCurve(e.colorOverLife, t);
    p.size = startSize(e, key) * evaluateCurve(e.sizeOverLife, t).x;
    return p;
}

// What a slot need not store: lifetime, angular velocity, colour and size are
// pure functions of the emitter, the birth serial's key and the age (nothing
// changes them after birth but the curves, which read the age), so a backend
// that keeps only position, velocity, age, rotation and birth restores them
// here. The values equal those the update computed when it stored the age,
// bit for bit: the same expressions of the same inputs.
SD_FN Particle restoreDerived(SD_IN(EmitterParams) e, Particle p) {
    uint key = particleKey(e.keyBase, p.birth);
    p.lifetime = randomRange(key, SD_RAND_LIFETIME, e.lifetimeMin, e.lifetimeMax);
    p.angularVelocity = randomRange(key, SD_RAND_SPIN, e.angularVelocityMin, e.angularVelocityMax);
    p.color = startColor(e, key);
    p.size = startSize(e, key);
    return applyOverLife(e, p);
}

SD_END
#endif
