// Back-to-front sorting, written once for both backends: the view depth, the
// depth -> key map (src/effects/sort.h documents the key ranges) and the shape
// of the GPU radix sort (src/gpu/shaders/back_to_front_sort.comp), whose
// dispatch sizes the C++ side computes from the same constants.
//
// Why the key is computed on the bits and not with float compares: GLSL lets a
// compiler assume no NaNs and fold x + 0.0 into x (spirv-opt and NIR both do,
// unless an operation is `precise`), so the CPU's `depth != depth` NaN test and
// `depth + 0.0f` -0 fold would not survive on the GPU. Integer operations on
// floatBitsToUint are exact everywhere.
#ifndef SPINDRIFT_KERNELS_SORT_KEY
#define SPINDRIFT_KERNELS_SORT_KEY
#include "prelude.glsl"

// SD_PRECISE (prelude.glsl) on the depth: the CPU build does not fuse, so
// neither may the GPU, or depths differ in the last bit and so may orders.
SD_BEGIN

// View depth of p: dot(p - eye, forward), with forward already unit length
// (normalizeViewDirection, src/effects/sort.h). Summed as glm::dot sums a vec3
// (x + y first, then z), so both backends round identically.
SD_FN float viewDepth(vec3 p, vec3 eye, vec3 forward) {
    SD_PRECISE vec3 d = p - eye;
    SD_PRECISE float depth = d.x * forward.x + d.y * forward.y + d.z * forward.z;
    return depth;
}

// Ascending key order = descending depth: positive depths flip every bit but
// the sign (0x00000000 .. 0x7FFFFFFF), negative depths keep their bits
// (0x80000001 .. 0xFF800000); -0 is treated as +0 (u > 0x80000000 excludes
// it), so the two tie at 0x7FFFFFFF; every NaN maps to 0xFFFFFFFF (last).
SD_FN uint backToFrontKey(float depth) {
    uint u = floatBitsToUint(depth);
    uint magnitude = u & 0x7FFFFFFFu;
    bool negative = u > 0x80000000u;
    uint key = magnitude ^ (negative ? 0x80000000u : 0x7FFFFFFFu);
    return magnitude > 0x7F800000u ? 0xFFFFFFFFu : key;
}

// GPU radix sort shape: 4-bit digits (8 passes over 32-bit keys), tiles of
// SD_SORT_WORKGROUP threads x SD_SORT_ITEMS_PER_THREAD consecutive keys.
// 4 bits keep the scatter's per-thread digit counters (radix x workgroup
// uints) at 4 KiB of shared memory; 8 bits would need 64 KiB, twice the
// 32 KiB a Vulkan device must offer (maxComputeSharedMemorySize).
SD_CONST uint SD_SORT_DIGIT_BITS = 4u;
SD_CONST uint SD_SORT_RADIX = 16u;
SD_CONST uint SD_SORT_PASSES = 8u;
SD_CONST uint SD_SORT_WORKGROUP = 64u;
SD_CONST uint SD_SORT_ITEMS_PER_THREAD = 16u;
SD_CONST uint SD_SORT_TILE = 1024u;  // SD_SORT_WORKGROUP * SD_SORT_ITEMS_PER_THREAD

SD_END

#endif
