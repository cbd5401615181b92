// Small pieces shared by the benchmark programs.
#pragma once

#include "core/cpu_target.h"

#include <spindrift/effects.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace spindrift::bench {

/// A plane collider through `point` with unit `normal` (the walls of a tank).
inline ColliderDef wall(glm::vec3 point, glm::vec3 normal) {
    ColliderDef c;
    c.kind = ColliderKind::Plane;
    c.position = point;
    c.normal = normal;
    return c;
}

/// The CPU's vector target named by a benchmark argument, set while it lives
/// and restored after: 0 the best this CPU has, 1 the scalar code for every
/// element (the vector code's baseline, UpdateTarget::Scalar), 2 the AVX2
/// copy (the best one's predecessor on a CPU with AVX-512). `ok()` is false,
/// and the benchmark skipped with an error, where the CPU cannot run it.
class ScopedTarget {
public:
    ScopedTarget(benchmark::State& state, std::int64_t argument) : saved_(updateTarget()) {
        const UpdateTarget target = argument == 1   ? UpdateTarget::Scalar
                                    : argument == 2 ? UpdateTarget::Avx2
                                                    : bestUpdateTarget();
        const std::vector<UpdateTarget> supported = supportedUpdateTargets();
        ok_ = std::find(supported.begin(), supported.end(), target) != supported.end();
        if (!ok_) {
            state.SkipWithError("this CPU cannot run the target");
            return;
        }
        setUpdateTarget(target);
        state.SetLabel(std::string(updateTargetName(target)));
    }
    ~ScopedTarget() { setUpdateTarget(saved_); }
    ScopedTarget(const ScopedTarget&) = delete;
    ScopedTarget& operator=(const ScopedTarget&) = delete;
    bool ok() const { return ok_; }

private:
    UpdateTarget saved_;
    bool ok_ = false;
};

}  // namespace spindrift::bench
