#include "io/summary.h"

#include "core/saturating.h"
#include "io/atomic_file.h"
#include "io/json_writer.h"

#include <algorithm>

namespace spindrift::io {

namespace {

/// Hits per collider in id order. The library may report only the colliders
/// that were hit, in any order; a dense array lines up with "colliders".
std::vector<std::uint64_t> denseHits(const StepStats& step, std::size_t colliderCount) {
    std::vector<std::uint64_t> hits(colliderCount, 0);
    for (const ColliderStepStats& c : step.colliderHits) {
        if (c.collider.index >= 1 && c.collider.index <= colliderCount) hits[c.collider.index - 1] += c.hits;
    }
    return hits;
}

void writeCounts(JsonWriter& json, const std::vector<std::uint64_t>& counts) {
    json.beginArray(true);
    for (std::uint64_t n : counts) json.value(n);
    json.endArray();
}

void writeNames(JsonWriter& json, const char* key, const std::vector<std::string>& names) {
    json.key(key);
    json.beginArray(true);
    for (const std::string& name : names) json.value(name);
    json.endArray();
}

void writeHeader(JsonWriter& json, const RunSummary& s) {
    json.key("schema");
    json.value(kSummarySchema);
    json.key("spindrift");
    json.value(versionString());
    json.key("scene");
    json.value(s.scene);
    json.key("backend");
    json.value(s.backend);
    json.key("threads");
    json.value(s.threads);
    json.key("seed");
    json.value(s.seed);
    json.key("dt");
    json.value(s.dt);
    json.key("steps");
    json.value(static_cast<std::uint64_t>(s.steps.size()));
    json.key("every");
    json.value(s.every);
    writeNames(json, "formats", s.formats);
    writeNames(json, "emitters", s.emitterNames);
    writeNames(json, "colliders", s.colliderNames);
    if (!s.fluidNames.empty()) writeNames(json, "fluids", s.fluidNames);
    if (!s.bodyNames.empty()) writeNames(json, "bodies", s.bodyNames);
}

/// Each body after the last step, with the members named as the body
/// cache's CSV columns, so a row and an object compare key by key.
void writeFinalBodies(JsonWriter& json, const std::vector<BodySnapshot>& bodies) {
    json.beginArray();
    for (const BodySnapshot& b : bodies) {
        json.beginObject(true);
        json.key("id");
        json.value(b.id.index);
        json.key("name");
        json.value(b.name);
        json.key("x");
        json.value(b.position.x);
        json.key("y");
        json.value(b.position.y);
        json.key("angle");
        json.value(b.angle);
        json.key("vx");
        json.value(b.linearVelocity.x);
        json.key("vy");
        json.value(b.linearVelocity.y);
        json.key("angular_velocity");
        json.value(b.angularVelocity);
        json.endObject();
    }
    json.endArray();
}

/// The frame measured after 1-based step `step`, or null.
const RunSummary::NumberDensityFrame* frameAt(const RunSummary& s, std::uint64_t step) {
    const auto it = std::lower_bound(s.numberDensity.begin(), s.numberDensity.end(), step,
                                     [](const RunSummary::NumberDensityFrame& f, std::uint64_t n) { return f.step < n; });
    return it != s.numberDensity.end() && it->step == step ? &*it : nullptr;
}

void writeFluidStep(JsonWriter& json, const FluidStepStats& f, const FluidNumberDensity* density) {
    json.beginObject(true);
    json.key("particles");
    json.value(f.particles);
    json.key("born");
    json.value(f.born);
    json.key("mean_density_error");
    json.value(f.meanDensityError);
    json.key("max_density_error");
    json.value(f.maxDensityError);
    json.key("mean_neighbours");
    json.value(f.meanNeighbours);
    json.key("max_speed");
    json.value(f.maxSpeed);
    json.key("neighbour_overflows");
    json.value(f.neighbourOverflows);
    json.key("substeps");
    json.value(f.substeps);
    json.key("substeps_for_speed");
    json.value(f.substepsForSpeed);
    json.key("substeps_for_depth");
    json.value(f.substepsForDepth);
    json.key("substeps_for_compression");
    json.value(f.substepsForCompression);
    json.key("device");
    json.boolean(f.device);
    json.key("non_finite");
    json.value(f.nonFinite);
    if (density != nullptr) {
        json.key("number_density_median");
        json.value(density->median);
        json.key("number_density_p95");
        json.value(density->p95);
    }
    json.endObject();
}

/// Per fluid over the run: final count, mean of the steps' mean density
/// error, max of their max, overflows summed; the number-density ratio of the
/// last frame measured and the largest p95 of all of them.
void writeFluidTotals(JsonWriter& json, const RunSummary& s) {
    json.beginArray();
    for (std::size_t k = 0; k < s.fluidNames.size(); ++k) {
        double meanError = 0.0, maxError = 0.0, maxSpeed = 0.0;
        std::uint64_t overflows = 0, particles = 0, born = 0, steps = 0, nonFinite = 0;
        for (const StepStats& step : s.steps) {
            if (k >= step.fluids.size()) continue;
            const FluidStepStats& f = step.fluids[k];
            meanError += f.meanDensityError;
            maxError = steps == 0 ? f.maxDensityError : std::max(maxError, f.maxDensityError);
            maxSpeed = std::max(maxSpeed, f.maxSpeed);
            overflows += f.neighbourOverflows;
            born += f.born;
            nonFinite += f.nonFinite;
            particles = f.particles;
            ++steps;
        }
        json.beginObject(true);
        json.key("final_particles");
        json.value(particles);
        json.key("born");
        json.value(born);
        json.key("non_finite");
        json.value(nonFinite);
        json.key("mean_density_error");
        json.value(steps > 0 ? meanError / static_cast<double>(steps) : 0.0);
        json.key("max_density_error");
        json.value(maxError);
        json.key("max_speed");
        json.value(maxSpeed);
        json.key("neighbour_overflows");
        json.value(overflows);
        const FluidNumberDensity* last = nullptr;
        double maxP95 = 0.0;
        for (const RunSummary::NumberDensityFrame& frame : s.numberDensity) {
            if (k >= frame.fluids.size()) continue;
            last = &frame.fluids[k];
            maxP95 = std::max(maxP95, last->p95);
        }
        if (last != nullptr) {
            json.key("number_density_reference");
            json.value(static_cast<std::uint64_t>(last->reference));
            json.key("final_number_density_median");
            json.value(last->median);
            json.key("final_number_density_p95");
            json.value(last->p95);
            json.key("max_number_density_p95");
            json.value(maxP95);
        }
        json.endObject();
    }
    json.endArray();
}

void writeStep(JsonWriter& json, const StepStats& step, const RunSummary& s) {
    const std::size_t colliderCount = s.colliderNames.size();
    json.beginObject(true);
    // 1-based: the state after this many steps, the number in the cache file names.
    json.key("step");
    json.value(step.step + 1);
    json.key("time");
    json.value(step.time);
    json.key("alive");
    json.value(step.alive);
    json.key("born");
    json.value(step.born);
    json.key("died");
    json.value(step.died);
    json.key("collisions");
    json.value(step.collisions);
    json.key("clamped");
    json.value(step.clamped);
    json.key("non_finite");
    json.value(step.nonFinite);
    if (!step.frozenBodies.empty()) {
        json.key("frozen_bodies");
        json.beginArray();
        for (BodyId b : step.frozenBodies) json.value(b.index);
        json.endArray();
    }
    json.key("ms");
    json.value(step.milliseconds);
    json.key("collider_hits");
    writeCounts(json, denseHits(step, colliderCount));
    if (!step.fluids.empty()) {
        json.key("fluids");
        json.beginArray();
        const RunSummary::NumberDensityFrame* frame = frameAt(s, step.step + 1);
        for (std::size_t k = 0; k < step.fluids.size(); ++k) {
            const bool measured = frame != nullptr && k < frame->fluids.size();
            writeFluidStep(json, step.fluids[k], measured ? &frame->fluids[k] : nullptr);
        }
        json.endArray();
    }
    json.endObject();
}

struct Totals {
    std::uint64_t born = 0, died = 0, collisions = 0, clamped = 0, nonFinite = 0, frozenBodies = 0;
    double milliseconds = 0.0;
    std::vector<std::uint64_t> colliderHits;
};

Totals sumSteps(const RunSummary& s) {
    Totals t;
    t.colliderHits.assign(s.colliderNames.size(), 0);
    for (const StepStats& step : s.steps) {
        t.born += step.born;
        t.died += step.died;
        t.collisions += step.collisions;
        t.clamped = saturatingAdd(t.clamped, step.clamped);
        t.nonFinite += step.nonFinite;
        t.frozenBodies += step.frozenBodies.size();
        t.milliseconds += step.milliseconds;
        const auto hits = denseHits(step, s.colliderNames.size());
        for (std::size_t i = 0; i < hits.size(); ++i) t.colliderHits[i] += hits[i];
    }
    return t;
}

void writeTotals(JsonWriter& json, const RunSummary& s) {
    const Totals t = sumSteps(s);
    json.beginObject();
    json.key("born");
    json.value(t.born);
    json.key("died");
    json.value(t.died);
    json.key("collisions");
    json.value(t.collisions);
    json.key("clamped");
    json.value(t.clamped);
    json.key("non_finite");
    json.value(t.nonFinite);
    json.key("frozen_bodies");
    json.value(t.frozenBodies);
    json.key("collider_hits");
    writeCounts(json, t.colliderHits);
    json.key("step_ms");
    json.value(t.milliseconds);
    json.key("final_alive");
    json.value(s.steps.empty() ? std::uint64_t{0} : s.steps.back().alive);
    json.key("simulated_seconds");
    json.value(s.steps.empty() ? 0.0 : s.steps.back().time);
    json.key("wall_seconds");
    json.value(s.wallSeconds);
    json.key("cache_files");
    json.value(s.cacheFiles);
    if (!s.fluidNames.empty()) {
        json.key("fluids");
        writeFluidTotals(json, s);
    }
    if (!s.bodyNames.empty()) {
        json.key("final_bodies");
        writeFinalBodies(json, s.finalBodies);
    }
    json.endObject();
}

}  // namespace

void writeSummaryJson(std::ostream& out, const RunSummary& summary) {
    JsonWriter json(out);
    json.beginObject();
    writeHeader(json, summary);
    json.key("per_step");
    json.beginArray();
    for (const StepStats& step : summary.steps) writeStep(json, step, summary);
    json.endArray();
    json.key("totals");
    writeTotals(json, summary);
    json.endObject();
    json.finish();
}

void writeSummary(const std::filesystem::path& path, const RunSummary& summary) {
    AtomicFile file(path);
    writeSummaryJson(file.stream(), summary);
    file.commit();
}

}  // namespace spindrift::io
