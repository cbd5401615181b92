// [[flow_field]]: a grid of velocities, read from a file or generated.
//
// The resolution and bounds are read with type checks only and checked by
// validateFlowFieldGrid (src/particles/flow_field_rules.h) before a generator
// fills the grid, the whole Def by validateFlowFieldDef after; a generator's
// own parameters (frequency, octaves ...) never reach the Def and are checked
// here.
#include "particles/flow_field_rules.h"
#include "particles/params.h"
#include "scene/field_sources.h"
#include "scene/parse_internal.h"

#include <fmt/format.h>

namespace spindrift::scene {

namespace {

enum class FlowSource { CurlNoise, Uniform, Vortex };

// `resolution = [nx, ny]` (planar, nz = 1) or `[nx, ny, nz]`.
void readResolution(const Table& t, FlowFieldDef& def, glm::uvec3 fallback) {
    glm::uvec3 n = fallback;
    if (auto v = t.find("resolution")) {
        const std::size_t count = v->array().size();
        if (count != 2 && count != 3) {
            v->fail(fmt::format("expected [nx, ny] or [nx, ny, nz], got an array of {}", count));
        }
        n = glm::uvec3(1);
        for (std::size_t a = 0; a < count; ++a) {
            n[a] = v->element(a).whole<std::uint32_t>(flow_field_rules::kAxis);
        }
    }
    def.nx = n.x;
    def.ny = n.y;
    def.nz = n.z;
}

void readBounds(const Table& t, FlowFieldDef& def) {
    def.boundsMin = t.require("bounds_min", "[x, y, z] (m)").vec3();
    def.boundsMax = t.require("bounds_max", "[x, y, z] (m)").vec3();
}

void generateCurlNoise(const Table& t, FlowFieldDef& def) {
    CurlNoiseParams params;
    params.frequency = t.real("frequency", params.frequency, Bounds::positive());
    params.strength = t.real("strength", params.strength, Bounds::nonNegative());
    params.seed = static_cast<std::uint32_t>(
        t.integer("seed", params.seed, Bounds::between(0, 4294967295.0)));
    params.octaves =
        static_cast<std::uint32_t>(t.integer("octaves", params.octaves, Bounds::between(1, 8)));
    checkNoiseCost(t, curlNoiseEvaluations(def, params.octaves),
                   fmt::format("curl noise of {} x {} x {} samples x {} octaves{}", def.nx, def.ny, def.nz,
                               params.octaves, def.nz == 1 ? "" : " x 3 potentials"));
    fillCurlNoise(def, params);
}

void generateVortex(const Table& t, FlowFieldDef& def) {
    const glm::vec3 center = t.vec3("center", glm::vec3(0.0f));
    const glm::vec3 axis = t.direction("axis", glm::vec3(0.0f, 1.0f, 0.0f));
    const float speed = t.real("speed", 1.0f);
    const float radius = t.real("radius", 1.0f, Bounds::positive());
    fillVortex(def, center, axis, speed, radius);
}

FlowSource readGenerator(const Table& t) {
    return t.find("generate")
        ->choice<FlowSource>({{"curl_noise", FlowSource::CurlNoise},
                              {"uniform", FlowSource::Uniform},
                              {"vortex", FlowSource::Vortex}});
}

std::vector<std::string_view> generatorKeys(FlowSource source) {
    std::vector<std::string_view> keys = {"name", "generate", "bounds_min", "bounds_max",
                                          "resolution"};
    switch (source) {
        case FlowSource::CurlNoise:
            keys.insert(keys.end(), {"frequency", "strength", "seed", "octaves"});
            break;
        case FlowSource::Uniform:
            keys.push_back("velocity");
            break;
        case FlowSource::Vortex:
            keys.insert(keys.end(), {"center", "axis", "speed", "radius"});
            break;
    }
    return keys;
}

void generateField(const Table& t, FlowSource source, FlowFieldDef& def) {
    // A uniform field needs no detail; the others default to 32^3 samples.
    readResolution(t, def, source == FlowSource::Uniform ? glm::uvec3(1) : glm::uvec3(32));
    readBounds(t, def);
    validateAt(t, [&] { validateFlowFieldGrid(def); });
    switch (source) {
        case FlowSource::CurlNoise:
            generateCurlNoise(t, def);
            break;
        case FlowSource::Uniform:
            fillUniform(def, t.require("velocity", "[vx, vy, vz] (m/s)").vec3());
            break;
        case FlowSource::Vortex:
            generateVortex(t, def);
            break;
    }
}

}  // namespace

FlowFieldDef parseFlowField(const Table& t, NameTable& names) {
    FlowFieldDef def;
    const bool fromFile = t.has("file");
    if (fromFile && t.has("generate")) {
        t.failAtKey("generate", "give either `file` or `generate`, not both");
    }
    if (!fromFile && !t.has("generate")) {
        // A misspelt `file` or `generate` is better reported as such.
        std::vector<std::string_view> all = {"file"};
        for (FlowSource s : {FlowSource::CurlNoise, FlowSource::Uniform, FlowSource::Vortex}) {
            for (std::string_view key : generatorKeys(s)) {
                all.push_back(key);
            }
        }
        t.allowOnly(all, "a flow field");
        t.fail(
            "a flow field needs a source: `file = \"...\"` or `generate = \"curl_noise\" | "
            "\"uniform\" | \"vortex\"`");
    }
    if (fromFile) {
        t.allowOnly({"name", "file"},
                    "a flow field read from a file (its header gives bounds and resolution)");
        def.name = names.add(t);
        DataFileRef ref;
        const std::string text = readDataFile(*t.find("file"), ref);
        readFlowFile(ref, text, def);
        return def;
    }
    const FlowSource source = readGenerator(t);
    t.allowOnly(generatorKeys(source),
                fmt::format("a flow field generated by \"{}\"", t.find("generate")->string()));
    def.name = names.add(t);
    generateField(t, source, def);
    validateAt(t, [&] { validateFlowFieldDef(def); });
    return def;
}

}  // namespace spindrift::scene
