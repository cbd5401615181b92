// Integrators (GPU particle talk: Euler, with Verlet and RK4 as alternatives).
// Requires the hooks of context_hooks.glsl.
#ifndef SPINDRIFT_KERNELS_INTEGRATE
#define SPINDRIFT_KERNELS_INTEGRATE
#include "forces.glsl"
SD_BEGIN

// a = F / m with every force acting on the emitter at (p, v). Damping and
// un-damping are not here: they are exact speed relaxations (applySpeedRelaxation).
SD_FN vec3 accelerationAt(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, vec3 p, vec3 v, float mass, float radius) {
    vec3 force = vec3(0.0f);
    vec3 gravity = vec3(0.0f);
    uint n = forceCount(ctx);
    for (uint i = 0u; i < n; ++i) {
        if ((e.forceMask & (1u << i)) == 0u) {
            continue;
        }
        SD_LET(ForceParams) f = forceAt(ctx, i);
        if (f.kind == SD_FORCE_GRAVITY) {
            gravity += vec3(f.vector);
        } else if (f.kind == SD_FORCE_WIND) {
            force += dragForce(f.strength, vec3(f.vector), v);
        } else if (f.kind == SD_FORCE_ATTRACTOR) {
            force += attractorForce(f, p);
        } else if (f.kind == SD_FORCE_VORTEX) {
            force += vortexForce(f, p);
        } else if (f.kind == SD_FORCE_FLOW_FIELD) {
            vec3 uvw = p * vec3(f.flowScale) + vec3(f.flowOffset);
            vec3 flow = sampleFlowField(ctx, f.flowField, uvw);
            force += dragForce(stokesCoefficient(f.flowOffset.w, radius), flow, v);
        }
    }
    return gravity + force / mass;
}

SD_FN vec3 applySpeedRelaxation(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, vec3 p, vec3 v, float dt) {
    uint n = forceCount(ctx);
    for (uint i = 0u; i < n; ++i) {
        if ((e.forceMask & (1u << i)) == 0u) {
            continue;
        }
        SD_LET(ForceParams) f = forceAt(ctx, i);
        if (f.kind == SD_FORCE_DAMPING) {
            v = relaxSpeed(v, 0.0f, relaxationRate(f, p), dt);
        } else if (f.kind == SD_FORCE_UNDAMPING) {
            v = relaxSpeed(v, f.axis.w, relaxationRate(f, p), dt);
        }
    }
    return v;
}

// Position and velocity after one step.
struct Motion {
    vec3 position;
    vec3 velocity;
};

// The Euler steps (explicit, and semi-implicit for any other integrator id)
// from the acceleration at the start, a0; shared with the CPU's vector update.
SD_FN Motion eulerMotion(uint integrator, vec3 p, vec3 v, vec3 a0, float dt) {
    Motion m;
    if (integrator == SD_INTEGRATE_EXPLICIT_EULER) {
        m.position = p + v * dt;
        m.velocity = v + a0 * dt;
    } else {
        m.velocity = v + a0 * dt;
        m.position = p + m.velocity * dt;
    }
    return m;
}

SD_FN Motion integrateMotion(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, vec3 p, vec3 v, float mass, float radius,
                             float dt) {
    Motion m;
    uint integrator = integratorOf(e);
    vec3 a0 = accelerationAt(ctx, e, p, v, mass, radius);
    if (integrator == SD_INTEGRATE_VERLET) {
        // Velocity Verlet; the new acceleration sees the Euler-predicted velocity
        // (exact for position-only forces, second order with drag).
        m.position = p + v * dt + a0 * (0.5f * dt * dt);
        vec3 a1 = accelerationAt(ctx, e, m.position, v + a0 * dt, mass, radius);
        m.velocity = v + (a0 + a1) * (0.5f * dt);
    } else if (integrator == SD_INTEGRATE_RK4) {
        // Classic RK4 on (p, v) with the forces re-evaluated at every stage
        // (Fiedler, "Integration Basics", cited by the GPU particle talk).
        float h = 0.5f * dt;
        vec3 p2 = p + v * h;
        vec3 v2 = v + a0 * h;
        vec3 a2 = accelerationAt(ctx, e, p2, v2, mass, radius);
        vec3 p3 = p + v2 * h;
        vec3 v3 = v + a2 * h;
        vec3 a3 = accelerationAt(ctx, e, p3, v3, mass, radius);
        vec3 p4 = p + v3 * dt;
        vec3 v4 = v + a3 * dt;
        vec3 a4 = accelerationAt(ctx, e, p4, v4, mass, radius);
        m.position = p + (v + (v2 + v3) * 2.0f + v4) * (dt / 6.0f);
        m.velocity = v + (a0 + (a2 + a3) * 2.0f + a4) * (dt / 6.0f);
    } else {
        m = eulerMotion(integrator, p, v, a0, dt);
    }
    return m;
}

SD_END
#endif
