// Elementary functions built from IEEE basic operations only (+, -, *, /,
// floor, integer conversions and bit casts), for every kernel that needs exp,
// pow, sin or cos. Why (issue 17, docs/performance.md "Vectorised update"):
// the C library picks its expf / powf / sinf / cosf per CPU (with FMA or
// without), so a CPU world's particles depended on the machine; these give the
// same bits on any x86-64 at any SIMD width (the build uses -ffp-contract=off),
// they vectorise in the CPU's lane loops, and the GPU computes the same
// functions (its built-ins have implementation-defined precision).
//
// Each function reduces its argument and evaluates a Taylor series (the
// coefficients are closed forms) long enough that the truncation is under
// 1e-8 relative; what is left is the rounding of about ten operations, a few
// ulp (tests/kernels/math_test.cpp states the bounds against double
// precision).
#ifndef SPINDRIFT_KERNELS_MATH
#define SPINDRIFT_KERNELS_MATH
#include "prelude.glsl"
SD_BEGIN

SD_CONST float SD_LN2 = 0.693147180559945f;
SD_CONST float SD_LOG2E = 1.44269504088896f;

SD_FN float positiveInfinity() {
    return uintBitsToFloat(0x7f800000u);
}
SD_FN float quietNaN() {
    return uintBitsToFloat(0x7fc00000u);
}

// 2^k for an integral k in [-126, 127], exactly (the exponent field).
SD_FN float exp2Integral(float k) {
    return uintBitsToFloat(uint(int(k) + 127) << 23u);
}

// p 2^n for an integral n in [-252, 254], as two exact powers so that neither
// leaves the normal range; the result may round to a subnormal, 0 or infinity.
SD_FN float scaleByPowerOfTwo(float p, float n) {
    float first = floor(n * 0.5f);
    return p * exp2Integral(first) * exp2Integral(n - first);
}

// e^r for |r| <= ln(2) / 2: Taylor to r^7 (the next term is under 6e-9).
SD_FN float expReduced(float r) {
    float p = 1.0f / 5040.0f;
    p = 1.0f / 720.0f + r * p;
    p = 1.0f / 120.0f + r * p;
    p = 1.0f / 24.0f + r * p;
    p = 1.0f / 6.0f + r * p;
    p = 0.5f + r * p;
    p = 1.0f + r * p;
    return 1.0f + r * p;
}

// The nearest integer to x, as a float; 0 for NaN, so that no integer
// conversion ever sees it (undefined in C++).
SD_FN float nearestIntegral(float x) {
    float n = floor(x + 0.5f);
    return selectf(0.0f, n, n == n);
}

// e^x = 2^n e^r with n = round(x / ln 2) and r = x - n ln 2, ln 2 split in
// two (Cody and Waite; fdlibm's constants) so that n times the first part is
// exact. Below -104 the result rounds to 0, above 89 to infinity.
SD_FN float sdExp(float x) {
    float clamped = clamp(x, -104.0f, 89.0f);
    float n = nearestIntegral(clamped * SD_LOG2E);
    float r = (clamped - n * 6.9314575195e-01f) - n * 1.4286067653e-06f;
    return scaleByPowerOfTwo(expReduced(r), n);
}

// 2^x = 2^n e^((x - n) ln 2); x - n is exact.
SD_FN float sdExp2(float x) {
    float clamped = clamp(x, -151.0f, 129.0f);
    float n = nearestIntegral(clamped);
    return scaleByPowerOfTwo(expReduced((clamped - n) * SD_LN2), n);
}

// log2 x for x = m 2^e, m in [sqrt(1/2), sqrt(2)): e + ln(m) / ln 2 with
// ln m = 2 atanh(s) = 2 (s + s^3/3 + ... + s^9/9), s = (m - 1) / (m + 1),
// |s| <= 0.172 (the next term is under 4e-10). 0 gives -infinity, a negative
// x or NaN gives NaN, infinity gives infinity.
SD_FN float sdLog2(float x) {
    bool subnormal = x < 1.17549435e-38f;
    float scaled = subnormal ? x * 8388608.0f : x;  // 2^23: a subnormal becomes normal
    uint bits = floatBitsToUint(scaled);
    float e = float(int((bits >> 23u) & 0xffu) - 127) - (subnormal ? 23.0f : 0.0f);
    float m = uintBitsToFloat((bits & 0x007fffffu) | 0x3f800000u);
    bool high = m > 1.41421356f;
    m = high ? m * 0.5f : m;
    e = high ? e + 1.0f : e;
    float s = (m - 1.0f) / (m + 1.0f);
    float s2 = s * s;
    // The series' coefficients 2 / (k ln 2), so the sum is log2 m at once.
    float series = 2.0f / (9.0f * SD_LN2);
    series = 2.0f / (7.0f * SD_LN2) + s2 * series;
    series = 2.0f / (5.0f * SD_LN2) + s2 * series;
    series = 2.0f / (3.0f * SD_LN2) + s2 * series;
    series = 2.88539008177793f + s2 * series;  // 2 / ln 2
    float result = e + s * series;
    result = selectf(result, -positiveInfinity(), x == 0.0f);
    result = selectf(result, positiveInfinity(), x == positiveInfinity());
    return selectf(result, quietNaN(), !(x >= 0.0f));
}

// x^y for x >= 0 (the kernels' bases are distances and uniform numbers):
// 2^(y log2 x), with x^0 = 1 for every x as C's pow. A negative x gives NaN.
SD_FN float sdPow(float x, float y) {
    return selectf(sdExp2(y * sdLog2(x)), 1.0f, y == 0.0f);
}

// (sin x, cos x): x = k pi/2 + r with |r| <= pi/4, pi/2 split in three (Cody
// and Waite; Cephes' constants) so that k times the first two parts is exact
// for |k| < 2^15; then Taylor series to r^9 and r^10 (the next terms are
// under 2e-9) and the quadrant k mod 4. Beyond |x| of about 5e4 the reduction
// loses digits (deterministically); infinity and NaN give NaN.
SD_FN vec2 sdSinCos(float x) {
    float k = nearestIntegral(x * 0.636619772367581f);
    float r = ((x - k * 1.5703125f) - k * 4.837512969970703125e-4f) - k * 7.54978995489188216e-8f;
    float r2 = r * r;
    float s = 1.0f / 362880.0f;
    s = -1.0f / 5040.0f + r2 * s;
    s = 1.0f / 120.0f + r2 * s;
    s = -1.0f / 6.0f + r2 * s;
    s = r + r * (r2 * s);
    float c = -1.0f / 3628800.0f;
    c = 1.0f / 40320.0f + r2 * c;
    c = -1.0f / 720.0f + r2 * c;
    c = 1.0f / 24.0f + r2 * c;
    c = -0.5f + r2 * c;
    c = 1.0f + r2 * c;
    float quadrant = k - 4.0f * floor(k * 0.25f);  // 0, 1, 2 or 3
    bool swapped = quadrant == 1.0f || quadrant == 3.0f;
    float sine = swapped ? c : s;
    float cosine = swapped ? s : c;
    sine = quadrant >= 2.0f ? -sine : sine;
    cosine = quadrant == 1.0f || quadrant == 2.0f ? -cosine : cosine;
    return vec2(sine, cosine);
}
SD_FN float sdSin(float x) {
    return sdSinCos(x).x;
}
SD_FN float sdCos(float x) {
    return sdSinCos(x).y;
}

SD_END
#endif
