// Which instruction set the CPU backend's vector code runs (cpu_target.h).
#include "core/cpu_target.h"

#include <spindrift/errors.h>

#include <atomic>
#include <string>

namespace spindrift {
namespace {

bool supports(UpdateTarget target) {
    switch (target) {
    case UpdateTarget::Scalar:
    case UpdateTarget::Sse2:
        return true;
#if SPINDRIFT_X86
    case UpdateTarget::Sse4:
        return __builtin_cpu_supports("sse4.2");
    case UpdateTarget::Avx2:
        return __builtin_cpu_supports("avx2");
    case UpdateTarget::Avx512:
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
#else
    case UpdateTarget::Sse4:
    case UpdateTarget::Avx2:
    case UpdateTarget::Avx512:
        return false;
#endif
    }
    return false;
}

std::atomic<UpdateTarget>& currentTarget() {
    static std::atomic<UpdateTarget> target{bestUpdateTarget()};
    return target;
}

}  // namespace

std::vector<UpdateTarget> supportedUpdateTargets() {
    std::vector<UpdateTarget> out;
    for (UpdateTarget t :
         {UpdateTarget::Scalar, UpdateTarget::Sse2, UpdateTarget::Sse4, UpdateTarget::Avx2, UpdateTarget::Avx512}) {
        if (supports(t)) {
            out.push_back(t);
        }
    }
    return out;
}

UpdateTarget bestUpdateTarget() {
    if (supports(UpdateTarget::Avx512)) return UpdateTarget::Avx512;
    if (supports(UpdateTarget::Avx2)) return UpdateTarget::Avx2;
    if (supports(UpdateTarget::Sse4)) return UpdateTarget::Sse4;
    return UpdateTarget::Sse2;
}

void setUpdateTarget(UpdateTarget target) {
    if (!supports(target)) {
        throw Error("setUpdateTarget: this CPU cannot run " + std::string(updateTargetName(target)));
    }
    currentTarget().store(target);
}

UpdateTarget updateTarget() { return currentTarget().load(); }

std::string_view updateTargetName(UpdateTarget target) {
    switch (target) {
    case UpdateTarget::Scalar: return "scalar";
    case UpdateTarget::Sse2: return "sse2";
    case UpdateTarget::Sse4: return "sse4.2";
    case UpdateTarget::Avx2: return "avx2";
    case UpdateTarget::Avx512: return "avx512";
    }
    return "?";
}

}  // namespace spindrift
