// Piecewise-linear curves over normalised age (colour and size over life).
#ifndef SPINDRIFT_KERNELS_CURVES
#define SPINDRIFT_KERNELS_CURVES
#include "types.glsl"
SD_BEGIN

SD_FN float curveTime(SD_IN(CurveParams) c, uint i) {
    vec4 group = c.times[i / 4u];
    uint lane = i % 4u;
    return lane == 0u ? group.x : (lane == 1u ? group.y : (lane == 2u ? group.z : group.w));
}

// Value at t on the segment from key i - 1 (at previousTime) to key i.
SD_FN vec4 curveSegment(SD_IN(CurveParams) c, uint i, float t, float previousTime, float keyTime) {
    float f = (t - previousTime) / (keyTime - previousTime);
    return mix(c.values[i - 1u], c.values[i], f);
}

// Value at t in [0, 1]; constant before the first and after the last key.
SD_FN vec4 evaluateCurve(SD_IN(CurveParams) c, float t) {
    if (c.count == 0u) {
        return vec4(1.0f);
    }
    vec4 result = c.values[0];
    float previousTime = curveTime(c, 0u);
    if (t <= previousTime) {
        return result;
    }
    for (uint i = 1u; i < c.count; ++i) {
        float keyTime = curveTime(c, i);
        if (t <= keyTime) {
            return curveSegment(c, i, t, previousTime, keyTime);
        }
        previousTime = keyTime;
        result = c.values[i];
    }
    return result;
}

SD_END
#endif
