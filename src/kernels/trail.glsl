// A particle's trail (EmitterDef::trail, docs/scene-format.md "Trails"): each
// slot keeps a ring of its last `points` positions, one written per step, the
// current position included. Both backends write it where they store a slot
// (src/effects/emitter_step.cpp, effects_update.comp) and the renderer reads
// it (sprites.vert), all through this one indexing rule.
#ifndef SPINDRIFT_KERNELS_TRAIL
#define SPINDRIFT_KERNELS_TRAIL
#include "prelude.glsl"
SD_BEGIN

// Index into an emitter's trail array (points entries per slot, one position
// each) of point k of slot's ribbon, k = 0 the newest; head is the ring index
// of the newest point, k < points.
SD_FN uint trailPointIndex(uint slot, uint k, uint head, uint points) {
    return slot * points + (head + points - k) % points;
}

// Trail points a stored slot writes in a step: a newborn fills its whole
// ring with its birth position (a reused slot never shows the previous
// particle's path), a survivor writes its newest point, a dead slot nothing.
SD_FN uint trailWrites(uint points, bool alive, bool born) {
    if (!alive) {
        return 0u;
    }
    return born ? points : (points > 0u ? 1u : 0u);
}

// Index of write j < trailWrites(...) of slot's step (head: this step's).
SD_FN uint trailWriteIndex(uint slot, uint j, uint head, uint points, bool born) {
    return born ? slot * points + j : trailPointIndex(slot, 0u, head, points);
}

// The ring index the step after a step that wrote `head` writes.
SD_FN uint nextTrailHead(uint head, uint points) {
    return points == 0u ? 0u : (head + 1u) % points;
}

SD_END
#endif
