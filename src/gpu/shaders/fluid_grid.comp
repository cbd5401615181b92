#version 450
// The constraint fluid's grid on the device (the CPU's buildGrid in
// src/fluid/grid.cpp): the two passes around the sort. The host records
// keys, then the back-to-front sort's radix passes (back_to_front_sort.comp,
// stable, so particles of one key keep their index order as the CPU's
// counting sort keeps them), then starts. The result is the CPU's order and
// keyStart, element for element (tests/gpu/gpu_fluid_grid_test.cpp).
//
// Passes (a specialization constant, one small pipeline each):
//   0 keys:   key (fluid.glsl's fluidGridKey) and index of every particle;
//   1 starts: keyStart[k] = how many sorted keys are below k, for every k in
//             [0, keyTotal]: a binary search of the sorted keys per k, so an
//             empty key gets the start of the next non-empty one (the CPU's
//             exclusive prefix sum of the counts) and every invocation does
//             the same work however the particles are spread.
#include "fluid.glsl"
#include "layout.glsl"

layout(constant_id = 0) const uint PASS = 0u;

layout(local_size_x = SD_FLUID_GRID_WORKGROUP) in;

layout(std430, set = 0, binding = SD_FLUID_GRID_BINDING_POSITIONS) readonly buffer Positions { float positions[]; };
layout(std430, set = 0, binding = SD_FLUID_GRID_BINDING_KEYS) writeonly buffer Keys { uint keys[]; };
layout(std430, set = 0, binding = SD_FLUID_GRID_BINDING_VALUES) writeonly buffer Values { uint values[]; };
layout(std430, set = 0, binding = SD_FLUID_GRID_BINDING_SORTED_KEYS) readonly buffer SortedKeys { uint sortedKeys[]; };
layout(std430, set = 0, binding = SD_FLUID_GRID_BINDING_KEY_START) writeonly buffer KeyStart { uint keyStart[]; };

layout(push_constant) uniform Grid { FluidGridPush gridArgs; };  // FluidGridPush in layout.glsl

void makeKey(uint i) {
    if (i >= gridArgs.count) {
        return;
    }
    uint d = gridArgs.dimension;
    vec3 x = vec3(positions[d * i], positions[d * i + 1u], d == 3u ? positions[d * i + 2u] : 0.0f);
    keys[i] = fluidGridKey(x, d, gridArgs.origin.xyz, gridArgs.origin.w, gridArgs.cells.xyz);
    values[i] = i;
}

void findStart(uint k) {
    if (k > gridArgs.keyTotal) {
        return;
    }
    // Lower bound: the first sorted index whose key is >= k (count if none).
    uint lo = 0u;
    uint hi = gridArgs.count;
    while (lo < hi) {
        uint mid = lo + (hi - lo) / 2u;
        if (sortedKeys[mid] < k) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    keyStart[k] = lo;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (PASS == SD_FLUID_GRID_PASS_KEYS) {
        makeKey(i);
    } else {
        findStart(i);
    }
}
