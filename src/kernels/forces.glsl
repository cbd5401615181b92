// Forces (GPU particle talk, "Update Velocities"): every force is evaluated at a
// position and velocity and accumulated into one vector; a = F / m.
//
// Requires the backend hooks declared in context_hooks.glsl.
#ifndef SPINDRIFT_KERNELS_FORCES
#define SPINDRIFT_KERNELS_FORCES
#include "math.glsl"
#include "types.glsl"
SD_BEGIN

// |F| = strength (radius / d)^falloff. For positive falloff d is softened at
// 1 % of the radius so the force stays finite at the centre; for falloff <= 0
// (constant or spring-like) no softening is needed and none is applied, so a
// spring (falloff -1) is exactly linear: F = strength d / radius.
SD_FN float falloffMagnitude(SD_IN(ForceParams) f, float d) {
    float softened = f.falloff > 0.0f ? max(d, 0.01f * f.radius) : d;
    float q = f.radius / softened;
    // The common exponents without pow(), which costs more than all the rest
    // of a force; the results are the same to rounding.
    if (f.falloff == 2.0f) {
        return f.strength * q * q;
    }
    if (f.falloff == 1.0f) {
        return f.strength * q;
    }
    if (f.falloff == 0.0f) {
        return f.strength;
    }
    if (f.falloff == -1.0f) {
        return f.strength * softened / f.radius;
    }
    return f.strength * sdPow(q, f.falloff);
}

SD_FN bool outOfRange(SD_IN(ForceParams) f, float d) {
    return f.position.w > 0.0f && d > f.position.w;
}

// Attraction toward f.position (repulsion for negative strength).
SD_FN vec3 attractorForce(SD_IN(ForceParams) f, vec3 p) {
    vec3 toCentre = vec3(f.position) - p;
    float d = length(toCentre);
    if (d <= 0.0f || outOfRange(f, d)) {
        return vec3(0.0f);
    }
    return toCentre * (falloffMagnitude(f, d) / d);
}

// Swirl around the line through f.position along f.axis.
SD_FN vec3 vortexForce(SD_IN(ForceParams) f, vec3 p) {
    vec3 axis = vec3(f.axis);
    vec3 offset = p - vec3(f.position);
    vec3 radial = offset - axis * dot(offset, axis);
    float d = length(radial);
    if (d <= 0.0f || outOfRange(f, d)) {
        return vec3(0.0f);
    }
    return cross(axis, radial) * (falloffMagnitude(f, d) / d);
}

// Linear drag toward a medium's velocity: F = k (u - v). Wind uses a user
// coefficient k (kg/s); a flow field uses Stokes' law for a sphere,
// k = 6 pi eta r (GPU particle talk, flow fields). It is not part of
// forcingAt's acceleration: the integrators solve it exactly over the step
// (integrate.glsl), so forcingAt first sums every drag term of a particle.
// Several drags F_i = k_i (u_i - v) are one drag k (u - v) with k = sum k_i and
// u = sum k_i u_i / sum k_i (the k-weighted medium velocity).
struct DragSum {
    vec3 momentum;      // sum k_i u_i (N)
    float coefficient;  // sum k_i (kg/s)
};

SD_FN DragSum noDrag() {
    DragSum d;
    d.momentum = vec3(0.0f);
    d.coefficient = 0.0f;
    return d;
}

SD_FN DragSum addDrag(DragSum d, float k, vec3 mediumVelocity) {
    d.momentum = d.momentum + mediumVelocity * k;
    d.coefficient = d.coefficient + k;
    return d;
}

// The summed drag of a particle of mass m as dv/dt = rate (medium - v).
struct LinearDrag {
    vec3 medium;  // m/s; 0 when there is no drag
    float rate;   // k / m (1/s)
};

SD_FN LinearDrag linearDrag(DragSum d, float mass) {
    LinearDrag l;
    l.medium = d.coefficient > 0.0f ? d.momentum / d.coefficient : vec3(0.0f);
    l.rate = d.coefficient / mass;
    return l;
}

SD_FN float stokesCoefficient(float viscosity, float radius) {
    return 6.0f * SD_PI * viscosity * radius;
}

// Exact speed relaxation for damping and un-damping: ds/dt = rate (target - s)
// has s(t + dt) = target + (s - target) exp(-rate dt), the same for any step
// length (frame-rate independent; "v *= 0.98" per frame is not). Damping is
// target 0. The direction of motion is kept.
// Split in two (the factor exp(-rate dt), then the relaxation by it) so the
// CPU's vector update can compute the factor once per step when the rate is
// the same for every particle: the same operations, so the same bits.
SD_FN float relaxationFactor(float rate, float dt) {
    return sdExp(-rate * dt);
}
// A select instead of an early return for a particle at rest, so the CPU's
// lane loops vectorise; the discarded side may divide by 0, which is harmless.
SD_FN vec3 relaxSpeedBy(vec3 v, float target, float factor) {
    float s = length(v);
    float relaxed = target + (s - target) * factor;
    vec3 scaled = v * (max(relaxed, 0.0f) / s);
    return select3(scaled, v, s <= 1e-20f);
}
SD_FN vec3 relaxSpeed(vec3 v, float target, float rate, float dt) {
    return relaxSpeedBy(v, target, relaxationFactor(rate, dt));
}

// Local damping: the rate falls linearly to 0 at `range` from the position.
SD_FN float relaxationRate(SD_IN(ForceParams) f, vec3 p) {
    if (f.position.w <= 0.0f) {
        return f.strength;
    }
    float d = length(p - vec3(f.position));
    return f.strength * max(0.0f, 1.0f - d / f.position.w);
}

SD_END
#endif
