// Integrators (GPU particle talk: Euler, with Verlet and RK4 as alternatives).
// Requires the hooks of context_hooks.glsl.
#ifndef SPINDRIFT_KERNELS_INTEGRATE
#define SPINDRIFT_KERNELS_INTEGRATE
#include "forces.glsl"
SD_BEGIN

// Everything that accelerates a particle at position p except damping and
// un-damping (exact speed relaxations, applySpeedRelaxation): `acceleration`
// holds gravity and the position-only forces (F / m), and the linear drags of
// winds and flow fields are kept apart as one LinearDrag. No force depends on
// the velocity but the drag, which the integrators solve exactly.
struct Forcing {
    vec3 acceleration;  // m/s^2
    vec3 medium;        // m/s, the drag's k-weighted medium velocity
    float rate;         // 1/s, the drag's k / m
};

SD_FN Forcing forcingAt(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, vec3 p, float mass, float radius) {
    vec3 force = vec3(0.0f);
    vec3 gravity = vec3(0.0f);
    DragSum drag = noDrag();
    uint n = forceCount(ctx);
    for (uint i = 0u; i < n; ++i) {
        if ((e.forceMask & (1u << i)) == 0u) {
            continue;
        }
        SD_LET(ForceParams) f = forceAt(ctx, i);
        if (f.kind == SD_FORCE_GRAVITY) {
            gravity += vec3(f.vector);
        } else if (f.kind == SD_FORCE_WIND) {
            drag = addDrag(drag, f.strength, vec3(f.vector));
        } else if (f.kind == SD_FORCE_ATTRACTOR) {
            force += attractorForce(f, p);
        } else if (f.kind == SD_FORCE_VORTEX) {
            force += vortexForce(f, p);
        } else if (f.kind == SD_FORCE_FLOW_FIELD) {
            vec3 uvw = p * vec3(f.flowScale) + vec3(f.flowOffset);
            vec3 flow = sampleFlowField(ctx, f.flowField, uvw);
            drag = addDrag(drag, stokesCoefficient(f.flowOffset.w, radius), flow);
        } else if (f.kind == SD_FORCE_CURL_NOISE) {
            // A medium velocity with Stokes drag, as flow_field forces: the
            // same keys and feel (a light particle follows the flow, a heavy
            // one lags), and the drag is solved exactly by every integrator.
            // The field is taken at the step's start time for every stage.
            vec3 flow = sampleCurlNoise(ctx, f, p);
            drag = addDrag(drag, stokesCoefficient(f.flowOffset.w, radius), flow);
        }
    }
    LinearDrag l = linearDrag(drag, mass);
    Forcing r;
    r.acceleration = gravity + force / mass;
    r.medium = l.medium;
    r.rate = l.rate;
    return r;
}

// Linear drag solved exactly over a step (exponential integrators, Hochbruck
// and Ostermann 2010, Acta Numerica 19). With the other accelerations a(t) and
// the medium velocity u(t), dv/dt = a + K (u - v) has
//   v(h) = e^(-Kh) v0 + integral_0^h e^(-K(h-s)) (a(s) + K u(s)) ds,
//   p(h) = p0 + integral_0^h v,
// and for a and u polynomial in s these integrals are sums of the functions
//   phi_k(z) = sum_i z^i / (i + k)!   at z = -K h,
// phi_0 = e^z, phi_{k+1}(z) = (phi_k(z) - 1/k!) / z. For constant a and u
// (dragDrift):
//   v(h) = e^(-Kh) v0 + h phi_1 a + K h phi_1 u  (= u + a/K + (v0 - u - a/K) e^(-Kh)),
//   p(h) = p0 + h phi_1 v0 + h^2 phi_2 a + h K h phi_2 u.
// e^(-Kh) is in [0, 1] and h phi_1 <= h for every K >= 0, so no mass or drag
// coefficient makes a step grow the velocity: the drag is unconditionally
// stable, and as K -> 0 the weights tend to Taylor's (phi_k -> 1/k!).
struct DragWeights {
    float decay;  // e^(-K h)
    float phi1;   // phi_1(-K h)
    float phi2;
    float phi3;
    float phi4;
    float x;      // K h, at most 1e30 (so x phi_k stays finite when K overflows)
};

// Below x = 1 the phi_k come from the series of phi_4 (9 terms: the first one
// left out, x^9 / 13!, is under 5e-9 of phi_4 for x < 1) and the recurrence
// upward, phi_k = 1/k! - x phi_{k+1}, which adds without cancellation; above,
// from exp and the recurrence downward, whose differences lose a few ulps at
// x = 1 and fewer beyond. At x = 0 the weights are exactly 1, 1, 1/2, 1/6 and
// 1/24 (rounded), so without drag the integrators are the plain ones.
SD_FN DragWeights dragWeights(float rate, float h) {
    DragWeights w;
    float x = min(rate * h, 1e30f);
    w.x = x;
    if (x < 1.0f) {
        float s = 1.0f / 479001600.0f;  // 1/12!
        s = 1.0f / 39916800.0f - x * s;
        s = 1.0f / 3628800.0f - x * s;
        s = 1.0f / 362880.0f - x * s;
        s = 1.0f / 40320.0f - x * s;
        s = 1.0f / 5040.0f - x * s;
        s = 1.0f / 720.0f - x * s;
        s = 1.0f / 120.0f - x * s;
        w.phi4 = 1.0f / 24.0f - x * s;
        w.phi3 = 1.0f / 6.0f - x * w.phi4;
        w.phi2 = 0.5f - x * w.phi3;
        w.phi1 = 1.0f - x * w.phi2;
        w.decay = 1.0f - x * w.phi1;
    } else {
        w.decay = sdExp(-x);
        w.phi1 = (1.0f - w.decay) / x;
        w.phi2 = (1.0f - w.phi1) / x;
        w.phi3 = (0.5f - w.phi2) / x;
        w.phi4 = (1.0f / 6.0f - w.phi3) / x;
    }
    return w;
}

// v decay + a h phi + u x phi: the velocity after a span h with drag weights of
// that span (x = K h), the weight phi (a phi_k combination) of the other
// accelerations a and of the medium velocity u.
SD_FN vec3 dragVelocity(vec3 v, float decay, vec3 a, vec3 u, float h, float phi, float x) {
    return v * decay + a * (h * phi) + u * (x * phi);
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

// The exact motion over a span h from (p, v) under constant a and u, with w =
// dragWeights(K, h): p + v + a t^2 / 2 and v + a t without drag.
SD_FN Motion dragDrift(vec3 p, vec3 v, vec3 a, vec3 u, DragWeights w, float h) {
    Motion m;
    m.position = p + v * (h * w.phi1) + a * (h * h * w.phi2) + u * (h * w.x * w.phi2);
    m.velocity = dragVelocity(v, w.decay, a, u, h, w.phi1, w.x);
    return m;
}

// The Euler steps (explicit, and semi-implicit for any other integrator id)
// from the acceleration a0 and drag medium u0 at the start (forcingAt), with
// the drag weights of the step, w = dragWeights(rate, dt); shared with the
// CPU's vector update. The velocity is exact for constant a and u (exponential
// Euler); each keeps its position rule, from the old velocity or the new one.
SD_FN Motion eulerMotion(uint integrator, vec3 p, vec3 v, vec3 a0, vec3 u0, DragWeights w, float dt) {
    Motion m;
    m.velocity = dragVelocity(v, w.decay, a0, u0, dt, w.phi1, w.x);
    if (integrator == SD_INTEGRATE_EXPLICIT_EULER) {
        m.position = p + v * dt;
    } else {
        m.position = p + m.velocity * dt;
    }
    return m;
}

SD_FN Motion integrateMotion(SD_IN(KernelContext) ctx, SD_IN(EmitterParams) e, vec3 p, vec3 v, float mass, float radius,
                             float dt) {
    Motion m;
    uint integrator = integratorOf(e);
    Forcing f0 = forcingAt(ctx, e, p, mass, radius);
    // The drag rate depends on the mass and radius only, not on the position:
    // the same at every stage of the step.
    DragWeights w = dragWeights(f0.rate, dt);
    if (integrator == SD_INTEGRATE_VERLET) {
        // Velocity Verlet with exact drag (exponential, second order): the
        // position is the exact drift with a and u held at their start values
        // (p + v h + a h^2 / 2 without drag); the velocity takes a and u linear
        // over the step from the start to the new position, weights
        // h (phi_1 - phi_2) and h phi_2 (h/2 and h/2 without drag).
        m.position = dragDrift(p, v, f0.acceleration, f0.medium, w, dt).position;
        Forcing f1 = forcingAt(ctx, e, m.position, mass, radius);
        m.velocity = dragVelocity(v, w.decay, f0.acceleration, f0.medium, dt, w.phi1 - w.phi2, w.x) +
                     f1.acceleration * (dt * w.phi2) + f1.medium * (w.x * w.phi2);
    } else if (integrator == SD_INTEGRATE_RK4) {
        // Fourth-order Runge-Kutta with exact drag: ETDRK4 (Cox and Matthews
        // 2002, J. Comput. Phys. 176) on (p, v) with the drag and p' = v as its
        // linear part, so every stage is an exact drift and the last stage and
        // the step weigh the forces with phi functions. Without drag its
        // weights are RK4's (1/6, 1/3, 1/3, 1/6 for the velocity; Nystrom's
        // 1/6, 1/6, 1/6, 0 for the position; Fiedler, "Integration Basics",
        // cited by the GPU particle talk) and the stage positions carry the
        // a h^2 / 8 term of RK4-Nystrom: fourth order. For constant a and u both
        // the position and the velocity are exact.
        float h = 0.5f * dt;
        DragWeights hw = dragWeights(f0.rate, h);
        Motion s2 = dragDrift(p, v, f0.acceleration, f0.medium, hw, h);
        Forcing f2 = forcingAt(ctx, e, s2.position, mass, radius);
        Motion s3 = dragDrift(p, v, f2.acceleration, f2.medium, hw, h);
        Forcing f3 = forcingAt(ctx, e, s3.position, mass, radius);
        Motion s4 = dragDrift(s2.position, s2.velocity, f3.acceleration * 2.0f - f0.acceleration,
                              f3.medium * 2.0f - f0.medium, hw, h);
        Forcing f4 = forcingAt(ctx, e, s4.position, mass, radius);
        // Weights of the start, the two middle stages (each) and the end:
        // for the velocity they sum to phi_1, for the position to phi_2.
        float v1 = w.phi1 - 3.0f * w.phi2 + 4.0f * w.phi3;
        float v23 = 2.0f * (w.phi2 - 2.0f * w.phi3);
        float v4 = 4.0f * w.phi3 - w.phi2;
        float p1 = w.phi2 - 3.0f * w.phi3 + 4.0f * w.phi4;
        float p23 = 2.0f * (w.phi3 - 2.0f * w.phi4);
        float p4 = 4.0f * w.phi4 - w.phi3;
        vec3 a23 = f2.acceleration + f3.acceleration;
        vec3 u23 = f2.medium + f3.medium;
        vec3 av = f0.acceleration * v1 + a23 * v23 + f4.acceleration * v4;
        vec3 uv = f0.medium * v1 + u23 * v23 + f4.medium * v4;
        vec3 ap = f0.acceleration * p1 + a23 * p23 + f4.acceleration * p4;
        vec3 up = f0.medium * p1 + u23 * p23 + f4.medium * p4;
        m.velocity = v * w.decay + av * dt + uv * w.x;
        m.position = p + v * (dt * w.phi1) + ap * (dt * dt) + up * (dt * w.x);
    } else {
        m = eulerMotion(integrator, p, v, f0.acceleration, f0.medium, w, dt);
    }
    return m;
}

SD_END
#endif
