// The machine-readable record of one `spindrift run`: summary.json.
#pragma once

#include <spindrift/world.h>

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace spindrift::io {

/// Everything summary.json reports. Steps are kept as the library returned
/// them; the writer derives totals so they can never disagree with the steps.
struct RunSummary {
    std::string scene;    ///< scene file as given on the command line
    std::string backend;  ///< "cpu", "vulkan" or "auto", as requested
    std::uint32_t threads = 0;  ///< as requested; 0 = all hardware threads
    std::uint32_t seed = 1;
    float dt = 0.0f;            ///< s
    std::uint32_t every = 0;    ///< dump interval in steps; 0 = no caches written
    std::vector<std::string> formats;        ///< cache formats written ("csv", "ply")
    std::vector<std::string> emitterNames;   ///< index i = emitter id i + 1
    std::vector<std::string> colliderNames;  ///< index i = collider id i + 1
    /// index i = fluid id i + 1; the "fluids" members appear only when non-empty.
    std::vector<std::string> fluidNames;
    /// index i = body id i + 1; the "bodies" members appear only when non-empty.
    std::vector<std::string> bodyNames;
    std::vector<StepStats> steps;            ///< in order, one per step taken
    /// The number-density ratio of every fluid (index i = fluid id i + 1),
    /// measured after some steps (`spindrift run`: each written frame).
    struct NumberDensityFrame {
        std::uint64_t step = 0;  ///< 1-based, as "step" of per_step
        std::vector<FluidNumberDensity> fluids;
    };
    std::vector<NumberDensityFrame> numberDensity;  ///< in step order
    std::vector<BodySnapshot> finalBodies;  ///< every body after the last step, in id order
    double wallSeconds = 0.0;   ///< whole run, including cache writes
    std::uint64_t cacheFiles = 0;  ///< cache files written (summary.json not counted)
};

/// Current schema version of summary.json ("schema" member); bump it when a
/// member changes meaning or disappears.
inline constexpr std::uint32_t kSummarySchema = 1;

/// Writes the summary as JSON (schema in docs/cli.md).
void writeSummaryJson(std::ostream& out, const RunSummary& summary);

/// Same, to `path`, atomically; throws spindrift::Error on failure.
void writeSummary(const std::filesystem::path& path, const RunSummary& summary);

}  // namespace spindrift::io
