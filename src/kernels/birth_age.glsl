// The one birth-age rule of a spawn emitter's rate (src/particles/
// birth_schedule.h): both backends call it with the step's schedule in float
// (ScheduleHeader in layout.glsl), so a birth's age is computed the same way
// on each.
#ifndef SPINDRIFT_KERNELS_BIRTH_AGE
#define SPINDRIFT_KERNELS_BIRTH_AGE
#include "prelude.glsl"
SD_BEGIN

// Age (s, at the end of the step) of the rate's j-th birth of the step: it is
// born when the rate's carry (particles owed before the step) reaches j + 1,
// (j + 1 - carry) / rate seconds into the step of length `span`; clamped to
// [0, maxAge] (maxAge = dt).
SD_FN float rateBirthAge(float j, float carry, float rate, float span, float maxAge) {
    float bornAfterStart = (j + 1.0f - carry) / rate;
    return clamp(span - bornAfterStart, 0.0f, maxAge);
}

SD_END
#endif
