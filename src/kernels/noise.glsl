// Animated curl noise (Bridson, Hourihan and Nordenstam 2007, "Curl-noise for
// procedural fluid flow", SIGGRAPH): the velocity is the curl of a smooth
// vector potential, so it is divergence-free at every instant. The potential's
// three components are fractal gradient noise (Perlin 2002, "Improving noise":
// quintic fade, the 12 cube-edge gradients) with their analytic gradients, as
// the static [[flow_field]] generate = "curl_noise" builds (src/scene/noise.cpp).
// It evolves by blending two independent noise slices in time: slice k and
// k + 1 at phase = time x speed, weights (1 - w, w) with w the quintic fade of
// the phase's fraction (C2 in time: no jolt at a slice boundary). A blend of
// potentials is a potential, so the blend is still divergence-free.
#ifndef SPINDRIFT_KERNELS_NOISE
#define SPINDRIFT_KERNELS_NOISE
#include "random.glsl"
#include "types.glsl"
SD_BEGIN

// E|grad n|^2 of one gradient-noise octave n (lattice units), averaged over a
// cell and over the gradients: each corner's gradient g is independent with
// E[g g^T] = 2/3 I (12 edge directions, two unit components each), so
// E|grad n|^2 = sum over corners of the cell average of
//   2/3 |grad W|^2 |r|^2 + 4/3 W (grad W . r) + 2 W^2
// (W the corner's fade weight, r = position - corner); the integrand is a sum
// of products of polynomials of one coordinate, integrated exactly:
// 238536280 / 160243083.
SD_CONST float SD_NOISE_GRADIENT_VARIANCE = 1.48859018f;

SD_FN float noiseFade(float t) {
    return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}
SD_FN float noiseFadeDerivative(float t) {
    return 30.0f * t * t * (t * (t - 2.0f) + 1.0f);
}

// Cell index of one coordinate. Beyond 2^24 cells a float has no fraction
// left; anything past 1e9 (or NaN: the particle is removed as non-finite
// anyway) uses cell 0 so the float-to-int conversion is always defined.
SD_FN float noiseCoordinate(float x) {
    return (x >= -1.0e9f && x <= 1.0e9f) ? x : 0.0f;
}

// One of the 12 cube-edge directions, in the order of src/scene/noise.cpp:
// (+-1, +-1, 0), (+-1, 0, +-1), (0, +-1, +-1), first sign from bit 0.
SD_FN vec3 noiseLatticeGradient(uint h) {
    uint d = h % 12u;
    float s1 = (d & 1u) != 0u ? -1.0f : 1.0f;
    float s2 = (d & 2u) != 0u ? -1.0f : 1.0f;
    uint group = d / 4u;
    vec3 g = vec3(0.0f, s1, s2);
    if (group == 0u) {
        g = vec3(s1, s2, 0.0f);
    } else if (group == 1u) {
        g = vec3(s1, 0.0f, s2);
    }
    return g;
}

// The gradient (lattice units) of one octave of gradient noise at q.
SD_FN vec3 gradientNoiseGradient(vec3 q, uint seed) {
    q = vec3(noiseCoordinate(q.x), noiseCoordinate(q.y), noiseCoordinate(q.z));
    vec3 cell = floor(q);
    vec3 f = q - cell;
    uint bx = uint(int(cell.x));
    uint by = uint(int(cell.y));
    uint bz = uint(int(cell.z));
    vec3 w = vec3(noiseFade(f.x), noiseFade(f.y), noiseFade(f.z));
    vec3 dw = vec3(noiseFadeDerivative(f.x), noiseFadeDerivative(f.y), noiseFadeDerivative(f.z));
    uint seedHash = pcgHash(seed ^ 0x9E3779B9u);
    vec3 gradient = vec3(0.0f);
    for (uint corner = 0u; corner < 8u; ++corner) {
        uint cx = corner & 1u;
        uint cy = (corner >> 1u) & 1u;
        uint cz = (corner >> 2u) & 1u;
        uint h = pcgHash(seedHash ^ (bx + cx));
        h = pcgHash(h ^ (by + cy));
        h = pcgHash(h ^ (bz + cz));
        vec3 g = noiseLatticeGradient(h);
        vec3 c = vec3(float(cx), float(cy), float(cz));
        float n = dot(g, f - c);
        // The corner's trilinear fade weight and its partial derivatives.
        vec3 k = vec3(cx != 0u ? w.x : 1.0f - w.x, cy != 0u ? w.y : 1.0f - w.y, cz != 0u ? w.z : 1.0f - w.z);
        vec3 dk = vec3(cx != 0u ? dw.x : -dw.x, cy != 0u ? dw.y : -dw.y, cz != 0u ? dw.z : -dw.z);
        float weight = k.x * k.y * k.z;
        vec3 dWeight = vec3(dk.x * k.y * k.z, k.x * dk.y * k.z, k.x * k.y * dk.z);
        gradient = gradient + dWeight * n + g * weight;
    }
    return gradient;
}

// Octave o at 2^o times the frequency and 2^-o the amplitude: each octave's
// gradient has the same weight (amplitude x frequency = 1), so the octaves'
// gradients, independent (seeds 101 apart), add their variances.
SD_FN vec3 fractalNoiseGradient(vec3 q, uint seed, uint octaves) {
    vec3 sum = vec3(0.0f);
    float scale = 1.0f;
    for (uint o = 0u; o < octaves; ++o) {
        sum = sum + gradientNoiseGradient(q * scale, seed + 101u * o);
        scale = scale * 2.0f;
    }
    return sum;
}

// The gradient of potential component i (0, 1, 2) of noise slice `slice`.
// The components use unrelated seeds and offsets (the static field's) so they
// are independent noises rather than shifted copies.
SD_FN vec3 potentialGradient(uint component, vec3 q, uint slice, uint seed, uint octaves) {
    uint componentSeed = component == 0u ? 0x1234567u : (component == 1u ? 0x89ABCDEu : 0xF1E2D3Cu);
    vec3 offset = component == 0u ? vec3(0.0f)
                                  : (component == 1u ? vec3(31.4f, 17.9f, 5.3f) : vec3(-12.7f, 43.1f, 23.9f));
    uint sliceSeed = pcgHash(seed ^ pcgHash(slice * 0x9E3779B9u + 0x7F4A7C15u));
    return fractalNoiseGradient(q + offset, sliceSeed ^ componentSeed, octaves);
}

// The curl-noise velocity (m/s) at p (m) and world time t (s) of a curl_noise
// force: flowScale x = frequency (1/m), y = speed (1/s), z = octaves; flowField
// = seed; strength = the rms speed (m/s). The gradients are in lattice units
// q = p frequency; the chain rule's factor `frequency` is left out because the
// result is scaled to rms `strength`: with the components, octaves and slices
// independent, E|curl psi|^2 = 2 octaves E|grad n|^2 (w^2 + (1 - w)^2), every
// factor constant in space, so dividing by its root keeps the curl's
// divergence-free form and the rms speed `strength` at every instant (no
// pulsing halfway between slices). At speed 0 the phase is 0 at every time:
// slice 0 alone, the same field always.
SD_FN vec3 curlNoiseVelocity(SD_IN(ForceParams) f, vec3 p, float time) {
    float frequency = f.flowScale.x;
    uint octaves = uint(f.flowScale.z);
    float phase = max(time * f.flowScale.y, 0.0f);
    float base = floor(phase);
    float w = noiseFade(phase - base);
    uint slice = uint(base);
    vec3 q = p * frequency;
    vec3 g0 = potentialGradient(0u, q, slice, f.flowField, octaves) * (1.0f - w);
    vec3 g1 = potentialGradient(1u, q, slice, f.flowField, octaves) * (1.0f - w);
    vec3 g2 = potentialGradient(2u, q, slice, f.flowField, octaves) * (1.0f - w);
    if (w > 0.0f) {
        g0 = g0 + potentialGradient(0u, q, slice + 1u, f.flowField, octaves) * w;
        g1 = g1 + potentialGradient(1u, q, slice + 1u, f.flowField, octaves) * w;
        g2 = g2 + potentialGradient(2u, q, slice + 1u, f.flowField, octaves) * w;
    }
    float variance = 2.0f * SD_NOISE_GRADIENT_VARIANCE * float(octaves) * ((1.0f - w) * (1.0f - w) + w * w);
    // curl (psi_0, psi_1, psi_2)
    vec3 curl = vec3(g2.y - g1.z, g0.z - g2.x, g1.x - g0.y);
    return curl * (f.strength / sqrt(variance));
}

SD_END
#endif
