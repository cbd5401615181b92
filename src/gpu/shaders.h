// SPIR-V of src/gpu/shaders/*.comp, compiled by glslc at build time and
// embedded by src/gpu/embed_spirv.cmake (see CMakeLists.txt).
#pragma once

#include <cstddef>
#include <cstdint>

namespace spindrift::gpu::shaders {
extern const std::uint32_t kEffectsUpdate[];
extern const std::size_t kEffectsUpdateWords;
extern const std::uint32_t kBackToFrontSort[];
extern const std::size_t kBackToFrontSortWords;
}  // namespace spindrift::gpu::shaders
