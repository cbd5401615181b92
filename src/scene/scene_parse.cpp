// Scene files: the top level (world, camera, run) and the order in which the
// object arrays are read. See docs/scene-format.md for the format.
#include "fluid/fluid_state.h"
#include "render/render_rules.h"
#include "scene/default_camera.h"
#include "scene/heightmap_png.h"
#include "scene/limits.h"
#include "scene/parse_internal.h"
#include "scene/toml_prescan.h"

#include <fmt/format.h>

#include <algorithm>

namespace spindrift {

namespace scene {

namespace {

WorldDef parseWorld(const Table& t) {
    t.allowOnly({"backend", "threads", "seed", "body_gravity"}, "[world]");
    WorldDef def;
    if (auto v = t.find("backend")) {
        def.backend = v->choice<Backend>(
            {{"cpu", Backend::Cpu}, {"vulkan", Backend::Vulkan}, {"auto", Backend::Auto}});
    }
    def.threads = static_cast<std::uint32_t>(
        t.integer("threads", def.threads, Bounds::between(0, kMaxThreads)));
    def.seed =
        static_cast<std::uint32_t>(t.integer("seed", def.seed, Bounds::between(0, 4294967295.0)));
    if (auto v = t.find("body_gravity")) {
        const std::vector<float> g = v->numbers(2, Bounds::between(-kMaxBodyGravity, kMaxBodyGravity));
        def.bodyGravity = {g[0], g[1]};
    }
    return def;
}

CameraDef parseCamera(const Table& t) {
    t.allowOnly({"eye", "target", "up", "fov", "orthographic", "ortho_height"}, "[camera]");
    // Type checks here; the ranges are validateCameraDef's (src/render/render_rules.h).
    CameraDef def;
    def.eye = t.vec3("eye", def.eye);
    def.target = t.vec3("target", def.target);
    def.up = t.direction("up", def.up);
    def.fovDegrees = t.real("fov", def.fovDegrees, render_rules::kFov);
    def.orthographic = t.boolean("orthographic", def.orthographic);
    def.orthoHeight = t.real("ortho_height", def.orthoHeight, render_rules::kOrthoHeight);
    validateAt(t, [&] { validateCameraDef(def); });
    return def;
}

RunDef parseRun(const Table& t) {
    t.allowOnly({"dt", "steps"}, "[run]");
    RunDef def;
    def.dt = t.real("dt", def.dt, Bounds::between(kMinStep, kMaxStep));
    def.steps = static_cast<std::uint32_t>(
        t.integer("steps", def.steps, Bounds::between(1, static_cast<double>(kMaxSteps))));
    return def;
}

// [world], [camera] and [run] are optional tables.
template <class Def, class Fn>
Def parseOptionalTable(const Table& root, std::string_view key, Fn parse) {
    if (auto t = root.subTable(key)) {
        return parse(*t);
    }
    return Def{};
}

void checkCount(const std::vector<Table>& tables, std::size_t limit, std::string_view kind) {
    if (tables.size() > limit) {
        tables[limit].fail(fmt::format("at most {} [[{}]] tables are supported, got {}", limit,
                                       kind, tables.size()));
    }
}

}  // namespace

std::string NameTable::add(const Table& table) {
    const Value value = table.require("name", "a string naming this " + kind_);
    std::string name = value.string();
    // Names are shown in messages, the viewer and cache file names: one that
    // is empty or only blanks would be an object nobody can see or name.
    if (name.find_first_not_of(" \t\n\r\f\v") == std::string::npos) {
        value.fail(fmt::format("expected a {} name with a visible character, got \"{}\"", kind_,
                               name.size() <= 16 ? name : name.substr(0, 16) + "..."));
    }
    const auto line = value.node().source().begin.line;
    const auto [it, inserted] =
        entries_.try_emplace(name, Entry{static_cast<std::uint32_t>(entries_.size()), line});
    if (!inserted) {
        value.fail(
            fmt::format("duplicate {} name \"{}\" (first used at line {}); names must be "
                        "unique per kind",
                        kind_, name, it->second.line));
    }
    return name;
}

std::uint32_t NameTable::resolve(const Value& reference) const {
    const std::string name = reference.string();
    if (auto it = entries_.find(name); it != entries_.end()) {
        return it->second.index;
    }
    if (entries_.empty()) {
        reference.fail(fmt::format("unknown {} \"{}\": the scene defines none", kind_, name));
    }
    std::vector<std::string_view> known;
    for (const auto& [key, entry] : entries_) {
        known.push_back(key);
    }
    const std::string_view typo = closestMatch(name, known);
    if (!typo.empty()) {
        reference.fail(fmt::format("unknown {} \"{}\" (did you mean \"{}\"?)", kind_, name, typo));
    }
    reference.fail(
        fmt::format("unknown {} \"{}\"; expected one of {}", kind_, name, quotedList(known)));
}

std::string readDataFile(const Value& value, DataFileRef& ref) {
    const std::string relative = value.string();
    ref.path = (value.context().baseDir / relative).lexically_normal();
    ref.display = ref.path.string();
    ref.keyPath = value.path();
    std::string error;
    std::optional<std::string> text = readWholeFile(ref.path, kMaxDataFileBytes, error);
    if (!text) {
        value.fail(fmt::format("cannot read \"{}\" (resolved to \"{}\"): {}", relative, ref.display,
                               error));
    }
    return *text;
}

void checkNoiseCost(const Table& table, std::uint64_t evaluations, const std::string& what) {
    if (evaluations <= kMaxNoiseEvaluations) {
        return;
    }
    const std::string message = fmt::format(
        "{} is {} noise evaluations, more than the limit of {} (fields are generated while the "
        "scene is read, and the limit keeps that under about half a second); lower the "
        "resolution or the octaves",
        what, evaluations, kMaxNoiseEvaluations);
    for (const std::string_view key : {"octaves", "resolution"}) {
        if (auto v = table.find(key)) {
            v->fail(message);
        }
    }
    table.fail(message);
}

std::string readPngPath(const Value& value) {
    DataFileRef ref;
    const std::string bytes = readDataFile(value, ref);
    std::string error;
    if (!checkPng(bytes, render_rules::kMaxImageSide, error)) {
        value.fail(fmt::format("\"{}\" (resolved to \"{}\"): {}", value.string(), ref.display, error));
    }
    return ref.display;
}

SurfaceTexture readSurfaceTexture(const Table& t) {
    SurfaceTexture texture;
    if (auto v = t.find("texture")) texture.path = readPngPath(*v);
    texture.scale = t.real("texture_scale", texture.scale, kTextureScale);
    return texture;
}

}  // namespace scene

using scene::Table;

SceneDef parseScene(std::string_view text, const std::string& sourceName,
                    const std::string& baseDir) {
    const scene::ParseContext ctx{sourceName, baseDir.empty() ? "." : baseDir};
    scene::prescanToml(text, sourceName);
    toml::table document;
    try {
        document = toml::parse(text, std::string_view(sourceName));
    } catch (const toml::parse_error& e) {
        throw SceneError(sourceName, static_cast<int>(e.source().begin.line),
                         static_cast<int>(e.source().begin.column), "",
                         "TOML syntax error: " + std::string(e.description()));
    }
    const Table root(ctx, document, "");
    root.allowOnly({"world", "camera", "render", "run", "flow_field", "force", "collider", "emitter", "fluid", "body",
                    "joint", "fire", "light"},
                   "the scene");

    SceneDef scene;
    scene.source = sourceName;
    scene.world = scene::parseOptionalTable<WorldDef>(root, "world", scene::parseWorld);
    scene.render = scene::parseOptionalTable<RenderDef>(root, "render", scene::parseRender);
    scene.render.camera = scene::parseOptionalTable<CameraDef>(root, "camera", scene::parseCamera);
    scene.run = scene::parseOptionalTable<RunDef>(root, "run", scene::parseRun);

    // Referenced kinds first, so every reference finds its target's name.
    scene::NameTable flowNames("flow field");
    scene::NameTable forceNames("force");
    scene::NameTable colliderNames("collider");
    scene::NameTable emitterNames("emitter");
    for (const Table& t : scene::tableArray(root, "flow_field")) {
        scene.flowFields.push_back(scene::parseFlowField(t, flowNames));
    }
    const std::vector<Table> forces = scene::tableArray(root, "force");
    scene::checkCount(forces, scene::kMaxForces, "force");
    for (const Table& t : forces) {
        scene.forces.push_back(scene::parseForce(t, forceNames, flowNames));
    }
    const std::vector<Table> colliders = scene::tableArray(root, "collider");
    scene::checkCount(colliders, scene::kMaxColliders, "collider");
    for (const Table& t : colliders) {
        scene.colliders.push_back(scene::parseCollider(t, colliderNames));
    }
    // Bodies before emitters: an emitter may ride on a body.
    scene::NameTable bodyNames("body");
    for (const Table& t : scene::tableArray(root, "body")) {
        scene.bodies.push_back(scene::parseBody(t, bodyNames));
    }
    for (const Table& t : scene::tableArray(root, "emitter")) {
        scene.emitters.push_back(scene::parseEmitter(t, emitterNames, forceNames, colliderNames, bodyNames, scene.emitters));
    }
    // Fluids after bodies: a jet may ride on a body.
    scene::NameTable fluidNames("fluid");
    const std::vector<Table> fluids = scene::tableArray(root, "fluid");
    for (const Table& t : fluids) {
        scene.fluids.push_back(scene::parseFluid(t, fluidNames, bodyNames));
    }
    scene::NameTable jointNames("joint");
    for (const Table& t : scene::tableArray(root, "joint")) {
        scene.joints.push_back(scene::parseJoint(t, jointNames, bodyNames));
    }
    scene::NameTable fireNames("fire");
    for (const Table& t : scene::tableArray(root, "fire")) {
        scene.fires.push_back(scene::parseFire(t, fireNames, bodyNames, emitterNames));
    }
    scene::NameTable lightNames("light");
    const std::vector<Table> lights = scene::tableArray(root, "light");
    scene::checkCount(lights, kRenderMaxLights, "light");
    for (const Table& t : lights) {
        scene.render.lights.push_back(scene::parseLight(t, lightNames, emitterNames));
    }
    if (!scene.fluids.empty()) {
        // Fluids collide with planes, spheres and boxes only (src/fluid/collide.cpp).
        for (std::size_t i = 0; i < colliders.size(); ++i) {
            const ColliderKind kind = scene.colliders[i].kind;
            if (kind == ColliderKind::Terrain || kind == ColliderKind::CubeMap) {
                colliders[i].fail("a scene with a [[fluid]] may use plane, sphere and box colliders only (fluids do "
                                  "not collide with terrain or cube maps yet)");
            }
        }
        // Each block clear of the colliders, as createFluid checks it.
        for (std::size_t i = 0; i < fluids.size(); ++i) {
            scene::validateAt(fluids[i], [&] { fluid::checkBlocksClear(scene.fluids[i], scene.colliders); });
        }
    }
    // Without [camera], a 2D fluid scene is framed square-on (default_camera.h).
    if (!root.subTable("camera")) scene.render.camera = scene::defaultCamera(scene);
    return scene;
}

SceneDef loadScene(const std::string& path) {
    std::string error;
    std::optional<std::string> text = scene::readWholeFile(path, scene::kMaxSceneBytes, error);
    if (!text) {
        throw SceneError(path, 0, 0, "", "cannot read scene file: " + error);
    }
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    return parseScene(*text, path, parent.empty() ? "." : parent.string());
}

}  // namespace spindrift
