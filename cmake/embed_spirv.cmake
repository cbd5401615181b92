# Turns a SPIR-V binary into a C++ source holding it as a std::uint32_t array,
# so shaders are part of the binary and nothing is looked up on disk at run time.
#   cmake -DINPUT=x.spv -DOUTPUT=x.cpp -DNAME=kEffectsUpdate -P embed_spirv.cmake
# SPIR-V is a stream of little-endian 32-bit words (SPIR-V spec 3.1, "Magic
# Number"); file(READ ... HEX) gives the bytes in order, so each group of four
# bytes b0 b1 b2 b3 becomes the word 0xb3b2b1b0.
file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" length)
math(EXPR remainder "${length} % 8")
if(length EQUAL 0 OR NOT remainder EQUAL 0)
    message(FATAL_ERROR "${INPUT} is not a whole number of 32-bit words (${length} hex digits)")
endif()
string(REGEX REPLACE "(..)(..)(..)(..)" "0x\\4\\3\\2\\1u," words "${hex}")
# Eight words per line keep the generated file readable in a diff or an editor.
string(REGEX REPLACE "(0x[0-9a-f]+u,0x[0-9a-f]+u,0x[0-9a-f]+u,0x[0-9a-f]+u,0x[0-9a-f]+u,0x[0-9a-f]+u,0x[0-9a-f]+u,0x[0-9a-f]+u,)" "\\1\n    " words "${words}")
file(WRITE "${OUTPUT}"
"// Generated from ${INPUT} by src/gpu/embed_spirv.cmake; do not edit.
#include <cstddef>
#include <cstdint>

namespace spindrift::gpu::shaders {
extern const std::uint32_t ${NAME}[];
extern const std::size_t ${NAME}Words;
const std::uint32_t ${NAME}[] = {
    ${words}
};
const std::size_t ${NAME}Words = sizeof(${NAME}) / sizeof(${NAME}[0]);
}  // namespace spindrift::gpu::shaders
")
