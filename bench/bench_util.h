// Small pieces shared by the benchmark programs.
#pragma once

#include "core/cpu_target.h"

#include <spindrift/effects.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
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

/// The CPU as /proc/cpuinfo names it, with its family and model ("unknown"
/// where the file cannot be read). The fluid's ratio to LiquidFun moved from
/// 1.1x to 1.5x between CPUs with the same code (docs/performance.md), and a
/// virtual machine's name can be as bare as "Intel(R) Xeon(R) Processor", so
/// the family and model go with it.
inline std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line, name, family, model;
    const auto valueOf = [](const std::string& l) {
        const std::size_t colon = l.find(':');
        return colon == std::string::npos || colon + 2 > l.size() ? std::string() : l.substr(colon + 2);
    };
    while (std::getline(in, line) && !line.empty()) {  // the first processor's block
        if (line.rfind("model name", 0) == 0) name = valueOf(line);
        if (line.rfind("cpu family", 0) == 0) family = valueOf(line);
        if (line.rfind("model\t", 0) == 0) model = valueOf(line);
    }
    if (name.empty()) return "unknown";
    return name + " (family " + family + ", model " + model + ")";
}

/// Every program's JSON context names the CPU and the vector target its
/// vector loops run at by default, next to Google Benchmark's own (host,
/// CPU count, clock, caches, load).
inline const bool kMachineContext = [] {
    benchmark::AddCustomContext("cpu_model", cpuModel());
    benchmark::AddCustomContext("best_update_target", std::string(updateTargetName(bestUpdateTarget())));
    return true;
}();

}  // namespace spindrift::bench
