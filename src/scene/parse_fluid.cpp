// [[fluid]]: constraint fluids with their blocks, jets and polygon obstacles.
#include "fluid/fluid_rules.h"
#include "kernels/fluid.glsl"
#include "scene/parse_internal.h"

#include <fmt/format.h>

#include <utility>

namespace spindrift::scene {

namespace {

FluidBlockDef parseBlock(const Table& t) {
    t.allowOnly({"min", "max", "velocity"}, "a [[fluid.block]]");
    FluidBlockDef b;
    b.min = t.require("min", "[x, y, z] (m), the block's low corner").vec3();
    b.max = t.require("max", "[x, y, z] (m), the block's high corner").vec3();
    b.velocity = t.vec3("velocity", b.velocity);
    return b;
}

/// Where `key` stands in the file, as (line, column); t has the key.
std::pair<std::uint32_t, std::uint32_t> keyPosition(const Table& t, std::string_view key) {
    for (auto&& [k, node] : t.raw()) {
        if (k.str() == key) return {k.source().begin.line, k.source().begin.column};
    }
    return {0, 0};
}

FluidJetDef parseJet(const Table& t, const NameTable& bodies) {
    t.allowOnly({"position", "direction", "speed", "rate", "radius", "start", "duration", "aim", "body"},
                "a [[fluid.jet]]");
    // Both set the direction: one would be silently unused. The error points
    // at whichever of the two comes second in the file.
    if (t.has("aim") && t.has("direction")) {
        const std::string_view second = keyPosition(t, "aim") > keyPosition(t, "direction") ? "aim" : "direction";
        t.failAtKey(second, "give either `direction` or `aim` (the direction over time), not both");
    }
    FluidJetDef j;
    j.position = t.require("position", "[x, y, z] (m), the nozzle").vec3();
    j.direction = t.direction("direction", j.direction);
    j.speed = t.real("speed", j.speed, fluid::rules::kJetSpeed);
    j.rate = t.real("rate", j.rate, fluid::rules::kJetRate);
    j.radius = t.real("radius", j.radius, fluid::rules::kJetRadius);
    j.start = t.real("start", j.start, fluid::rules::kJetStart);
    j.duration = t.real("duration", j.duration, fluid::rules::kJetDuration);
    if (auto aim = t.find("aim")) {
        const std::size_t n = aim->array().size();
        if (n == 0) aim->failExpected("one or more [time, angle] keys (s, rad)");
        for (std::size_t i = 0; i < n; ++i) {
            const std::vector<float> ta = aim->element(i).numbers(2);
            j.aim.push_back({ta[0], ta[1]});
        }
    }
    if (auto body = t.find("body")) j.body = {bodies.resolve(*body) + 1};
    return j;
}

FluidPolygonDef parsePolygon(const Table& t) {
    t.allowOnly({"vertices"}, "a [[fluid.polygon]]");
    constexpr std::size_t kMaxCorners = kernels::SD_FLUID_MAX_POLYGON_VERTICES;  // the kernel's FluidPolygon
    const std::string what = fmt::format("[[x, y], ...] (m), 3 to {} corners of a convex polygon", kMaxCorners);
    const Value list = t.require("vertices", what);
    FluidPolygonDef p;
    for (std::size_t i = 0; i < list.array().size(); ++i) {
        const std::vector<float> xy = list.element(i).numbers(2);
        p.vertices.emplace_back(xy[0], xy[1]);
    }
    return p;
}

}  // namespace

FluidDef parseFluid(const Table& t, NameTable& names, const NameTable& bodies) {
    t.allowOnly({"name", "dimension", "spacing", "h", "iterations", "relaxation", "baumgarte", "warm_start", "split_impulse", "max_neighbours",
                 "solver", "backend", "substeps", "sleep_speed", "sleep_time", "gravity", "friction", "density", "capacity", "rest_density", "block", "jet", "polygon"},
                "a [[fluid]]");
    FluidDef def;
    def.name = names.add(t);
    // Values are read with type checks only; their ranges are the rules of
    // validateFluidDef, checked once below (src/fluid/fluid_rules.h).
    namespace rules = fluid::rules;
    def.dimension = t.whole("dimension", def.dimension, rules::kDimension);
    def.spacing = t.real("spacing", def.spacing, rules::kSpacing);
    def.smoothing = t.real("h", def.smoothing, rules::kSmoothing);
    def.iterations = t.whole("iterations", def.iterations, rules::kIterations);
    def.relaxation = t.real("relaxation", def.relaxation, rules::kRelaxation);
    def.baumgarte = t.real("baumgarte", def.baumgarte, rules::kBaumgarte);
    def.warmStart = t.real("warm_start", def.warmStart, rules::kWarmStart);
    def.splitImpulse = t.boolean("split_impulse", def.splitImpulse);
    def.maxNeighbours = t.whole("max_neighbours", def.maxNeighbours, rules::kMaxNeighbours);
    if (auto v = t.find("solver")) {
        def.solver = v->choice<FluidSolver>({{"parallel", FluidSolver::Parallel}, {"sequential", FluidSolver::Sequential}});
    }
    if (auto v = t.find("backend")) {
        def.backend = v->choice<FluidBackend>(
            {{"auto", FluidBackend::Auto}, {"cpu", FluidBackend::Cpu}, {"gpu", FluidBackend::Gpu}});
    }
    def.substeps = t.whole("substeps", def.substeps, rules::kSubsteps);
    def.sleepSpeed = t.real("sleep_speed", def.sleepSpeed, rules::kSleepSpeed);
    def.sleepTime = t.real("sleep_time", def.sleepTime, rules::kSleepTime);
    def.gravity = t.vec3("gravity", def.gravity);
    def.friction = t.real("friction", def.friction, rules::kFriction);
    def.density = t.real("density", def.density, rules::kDensity);
    def.capacity = t.whole("capacity", def.capacity, rules::kCapacity);
    def.restDensity = t.real("rest_density", def.restDensity, rules::kRestDensity);
    for (const Table& b : tableArray(t, "block")) def.blocks.push_back(parseBlock(b));
    for (const Table& j : tableArray(t, "jet")) def.jets.push_back(parseJet(j, bodies));
    for (const Table& p : tableArray(t, "polygon")) def.polygons.push_back(parsePolygon(p));
    if (def.blocks.empty() && def.jets.empty()) {
        t.fail("a fluid needs at least one [[fluid.block]] or [[fluid.jet]]");
    }
    // The library's rules, each reported at the key that broke it.
    validateAt(t, [&] { validateFluidDef(def); });
    return def;
}

}  // namespace spindrift::scene
