#include "particles/slots.h"

#include "kernels/derived.glsl"

namespace spindrift {

kernels::Particle storedParticle(const ParticleArrays& a, const kernels::EmitterParams& e, std::size_t i) {
    kernels::Particle p{};
    p.position = a.position[i];
    p.velocity = a.velocity[i];
    p.age = a.age[i];
    p.lifetime = a.lifetime[i];
    p.rotation = a.rotation[i];
    p.angularVelocity = a.angularVelocity[i];
    p.mass = e.mass;
    p.birth = a.birth[i];
    p.alive = p.age >= 0.0f ? 1u : 0u;
    return p;
}

kernels::Particle loadParticle(const ParticleArrays& a, const kernels::EmitterParams& e, std::size_t i) {
    return kernels::restoreLook(e, storedParticle(a, e, i));
}

kernels::Particle loadForUpdate(const ParticleArrays& a, const kernels::EmitterParams& e, std::size_t i) {
    return kernels::restoreUpdateLook(e, storedParticle(a, e, i));
}

void storeParticle(ParticleArrays& a, std::size_t i, const kernels::Particle& p) {
    a.position[i] = p.position;
    a.velocity[i] = p.velocity;
    a.age[i] = p.age;
    a.lifetime[i] = p.lifetime;
    a.rotation[i] = p.rotation;
    a.angularVelocity[i] = p.angularVelocity;
    a.birth[i] = p.birth;
}

}  // namespace spindrift
