#version 450
// Back-to-front sort of n particle positions on the device: (key, slot) pairs,
// key = backToFrontKey(viewDepth(...)) of src/kernels/sort_key.glsl, sorted by
// an LSD radix sort with 4-bit digits; the result is the slot order, farthest
// first, with ties in slot order: exactly the CPU's sortBackToFront.
//
// Why radix and not bitonic: radix is O(n) with 8 passes that each read and
// write every pair about once (about 210 B per key in all, see
// docs/performance.md); a bitonic network over pairs padded to 2^20 makes 210
// compare-exchange steps, about 1 GB of traffic for 1M keys even when the
// short steps run in shared memory. Radix is stable
// by construction; bitonic would need the index in the compare to be.
//
// Stability without subgroup operations (lavapipe 22.3 has them, but a device
// need not; avoiding them keeps one code path): a tile of keys is split into
// one run of SD_SORT_ITEMS_PER_THREAD consecutive keys per invocation. Every
// invocation counts its run's digits in its own column of a shared table,
// the columns are scanned in invocation order per digit, and each invocation
// scatters its run in order. So pairs leave a tile in input order within a
// digit, tiles are ordered by the digit-major scan of the per-tile counts
// (the CPU sort's order, src/effects/sort.cpp), and every pass is stable.
// This favours small shaders (llvmpipe compiles each pipeline at first use)
// over coalesced loads; a GPU-tuned ranking (Adinets and Merrill, "Onesweep",
// 2022) can replace the scatter without changing the result.
//
// Passes (a specialization constant, one small pipeline each):
//   0 keys:    key and slot of every position; dead slots (age < 0, when an
//              age buffer is bound) get key 0xFFFFFFFF and a live NaN depth
//              0xFFFFFFFE, so the live come first, NaNs last among them;
//              counts the live ones;
//   1 count:   per tile, how many keys have each value of the pass's digit;
//   2 scan:    one workgroup turns the digit-major counts into offsets;
//   3 scatter: pairs to their place in the other buffer pair.
#include "layout.glsl"
#include "sort_key.glsl"

layout(constant_id = 0) const uint PASS = 0u;

const uint DEAD_KEY = 0xFFFFFFFFu;
const uint LIVE_NAN_KEY = 0xFFFFFFFEu;  // no depth maps there (-inf is 0xFF800000)

layout(local_size_x = SD_SORT_WORKGROUP) in;

// Tightly packed xyz floats, as effects_update.comp stores them.
layout(std430, set = 0, binding = SD_SORT_BINDING_POSITIONS) readonly buffer Positions { float positions[]; };
layout(std430, set = 0, binding = SD_SORT_BINDING_AGES) readonly buffer Ages { float ages[]; };
// The current pairs and the next (the CPU swaps them between passes by
// binding the other descriptor set).
layout(std430, set = 0, binding = SD_SORT_BINDING_KEYS) buffer Keys { uint keys[]; };
layout(std430, set = 0, binding = SD_SORT_BINDING_VALUES) buffer Values { uint values[]; };
layout(std430, set = 0, binding = SD_SORT_BINDING_NEXT_KEYS) writeonly buffer NextKeys { uint nextKeys[]; };
layout(std430, set = 0, binding = SD_SORT_BINDING_NEXT_VALUES) writeonly buffer NextValues { uint nextValues[]; };
// Per (digit, tile), digit-major: counts, then (after the scan) offsets.
layout(std430, set = 0, binding = SD_SORT_BINDING_TILE_COUNTS) buffer TileCounts { uint tileCounts[]; };
layout(std430, set = 0, binding = SD_SORT_BINDING_HEADER) buffer Header { TableHeader live; };

layout(push_constant) uniform Sort { SortPush sortArgs; };  // SortPush in layout.glsl

shared uint columns[SD_SORT_RADIX * SD_SORT_WORKGROUP];  // [digit][invocation]
shared uint partials[SD_SORT_WORKGROUP];
shared uint tileLive;

uint digitOf(uint key) { return (key >> sortArgs.shift) & (SD_SORT_RADIX - 1u); }

// The first key of invocation t's run in tile g.
uint runStart(uint g, uint t) { return g * SD_SORT_TILE + t * SD_SORT_ITEMS_PER_THREAD; }

void makeKeys(uint g, uint t) {
    if (t == 0u) {
        tileLive = 0u;
    }
    barrier();
    // Strided over the tile (order does not matter here): neighbouring
    // invocations touch neighbouring keys.
    for (uint r = 0u; r < SD_SORT_ITEMS_PER_THREAD; ++r) {
        uint i = g * SD_SORT_TILE + r * SD_SORT_WORKGROUP + t;
        if (i < sortArgs.count) {
            vec3 p = vec3(positions[3u * i], positions[3u * i + 1u], positions[3u * i + 2u]);
            uint key = backToFrontKey(viewDepth(p, sortArgs.eye.xyz, sortArgs.forward.xyz));
            bool dead = (sortArgs.flags & SD_SORT_FLAG_AGES) != 0u && ages[i] < 0.0f;
            if (dead) {
                key = DEAD_KEY;
            } else {
                key = min(key, LIVE_NAN_KEY);
                atomicAdd(tileLive, 1u);
            }
            keys[i] = key;
            values[i] = i;
        }
    }
    // One global atomic per tile, not per key.
    barrier();
    if (t == 0u) {
        atomicAdd(live.count, tileLive);
    }
}

// Fills this invocation's column with the digit counts of its run.
void countRun(uint g, uint t) {
    for (uint d = 0u; d < SD_SORT_RADIX; ++d) {
        columns[d * SD_SORT_WORKGROUP + t] = 0u;
    }
    uint start = runStart(g, t);
    uint end = min(start + SD_SORT_ITEMS_PER_THREAD, sortArgs.count);
    for (uint i = start; i < end; ++i) {
        columns[digitOf(keys[i]) * SD_SORT_WORKGROUP + t] += 1u;
    }
}

void countTile(uint g, uint t) {
    countRun(g, t);
    barrier();
    if (t < SD_SORT_RADIX) {
        uint total = 0u;
        for (uint u = 0u; u < SD_SORT_WORKGROUP; ++u) {
            total += columns[t * SD_SORT_WORKGROUP + u];
        }
        tileCounts[t * sortArgs.tiles + g] = total;
    }
}

// Exclusive scan of the SD_SORT_RADIX x tiles counts, digit-major, by one
// workgroup: each invocation sums a segment, invocation 0 scans the segment
// sums, each invocation rewrites its segment as offsets.
void scanCounts(uint t) {
    uint entries = SD_SORT_RADIX * sortArgs.tiles;
    uint segment = (entries + SD_SORT_WORKGROUP - 1u) / SD_SORT_WORKGROUP;
    uint start = min(t * segment, entries);
    uint end = min(start + segment, entries);
    uint sum = 0u;
    for (uint j = start; j < end; ++j) {
        sum += tileCounts[j];
    }
    partials[t] = sum;
    barrier();
    if (t == 0u) {
        uint running = 0u;
        for (uint u = 0u; u < SD_SORT_WORKGROUP; ++u) {
            uint s = partials[u];
            partials[u] = running;
            running += s;
        }
    }
    barrier();
    uint running = partials[t];
    for (uint j = start; j < end; ++j) {
        uint c = tileCounts[j];
        tileCounts[j] = running;
        running += c;
    }
}

void scatterTile(uint g, uint t) {
    countRun(g, t);
    barrier();
    // Digit d's columns become the destinations of each invocation's run:
    // the tile's offset for d plus the counts of the runs before it.
    if (t < SD_SORT_RADIX) {
        uint running = tileCounts[t * sortArgs.tiles + g];
        for (uint u = 0u; u < SD_SORT_WORKGROUP; ++u) {
            uint c = columns[t * SD_SORT_WORKGROUP + u];
            columns[t * SD_SORT_WORKGROUP + u] = running;
            running += c;
        }
    }
    barrier();
    uint start = runStart(g, t);
    uint end = min(start + SD_SORT_ITEMS_PER_THREAD, sortArgs.count);
    for (uint i = start; i < end; ++i) {
        uint key = keys[i];
        uint at = digitOf(key) * SD_SORT_WORKGROUP + t;
        uint to = columns[at];
        columns[at] = to + 1u;
        nextKeys[to] = key;
        nextValues[to] = values[i];
    }
}

void main() {
    uint g = gl_WorkGroupID.x;
    uint t = gl_LocalInvocationID.x;
    if (PASS == SD_SORT_PASS_KEYS) {
        makeKeys(g, t);
    } else if (PASS == SD_SORT_PASS_COUNT) {
        countTile(g, t);
    } else if (PASS == SD_SORT_PASS_SCAN) {
        scanCounts(t);
    } else {
        scatterTile(g, t);
    }
}
