// Which instruction set the CPU backend's vector code runs: chosen at run time
// from what the CPU supports, the same for every vector loop of the process
// (the effects' batch update, src/effects/batch_update.h, and the fluid's
// neighbour filter, src/fluid/neighbours.cpp), and settable so that tests can
// compare every target with the scalar code bit for bit.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#define SPINDRIFT_X86 1
#else
#define SPINDRIFT_X86 0
#endif

namespace spindrift {

/// Which code runs the CPU's vector loops. Scalar: the scalar code for every
/// element (the path before the vector code, kept as the benchmarks'
/// baseline). The others: the vector code compiled for that instruction set
/// (Sse2 is the baseline x86-64 build, 4 lanes; Sse4: SSE4.2, 4 lanes; Avx2:
/// 8 lanes; Avx512: AVX-512 F, VL, BW and DQ, 16 lanes). A loop without a
/// copy for a target runs the next narrower one it has.
enum class UpdateTarget : std::uint8_t { Scalar, Sse2, Sse4, Avx2, Avx512 };

/// The targets this CPU can run, Scalar first.
std::vector<UpdateTarget> supportedUpdateTargets();

/// The best target this CPU supports.
UpdateTarget bestUpdateTarget();

/// Sets the target of every CPU vector loop in the process (tests and
/// benchmarks; the default is bestUpdateTarget()). Throws spindrift::Error
/// if the CPU cannot run it.
void setUpdateTarget(UpdateTarget target);
UpdateTarget updateTarget();
std::string_view updateTargetName(UpdateTarget target);

}  // namespace spindrift
