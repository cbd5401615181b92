// What a slot need not store, recomputed from what it does (the GPU backend's
// update, readParticles and the renderer's sprite vertex stage share it).
#ifndef SPINDRIFT_KERNELS_DERIVED
#define SPINDRIFT_KERNELS_DERIVED
#include "curves.glsl"
#include "spawn.glsl"
SD_BEGIN

// The over-speed curves' t for velocity v: the speed mapped from
// [overSpeedMin, overSpeedMax] (m/s) onto [0, 1], clamped; with min = max a
// step from 0 to 1 at that speed.
SD_FN float overSpeedT(SD_IN(EmitterParams) e, vec3 v) {
    float s = length(v);
    float range = e.overSpeedMax - e.overSpeedMin;
    if (range > 0.0f) {
        return clamp((s - e.overSpeedMin) / range, 0.0f, 1.0f);
    }
    return s >= e.overSpeedMax ? 1.0f : 0.0f;
}

// A particle's size and colour at normalised age t and velocity v: the start
// values (re-derived from the key) times the curves at t, then times the
// curves at its speed (a missing curve is a factor of 1, which changes no bit).
SD_FN float lifeT(Particle p) {
    return clamp(p.age / p.lifetime, 0.0f, 1.0f);
}
SD_FN float sizeOf(SD_IN(EmitterParams) e, uint key, float t, vec3 v) {
    float size = startSize(e, key) * evaluateCurve(e.sizeOverLife, t).x;
    if (e.sizeOverSpeed.count != 0u) {
        size = size * evaluateCurve(e.sizeOverSpeed, overSpeedT(e, v)).x;
    }
    return size;
}
SD_FN vec4 colorOf(SD_IN(EmitterParams) e, uint key, float t, vec3 v) {
    vec4 color = startColor(e, key) * evaluateCurve(e.colorOverLife, t);
    if (e.colorOverSpeed.count != 0u) {
        color = color * evaluateCurve(e.colorOverSpeed, overSpeedT(e, v));
    }
    return color;
}

// A particle's look, colour and size, from its key, age, lifetime and
// velocity: what the update's applyOverLife gives it, bit for bit (the same
// expressions of the same inputs). Neither backend stores the look; the
// readers and the renderer restore it here.
SD_FN Particle restoreLook(SD_IN(EmitterParams) e, Particle p) {
    uint key = particleKey(e.keyBase, p.birth);
    float t = lifeT(p);
    p.color = colorOf(e, key, t, p.velocity);
    p.size = sizeOf(e, key, t, p.velocity);
    return p;
}

// Colour and size over life and by speed, for the particle the update ends
// with (no curves: p's own, the start values, unchanged).
SD_FN Particle applyOverLife(SD_IN(EmitterParams) e, Particle p) {
    if (e.colorOverLife.count == 0u && e.sizeOverLife.count == 0u && e.colorOverSpeed.count == 0u &&
        e.sizeOverSpeed.count == 0u) {
        return p;
    }
    return restoreLook(e, p);
}

// The look as the update reads it, for a backend that restores it before
// each update (the CPU's scalar path): the size (its half is the radius a
// flow field's drag takes) and the start colour, which applyOverLife keeps
// where no curve changes it and recomputes from the key where one does, so
// the colour curves need not be evaluated twice.
SD_FN Particle restoreUpdateLook(SD_IN(EmitterParams) e, Particle p) {
    uint key = particleKey(e.keyBase, p.birth);
    p.color = startColor(e, key);
    p.size = sizeOf(e, key, lifeT(p), p.velocity);
    return p;
}

// Lifetime and angular velocity: drawn from the key at birth (spawnParticle)
// and never changed after it.
SD_FN Particle restoreBirthDraws(SD_IN(EmitterParams) e, Particle p) {
    uint key = particleKey(e.keyBase, p.birth);
    p.lifetime = randomRange(key, SD_RAND_LIFETIME, e.lifetimeMin, e.lifetimeMax);
    p.angularVelocity = randomRange(key, SD_RAND_SPIN, e.angularVelocityMin, e.angularVelocityMax);
    return p;
}

// What a slot need not store: lifetime, angular velocity, colour and size are
// pure functions of the emitter, the birth serial's key, the age and the
// velocity (nothing changes them after birth but the curves, which read the
// age and the speed), so a backend that keeps only position, velocity, age,
// rotation and birth restores them here. The values equal those the update
// computed when it stored the age, bit for bit: the same expressions of the
// same inputs.
SD_FN Particle restoreDerived(SD_IN(EmitterParams) e, Particle p) {
    return restoreLook(e, restoreBirthDraws(e, p));
}

SD_END
#endif
