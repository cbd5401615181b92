// Valid scenes: values land in the Def structs with the documented units and
// defaults, references become 1-based ids, and every scene in scenes/ and
// every ```toml example in docs/scene-format.md parses.
#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

using namespace spindrift;

constexpr float kPi = 3.14159265358979f;
const std::filesystem::path kSourceDir = SPINDRIFT_SOURCE_DIR;

SceneDef parse(const std::string& text) { return parseScene(text, "test.toml"); }

TEST(SceneParse, EmptyFileGivesDefaults) {
    const SceneDef s = parse("");
    EXPECT_EQ(s.source, "test.toml");
    EXPECT_EQ(s.world.backend, Backend::Cpu);
    EXPECT_EQ(s.world.seed, 1u);
    EXPECT_FLOAT_EQ(s.run.dt, 1.0f / 60.0f);
    EXPECT_EQ(s.run.steps, 300u);
    EXPECT_TRUE(s.emitters.empty());
}

TEST(SceneParse, WorldCameraRun) {
    const SceneDef s = parse(R"([world]
backend = "auto"
threads = 3
seed = 4294967295
[camera]
eye = [1, 2, 3]
target = [0, 1, 0]
up = [0, 2, 0]
fov = 60
orthographic = true
ortho_height = 4.5
[run]
dt = 0.01
steps = 42
)");
    EXPECT_EQ(s.world.backend, Backend::Auto);
    EXPECT_EQ(s.world.threads, 3u);
    EXPECT_EQ(s.world.seed, 4294967295u);
    EXPECT_EQ(s.render.camera.eye, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.render.camera.target, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.render.camera.up, glm::vec3(0, 1, 0));  // normalised
    EXPECT_FLOAT_EQ(s.render.camera.fovDegrees, 60.0f);
    EXPECT_TRUE(s.render.camera.orthographic);
    EXPECT_FLOAT_EQ(s.render.camera.orthoHeight, 4.5f);
    EXPECT_FLOAT_EQ(s.run.dt, 0.01f);
    EXPECT_EQ(s.run.steps, 42u);
}

TEST(SceneParse, EmitterFieldsAndUnits) {
    const SceneDef s = parse(R"([[emitter]]
name = "e"
lifecycle = "spawn"
capacity = 500
rate = 25.5
duration = 3
bursts = [{time = 0.5, count = 7}, {time = 0, count = 1}]
speed = [1, 2]
lifetime = 4
size = [0.1, 0.2]
rotation = [90, 180]
angular_velocity = -360
color = [[1, 0, 0, 1], [0, 0, 1, 0.5]]
mass = 0.25
integrator = "rk4"
[emitter.shape]
kind = "cone"
center = [1, 2, 3]
radius = 0.5
direction = [0, 0, 2]
spread = 90
)");
    ASSERT_EQ(s.emitters.size(), 1u);
    const EmitterDef& e = s.emitters[0];
    EXPECT_EQ(e.name, "e");
    EXPECT_EQ(e.lifecycle, Lifecycle::Spawn);
    EXPECT_EQ(e.capacity, 500u);
    EXPECT_FLOAT_EQ(e.rate, 25.5f);
    EXPECT_FLOAT_EQ(e.duration, 3.0f);
    ASSERT_EQ(e.bursts.size(), 2u);
    EXPECT_FLOAT_EQ(e.bursts[0].time, 0.5f);
    EXPECT_EQ(e.bursts[0].count, 7u);
    EXPECT_EQ(e.bursts[1].count, 1u);
    EXPECT_FLOAT_EQ(e.speed.min, 1.0f);
    EXPECT_FLOAT_EQ(e.speed.max, 2.0f);
    EXPECT_FLOAT_EQ(e.lifetime.min, 4.0f);  // a single number is [x, x]
    EXPECT_FLOAT_EQ(e.lifetime.max, 4.0f);
    // Degrees in the file, radians in the API.
    EXPECT_NEAR(e.rotation.min, kPi / 2, 1e-6);
    EXPECT_NEAR(e.rotation.max, kPi, 1e-6);
    EXPECT_NEAR(e.angularVelocity.min, -2 * kPi, 1e-5);
    EXPECT_NEAR(e.angularVelocity.max, -2 * kPi, 1e-5);
    EXPECT_EQ(e.color.min, glm::vec4(1, 0, 0, 1));
    EXPECT_EQ(e.color.max, glm::vec4(0, 0, 1, 0.5));
    EXPECT_FLOAT_EQ(e.mass, 0.25f);
    EXPECT_EQ(e.integrator, Integrator::Rk4);
    EXPECT_EQ(e.shape.kind, SpawnShapeKind::Cone);
    EXPECT_EQ(e.shape.center, glm::vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(e.shape.radius, 0.5f);
    EXPECT_EQ(e.shape.direction, glm::vec3(0, 0, 1));  // normalised
    EXPECT_NEAR(e.shape.spreadAngle, kPi / 2, 1e-6);
}

TEST(SceneParse, EmitterDefaultsMatchTheApi) {
    const EmitterDef parsed = parse("[[emitter]]\nname = \"e\"\n").emitters.at(0);
    const EmitterDef api;
    EXPECT_EQ(parsed.lifecycle, api.lifecycle);
    EXPECT_EQ(parsed.capacity, api.capacity);
    EXPECT_EQ(parsed.rate, api.rate);
    EXPECT_EQ(parsed.duration, api.duration);
    EXPECT_EQ(parsed.integrator, api.integrator);
    EXPECT_EQ(parsed.shape.kind, SpawnShapeKind::Point);
    EXPECT_TRUE(parsed.forces.empty());
    EXPECT_TRUE(parsed.collision.enabled);
    EXPECT_FALSE(parsed.stateless);
}

TEST(SceneParse, EveryIntegratorAndLifecycleName) {
    const std::vector<std::pair<std::string, Integrator>> integrators = {
        {"explicit_euler", Integrator::ExplicitEuler},
        {"semi_implicit_euler", Integrator::SemiImplicitEuler},
        {"verlet", Integrator::Verlet},
        {"rk4", Integrator::Rk4}};
    for (const auto& [name, value] : integrators) {
        const SceneDef s = parse("[[emitter]]\nname = \"e\"\nintegrator = \"" + name + "\"\n");
        EXPECT_EQ(s.emitters.at(0).integrator, value) << name;
    }
    EXPECT_EQ(
        parse("[[emitter]]\nname = \"e\"\nlifecycle = \"recycle\"\n").emitters.at(0).lifecycle,
        Lifecycle::Recycle);
}

TEST(SceneParse, CurvesKeepKeysAndValues) {
    const SceneDef s = parse(R"([[emitter]]
name = "e"
color_over_life = [{t = 0, value = [1, 1, 1, 1]}, {t = 1, value = [2, 0.5, 0, 0]}]
size_over_life = [{t = 0, value = 1}, {t = 0.25, value = 3}, {t = 1, value = 0}]
)");
    const EmitterDef& e = s.emitters.at(0);
    ASSERT_EQ(e.colorOverLife.keys.size(), 2u);
    EXPECT_EQ(e.colorOverLife.keys[1].value, glm::vec4(2, 0.5, 0, 0));
    ASSERT_EQ(e.sizeOverLife.keys.size(), 3u);
    EXPECT_FLOAT_EQ(e.sizeOverLife.keys[1].t, 0.25f);
    EXPECT_FLOAT_EQ(e.sizeOverLife.keys[1].value.x, 3.0f);  // size curves use .x
}

TEST(SceneParse, ReferencesBecomeOneBasedIdsInCreationOrder) {
    const SceneDef s = parse(R"(
[[emitter]]
name = "e"
forces = ["wind", "drag"]
collision = {colliders = ["wall"], kill = true}

[[force]]
name = "gravity"
kind = "gravity"
[[force]]
name = "wind"
kind = "wind"
velocity = [1, 0, 0]
[[force]]
name = "drag"
kind = "flow_field"
field = "f2"

[[flow_field]]
name = "f1"
generate = "uniform"
velocity = [0, 1, 0]
bounds_min = [0, 0, 0]
bounds_max = [1, 1, 1]
[[flow_field]]
name = "f2"
generate = "uniform"
velocity = [0, 2, 0]
bounds_min = [0, 0, 0]
bounds_max = [1, 1, 1]

[[collider]]
name = "floor"
kind = "plane"
[[collider]]
name = "wall"
kind = "plane"
normal = [1, 0, 0]
)");
    const EmitterDef& e = s.emitters.at(0);
    ASSERT_EQ(e.forces.size(), 2u);
    EXPECT_EQ(e.forces[0].index, 2u);  // wind is the 2nd force
    EXPECT_EQ(e.forces[1].index, 3u);
    ASSERT_EQ(e.collision.colliders.size(), 1u);
    EXPECT_EQ(e.collision.colliders[0].index, 2u);
    EXPECT_TRUE(e.collision.killOnCollision);
    EXPECT_EQ(s.forces.at(2).flowField.index, 2u);
    EXPECT_EQ(s.forces.at(2).kind, ForceKind::FlowField);
}

TEST(SceneParse, ForceKinds) {
    const SceneDef s = parse(R"(
[[force]]
name = "push"
kind = "repulsor"
position = [1, 2, 3]
strength = 5
radius = 2
falloff = 1
range = 4
[[force]]
name = "spin"
kind = "vortex"
axis = [0, 0, 3]
strength = -2
[[force]]
name = "bees"
kind = "undamping"
strength = 2
target_speed = 3
[[force]]
name = "air"
kind = "damping"
strength = 0.5
range = 2
)");
    const ForceDef& push = s.forces.at(0);
    EXPECT_EQ(push.kind, ForceKind::Attractor);
    EXPECT_FLOAT_EQ(push.strength, -5.0f);  // a repulsor is a negative attractor
    EXPECT_EQ(push.position, glm::vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(push.radius, 2.0f);
    EXPECT_FLOAT_EQ(push.falloff, 1.0f);
    EXPECT_FLOAT_EQ(push.range, 4.0f);
    EXPECT_EQ(s.forces.at(1).kind, ForceKind::Vortex);
    EXPECT_EQ(s.forces.at(1).axis, glm::vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(s.forces.at(1).strength, -2.0f);
    EXPECT_EQ(s.forces.at(2).kind, ForceKind::Undamping);
    EXPECT_FLOAT_EQ(s.forces.at(2).targetSpeed, 3.0f);
    EXPECT_EQ(s.forces.at(3).kind, ForceKind::Damping);
    EXPECT_FLOAT_EQ(s.forces.at(3).range, 2.0f);
}

TEST(SceneParse, CurlNoiseForce) {
    const SceneDef s = parse(R"(
[[force]]
name = "stir"
kind = "curl_noise"
strength = 0.8
frequency = 2.5
speed = 0.25
octaves = 3
seed = 4000000000
viscosity = 0.001
[[force]]
name = "plain"
kind = "curl_noise"
)");
    const ForceDef& f = s.forces.at(0);
    EXPECT_EQ(f.kind, ForceKind::CurlNoise);
    EXPECT_FLOAT_EQ(f.strength, 0.8f);
    EXPECT_FLOAT_EQ(f.frequency, 2.5f);
    EXPECT_FLOAT_EQ(f.speed, 0.25f);
    EXPECT_EQ(f.octaves, 3u);
    EXPECT_EQ(f.seed, 4000000000u);
    EXPECT_FLOAT_EQ(f.viscosity, 0.001f);
    // The defaults: a static single-octave noise of rms 1 m/s, 1 cell per metre, in air.
    const ForceDef& d = s.forces.at(1);
    EXPECT_FLOAT_EQ(d.strength, 1.0f);
    EXPECT_FLOAT_EQ(d.frequency, 1.0f);
    EXPECT_FLOAT_EQ(d.speed, 0.0f);
    EXPECT_EQ(d.octaves, 1u);
    EXPECT_EQ(d.seed, 0u);
    EXPECT_FLOAT_EQ(d.viscosity, 1.8e-5f);
}

TEST(SceneParse, SimpleColliders) {
    const SceneDef s = parse(R"(
[[collider]]
name = "p"
kind = "plane"
point = [0, 1, 0]
normal = [0, 0, -2]
friction = 0.25
resilience = 0.75
rest_speed = 0.05
[[collider]]
name = "s"
kind = "sphere"
center = [1, 1, 1]
radius = 2
[[collider]]
name = "b"
kind = "box"
center = [0, 0, 1]
half_extents = [1, 2, 3]
rotation = [0, 45, 0]
)");
    const ColliderDef& p = s.colliders.at(0);
    EXPECT_EQ(p.kind, ColliderKind::Plane);
    EXPECT_EQ(p.position, glm::vec3(0, 1, 0));
    EXPECT_EQ(p.normal, glm::vec3(0, 0, -1));
    EXPECT_FLOAT_EQ(p.friction, 0.25f);
    EXPECT_FLOAT_EQ(p.resilience, 0.75f);
    EXPECT_FLOAT_EQ(p.restSpeed, 0.05f);
    EXPECT_EQ(s.colliders.at(1).kind, ColliderKind::Sphere);
    EXPECT_FLOAT_EQ(s.colliders.at(1).radius, 2.0f);
    EXPECT_EQ(s.colliders.at(2).halfExtents, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.colliders.at(2).rotationDegrees, glm::vec3(0, 45, 0));  // the API keeps degrees
}

TEST(SceneParse, InlineTerrainHeightsKeepTheirOrder) {
    const SceneDef s = parse(R"([[collider]]
name = "t"
kind = "terrain"
origin = [-1, 0.5, -2]
size = [4, 6]
resolution = [3, 2]
heights = [0, 1, 2, 3, 4, 5]
)");
    const ColliderDef& t = s.colliders.at(0);
    EXPECT_EQ(t.kind, ColliderKind::Terrain);
    EXPECT_EQ(t.position, glm::vec3(-1, 0.5, -2));
    EXPECT_FLOAT_EQ(t.terrainSizeX, 4.0f);
    EXPECT_FLOAT_EQ(t.terrainSizeZ, 6.0f);
    EXPECT_EQ(t.terrainNx, 3u);
    EXPECT_EQ(t.terrainNz, 2u);
    EXPECT_EQ(t.heights, (std::vector<float>{0, 1, 2, 3, 4, 5}));
}

TEST(SceneParse, StatelessEmitter) {
    const SceneDef s = parse(R"([[emitter]]
name = "sparks"
stateless = true
stateless_gravity = [0, -3, 0]
rate = 0
bursts = [{time = 1, count = 10}]
)");
    EXPECT_TRUE(s.emitters.at(0).stateless);
    EXPECT_EQ(s.emitters.at(0).statelessGravity, glm::vec3(0, -3, 0));
}

TEST(SceneParse, LoadSceneResolvesDataRelativeToTheFile) {
    // Relative data paths start at the scene file's folder, not at the
    // current directory (the test runs in the source tree).
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("spindrift-scene-load-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "data");
    std::ofstream(dir / "data" / "one.flow") << "spindrift-flow 1 1 1 1 0 0 0 1 1 1\n3 2 1\n";
    std::ofstream(dir / "s.toml") << "[[flow_field]]\nname = \"f\"\nfile = \"data/one.flow\"\n";
    const SceneDef s = loadScene((dir / "s.toml").string());
    std::filesystem::remove_all(dir);
    ASSERT_EQ(s.flowFields.size(), 1u);
    EXPECT_EQ(s.flowFields[0].velocities.at(0), glm::vec3(3, 2, 1));
    EXPECT_EQ(s.source, (dir / "s.toml").string());
}

// --- The shipped scenes --------------------------------------------------------

std::vector<std::filesystem::path> sceneFiles() {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(kSourceDir / "scenes")) {
        if (entry.path().extension() == ".toml") {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

TEST(SceneFiles, TheRequiredScenesExist) {
    for (const char* name : {"default", "fountain", "sparks", "bees", "smoke", "rain", "cubemap"}) {
        EXPECT_TRUE(std::filesystem::exists(kSourceDir / "scenes" / (std::string(name) + ".toml")))
            << name;
    }
}

TEST(SceneFiles, EverySceneParsesWithModerateCapacities) {
    const auto files = sceneFiles();
    ASSERT_GE(files.size(), 7u);
    for (const auto& path : files) {
        SCOPED_TRACE(path.string());
        SceneDef s;
        ASSERT_NO_THROW(s = loadScene(path.string()));
        EXPECT_FALSE(s.emitters.empty() && s.fluids.empty());
        for (const EmitterDef& e : s.emitters) {
            EXPECT_LE(e.capacity, 20000u) << e.name;  // keeps the scene tests fast
        }
        for (const FluidDef& f : s.fluids) {
            EXPECT_LE(f.capacity, 5000u) << f.name;  // fluids cost far more per particle
        }
    }
}

TEST(SceneFiles, ScenesShowWhatTheirNamesPromise) {
    const auto load = [](const char* name) {
        return loadScene((kSourceDir / "scenes" / name).string());
    };
    const SceneDef fountain = load("fountain.toml");
    EXPECT_EQ(fountain.emitters.at(0).lifecycle, Lifecycle::Spawn);
    EXPECT_EQ(fountain.forces.at(0).kind, ForceKind::Gravity);
    EXPECT_EQ(fountain.colliders.at(0).kind, ColliderKind::Plane);
    EXPECT_GT(fountain.colliders.at(0).resilience, 0.0f);

    const SceneDef sparks = load("sparks.toml");
    EXPECT_TRUE(sparks.emitters.at(0).stateless);
    EXPECT_FALSE(sparks.emitters.at(0).bursts.empty());

    const SceneDef bees = load("bees.toml");
    std::multiset<ForceKind> beeForces;
    bool repulsor = false;
    for (const ForceDef& f : bees.forces) {
        beeForces.insert(f.kind);
        repulsor = repulsor || (f.kind == ForceKind::Attractor && f.strength < 0.0f);
    }
    EXPECT_EQ(beeForces.count(ForceKind::Undamping), 1u);
    EXPECT_GE(beeForces.count(ForceKind::Attractor), 2u);
    EXPECT_TRUE(repulsor);

    const SceneDef smoke = load("smoke.toml");
    EXPECT_EQ(smoke.flowFields.size(), 1u);
    std::set<ForceKind> smokeForces;
    for (const ForceDef& f : smoke.forces) {
        smokeForces.insert(f.kind);
    }
    EXPECT_TRUE(smokeForces.count(ForceKind::FlowField) && smokeForces.count(ForceKind::Wind));
    EXPECT_FALSE(smoke.emitters.at(0).sizeOverLife.keys.empty());
    EXPECT_FALSE(smoke.emitters.at(0).colorOverLife.keys.empty());

    const SceneDef rain = load("rain.toml");
    EXPECT_EQ(rain.colliders.at(0).kind, ColliderKind::Terrain);
    EXPECT_TRUE(rain.emitters.at(0).collision.killOnCollision);
    EXPECT_GT(rain.emitters.at(1).collision.lifeLossOnCollision, 0.0f);

    const SceneDef cube = load("cubemap.toml");
    EXPECT_EQ(cube.colliders.at(0).kind, ColliderKind::CubeMap);
    EXPECT_EQ(cube.colliders.at(0).cubeDepths.size(),
              6u * cube.colliders.at(0).cubeResolution * cube.colliders.at(0).cubeResolution);

    const SceneDef showcase = load("default.toml");
    std::set<std::string> names;
    for (const EmitterDef& e : showcase.emitters) {
        names.insert(e.name);
    }
    EXPECT_EQ(names, (std::set<std::string>{"fountain", "smoke", "sparks"}));
}

// --- The documentation's examples ------------------------------------------------

struct DocBlock {
    int line;  ///< line of the opening fence in the markdown file
    std::string text;
};

std::vector<DocBlock> tomlBlocks(const std::filesystem::path& markdown) {
    std::ifstream in(markdown);
    std::vector<DocBlock> blocks;
    std::string line;
    int number = 0;
    bool inside = false;
    while (std::getline(in, line)) {
        ++number;
        if (!inside && line.rfind("```toml", 0) == 0) {
            inside = true;
            blocks.push_back({number, ""});
        } else if (inside && line.rfind("```", 0) == 0) {
            inside = false;
        } else if (inside) {
            blocks.back().text += line + "\n";
        }
    }
    EXPECT_FALSE(inside) << "unterminated ```toml block in " << markdown;
    return blocks;
}

const std::filesystem::path kDoc = kSourceDir / "docs" / "scene-format.md";

TEST(SceneDocs, EveryTomlExampleParses) {
    const auto blocks = tomlBlocks(kDoc);
    ASSERT_GE(blocks.size(), 30u) << "the extractor found too few examples";
    for (const DocBlock& b : blocks) {
        // Data paths in the examples are relative to scenes/, like the scenes'.
        try {
            parseScene(b.text,
                       "docs/scene-format.md (example at line " + std::to_string(b.line) + ")",
                       (kSourceDir / "scenes").string());
        } catch (const SceneError& e) {
            ADD_FAILURE() << e.what() << "\n" << b.text;
        }
    }
}

TEST(SceneDocs, EveryFeatureHasAnExample) {
    std::string all;
    for (const DocBlock& b : tomlBlocks(kDoc)) {
        all += b.text;
    }
    const std::vector<std::string> features = {
        // shapes
        "kind = \"point\"", "kind = \"sphere\"", "kind = \"box\"", "kind = \"disk\"",
        "kind = \"cone\"", "surface = true",
        // forces
        "kind = \"gravity\"", "kind = \"wind\"", "kind = \"attractor\"", "kind = \"repulsor\"",
        "kind = \"vortex\"", "kind = \"damping\"", "kind = \"undamping\"", "kind = \"flow_field\"",
        "kind = \"curl_noise\"",
        // colliders
        "kind = \"plane\"", "kind = \"terrain\"", "kind = \"cube_map\"",
        // integrators and lifecycles
        "\"explicit_euler\"", "\"semi_implicit_euler\"", "\"verlet\"", "\"rk4\"",
        "lifecycle = \"recycle\"", "lifecycle = \"spawn\"",
        // emitter features
        "color_over_life", "size_over_life", "bursts", "stateless = true", "duration",
        "kill = true", "life_loss", "[world]", "[camera]", "[run]",
        // drawing
        "[render]", "kind = \"color\"", "kind = \"gradient\"", "kind = \"image\"", "[render.fluid]", "steps = ",
        "[emitter.sprite]", "blend = \"alpha\"", "texture = ",
        "[emitter.sprite.flipbook]", "soft_distance", "blend = \"oit\"",
        // data sources
        "generate = \"curl_noise\"", "generate = \"uniform\"", "generate = \"vortex\"",
        "file = \"data/swirl.flow\"", "generate = \"hills\"", "image = \"data/hills.png\"",
        "heights = [", "shapes = [", "file = \"data/rock.cube\"",
        // bodies and joints
        "type = \"static\"", "type = \"kinematic\"", "box = [", "circle = ", "polygon = [", "edge = [",
        "chain = [", "[[body.shape]]", "kind = \"revolute\"", "kind = \"prismatic\"", "kind = \"weld\"",
        "body_gravity", "aim = [[", "body = \"truck\"",
        // fires
        "[[fire]]", "douse_per_strike", "steam_per_strike"};
    for (const std::string& f : features) {
        EXPECT_NE(all.find(f), std::string::npos) << "no example shows " << f;
    }
}

}  // namespace
