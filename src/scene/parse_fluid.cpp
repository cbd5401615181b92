// [[fluid]]: constraint fluids with their blocks, jets and polygon obstacles.
#include "kernels/fluid.glsl"
#include "scene/parse_internal.h"

#include <fmt/format.h>

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

FluidJetDef parseJet(const Table& t, const NameTable& bodies) {
    t.allowOnly({"position", "direction", "speed", "rate", "radius", "start", "duration", "aim", "body"},
                "a [[fluid.jet]]");
    FluidJetDef j;
    j.position = t.require("position", "[x, y, z] (m), the nozzle").vec3();
    j.direction = t.direction("direction", j.direction);
    j.speed = t.real("speed", j.speed, Bounds::positive());
    j.rate = t.real("rate", j.rate, Bounds::nonNegative());
    j.radius = t.real("radius", j.radius, Bounds::nonNegative());
    j.start = t.real("start", j.start, Bounds::nonNegative());
    j.duration = t.real("duration", j.duration);
    if (auto aim = t.find("aim")) {
        const std::size_t n = aim->array().size();
        if (n == 0) aim->failExpected("one or more [time, angle] keys (s, rad)");
        for (std::size_t i = 0; i < n; ++i) {
            const Value key = aim->element(i);
            const std::vector<float> ta = key.numbers(2);
            if (ta[0] < 0.0f || (i > 0 && ta[0] < j.aim.back().time)) {
                key.failExpected("a [time, angle] key with time >= 0 s and not before the previous key's");
            }
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
    const std::size_t n = list.array().size();
    if (n < 3 || n > kMaxCorners) {
        list.failExpected(fmt::format("3 to {} [x, y] corners", kMaxCorners));
    }
    FluidPolygonDef p;
    for (std::size_t i = 0; i < n; ++i) {
        const std::vector<float> xy = list.element(i).numbers(2);
        p.vertices.emplace_back(xy[0], xy[1]);
    }
    return p;
}

}  // namespace

FluidDef parseFluid(const Table& t, NameTable& names, const NameTable& bodies) {
    t.allowOnly({"name", "dimension", "spacing", "h", "iterations", "baumgarte", "warm_start", "split_impulse", "max_neighbours",
                 "solver", "substeps", "sleep_speed", "sleep_time", "gravity", "friction", "density", "capacity", "rest_density", "block", "jet", "polygon"},
                "a [[fluid]]");
    FluidDef def;
    def.name = names.add(t);
    def.dimension = static_cast<std::uint32_t>(t.integer("dimension", def.dimension, Bounds::between(2, 3)));
    def.spacing = t.real("spacing", def.spacing, Bounds::positive());
    def.smoothing = t.real("h", def.smoothing, Bounds::nonNegative());
    if (def.smoothing > 0.0f && def.smoothing <= def.spacing) {
        t.failAtKey("h", fmt::format("the smoothing length h must be greater than the spacing {} m, or 0 for "
                                     "the default",
                                     def.spacing));
    }
    def.iterations = static_cast<std::uint32_t>(t.integer("iterations", def.iterations, Bounds::between(kFluidMinIterations, kFluidMaxIterations)));
    def.baumgarte = t.real("baumgarte", def.baumgarte, Bounds::unit());
    def.warmStart = t.real("warm_start", def.warmStart, Bounds::unit());
    def.splitImpulse = t.boolean("split_impulse", def.splitImpulse);
    def.maxNeighbours =
        static_cast<std::uint32_t>(t.integer("max_neighbours", def.maxNeighbours, Bounds::between(0, kFluidMaxNeighbours)));
    if (auto v = t.find("solver")) {
        def.solver = v->choice<FluidSolver>({{"parallel", FluidSolver::Parallel}, {"sequential", FluidSolver::Sequential}});
    }
    def.substeps = static_cast<std::uint32_t>(t.integer("substeps", def.substeps, Bounds::between(0, kFluidMaxSubsteps)));
    def.sleepSpeed = t.real("sleep_speed", def.sleepSpeed, Bounds::nonNegative());
    def.sleepTime = t.real("sleep_time", def.sleepTime, Bounds::nonNegative());
    def.gravity = t.vec3("gravity", def.gravity);
    def.friction = t.real("friction", def.friction, Bounds::nonNegative());
    def.density = t.real("density", def.density, Bounds::positive());
    def.capacity = static_cast<std::uint32_t>(t.integer("capacity", def.capacity, Bounds::between(0, 16 * 1024 * 1024)));
    def.restDensity = t.real("rest_density", def.restDensity, Bounds::nonNegative());
    for (const Table& b : tableArray(t, "block")) def.blocks.push_back(parseBlock(b));
    for (const Table& j : tableArray(t, "jet")) def.jets.push_back(parseJet(j, bodies));
    for (const Table& p : tableArray(t, "polygon")) def.polygons.push_back(parsePolygon(p));
    if (def.blocks.empty() && def.jets.empty()) {
        t.fail("a fluid needs at least one [[fluid.block]] or [[fluid.jet]]");
    }
    // The library's own checks (block sizes, polygon convexity ...), reported
    // at this fluid's table.
    try {
        validateFluidDef(def);
    } catch (const Error& e) {
        t.fail(e.what());
    }
    return def;
}

}  // namespace spindrift::scene
