// The common subset of GLSL 450 and C++20/glm that every kernel is written in.
//
// Rules (docs/design.md, "Write each rule of physics once"): plain structs, vecN,
// functions that take values and return values (no references, no inout), no
// swizzle assignment, float literals with an f suffix (glm does not mix float
// and double), unsigned literals with a u suffix. Struct values are built by
// declaring and assigning fields, never with constructors (the syntax differs).
// Large parameter structs are passed as SD_IN(Type) and bound as SD_LET(Type),
// which are const references on the C++ side and plain values in GLSL.
// A kernel file wraps its contents in SD_BEGIN / SD_END so that on the C++ side
// it lives in namespace spindrift::kernels.
#ifndef SPINDRIFT_KERNELS_PRELUDE
#define SPINDRIFT_KERNELS_PRELUDE

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

#include <bit>
#include <cstdint>

// SD_PRECISE marks a GLSL variable `precise` (GLSL 4.00, section 4.7): no
// contraction of a * b + c into a fused multiply-add, and no other rewriting
// of the operations that compute it. The CPU build does not fuse
// (-ffp-contract=off), so a value both backends must agree on bit for bit
// (sort keys, grid keys) is computed as written on both.
#define SD_PRECISE
#define SD_BEGIN                        \
    namespace spindrift::kernels {      \
    using namespace glm;                \
    using uint = std::uint32_t;
#define SD_END }
// Always inlined: kernels pass structs by value (GLSL has no references), and
// inlining turns those copies into plain register and memory reads.
#define SD_FN [[gnu::always_inline]] inline
// Large read-only parameter structs: a const reference in C++ (a value in
// GLSL). Semantically still a value: nothing writes through it.
#define SD_IN(T) const T&
#define SD_LET(T) const T&
#define SD_CONST inline constexpr
#else
#define SD_PRECISE precise
#define SD_BEGIN
#define SD_END
#define SD_FN
#define SD_IN(T) T
#define SD_LET(T) T
#define SD_CONST const
#endif

SD_BEGIN
SD_CONST float SD_PI = 3.14159265358979f;
SD_CONST uint SD_NONE = 0xFFFFFFFFu;

// whenTrue where c holds, else whenFalse, as a select of each component. In
// C++ `c ? a : b` on vectors is a branch around a copy, and g++ turns a `?:`
// between two loaded floats into a load from a selected address; either keeps
// the CPU's lane loops scalar (src/effects/batch_update_body.inc). A blend of
// the bits is neither, and gives exactly the chosen value.
#ifdef __cplusplus
SD_FN float selectf(float whenFalse, float whenTrue, bool c) {
    const std::uint32_t mask = 0u - static_cast<std::uint32_t>(c);
    return std::bit_cast<float>((std::bit_cast<std::uint32_t>(whenFalse) & ~mask) |
                                (std::bit_cast<std::uint32_t>(whenTrue) & mask));
}
SD_FN vec3 select3(vec3 whenFalse, vec3 whenTrue, bool c) {
    return vec3(selectf(whenFalse.x, whenTrue.x, c), selectf(whenFalse.y, whenTrue.y, c),
                selectf(whenFalse.z, whenTrue.z, c));
}
#else
float selectf(float whenFalse, float whenTrue, bool c) {
    return c ? whenTrue : whenFalse;
}
vec3 select3(vec3 whenFalse, vec3 whenTrue, bool c) {
    return mix(whenFalse, whenTrue, bvec3(c));
}
#endif
SD_END

#endif
