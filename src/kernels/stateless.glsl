// Stateless particles (GPU particle talk, "Stateless / State-preserving PS"): a
// closed-form function of time, p = p0 + v0 t + g t^2 / 2, evaluated wherever
// it is needed; nothing is stored. No hooks needed.
#ifndef SPINDRIFT_KERNELS_STATELESS
#define SPINDRIFT_KERNELS_STATELESS
#include "derived.glsl"
SD_BEGIN

// Serials of burst particles live above the rate's: burst b, particle j has
// serial SD_BURST_SERIAL_BASE + b * SD_BURST_SERIAL_STRIDE + j.
SD_CONST uint SD_BURST_SERIAL_BASE = 0x80000000u;
SD_CONST uint SD_BURST_SERIAL_STRIDE = 1048576u;

// The particle with serial `serial`, `age` seconds after its birth.
SD_FN Particle evaluateStatelessParticle(SD_IN(EmitterParams) e, uint serial, float age) {
    Particle p = spawnParticle(e, serial);
    vec3 g = vec3(e.statelessGravity);
    p.position = p.position + p.velocity * age + g * (0.5f * age * age);
    p.velocity = p.velocity + g * age;
    p.rotation = p.rotation + p.angularVelocity * age;
    p.age = age;
    p = restoreLook(e, p);
    p.alive = age < p.lifetime ? 1u : 0u;
    return p;
}

SD_END
#endif
