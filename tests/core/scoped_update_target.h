// Sets the process's vector target (src/core/cpu_target.h) for one test and
// restores the previous one when the test ends.
#pragma once

#include "core/cpu_target.h"

namespace spindrift::test {

struct ScopedTarget {
    explicit ScopedTarget(UpdateTarget t) : saved(updateTarget()) { setUpdateTarget(t); }
    ~ScopedTarget() { setUpdateTarget(saved); }
    ScopedTarget(const ScopedTarget&) = delete;
    ScopedTarget& operator=(const ScopedTarget&) = delete;
    UpdateTarget saved;
};

}  // namespace spindrift::test
