// libFuzzer target: the scene parser and world builder (issue 14). Every
// input must either load or be refused with a located SceneError; an
// accepted scene is built on the CPU and stepped twice, and what it then
// shows (particles, fluids, bodies) must be finite. A scene whose fluids
// start with more work than kStepWorkBudget (particles, 3D ones weighted)
// is built and checked but not stepped: its step is legal work, linear in the particles that the
// scene asks for (bench_fluid measures 100,000), and would only measure the
// scene's size against libFuzzer's wall-clock timeout. A squeezed fluid's
// cost, the one way a small scene can take long, is bounded by the solver
// and tested in the suite (FluidCrushed). Anything else (a crash,
// a sanitizer report, another exception, an error without a line, a NaN or
// an infinity) stops the fuzzer with the input saved. docs/fuzzing.md says how to build and
// run it; the bundled scenes are its seed corpus.
#include <spindrift/scene.h>
#include <spindrift/world.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

namespace {

// The solver's work at build, in 2D particles, above which the harness does
// not step the world: 220,000 2D particles took 11 s for two steps under ASan
// (docs/fuzzing.md), so this budget's scenes take about 2.5 s, well inside
// the 10 s timeout. A 3D particle costs about 5.5 times a 2D one there (a
// legal 44,800-particle 3D block took 12.5 s of CPU for two steps: 80
// neighbours in 27 sub-cells against 28 in 9).
constexpr double kStepWorkBudget = 50000.0;
constexpr double kWorkPer3DParticle = 5.5;

double fluidWork(spindrift::WorldId world, const spindrift::SceneDef& scene) {
    double work = 0.0;
    for (std::uint32_t f = 1; f <= spindrift::fluidCount(world); ++f) {
        const double n = static_cast<double>(spindrift::readFluid(world, spindrift::FluidId{f}).count());
        const bool is3D = f <= scene.fluids.size() && scene.fluids[f - 1].dimension == 3;
        work += is3D ? n * kWorkPer3DParticle : n;
    }
    return work;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Aborts (a finding) if anything the world shows is NaN or infinite.
void checkFinite(spindrift::WorldId world) {
    bool ok = true;
    for (std::uint32_t e = 1; e <= spindrift::emitterCount(world); ++e) {
        const spindrift::ParticleSnapshot p = spindrift::readParticles(world, spindrift::EmitterId{e});
        for (std::size_t i = 0; i < p.count(); ++i) {
            ok = ok && finite(p.position[i]) && finite(p.velocity[i]) && std::isfinite(p.size[i]) &&
                 std::isfinite(p.rotation[i]) && finite(glm::vec3(p.color[i])) && std::isfinite(p.color[i].a);
        }
    }
    for (std::uint32_t f = 1; f <= spindrift::fluidCount(world); ++f) {
        const spindrift::FluidSnapshot s = spindrift::readFluid(world, spindrift::FluidId{f});
        for (std::size_t i = 0; i < s.position.size(); ++i) ok = ok && finite(s.position[i]) && finite(s.velocity[i]);
    }
    for (const spindrift::BodySnapshot& b : spindrift::readBodies(world)) {
        ok = ok && finite(glm::vec3(b.position, b.angle)) && finite(glm::vec3(b.linearVelocity, b.angularVelocity));
    }
    if (!ok) {
        std::fprintf(stderr, "a NaN or an infinity in the world's output\n");
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    spindrift::SceneDef scene;
    try {
        // Data paths resolve against the bundled scenes, so mutants of them
        // still find their data files.
        scene = spindrift::parseScene(text, "fuzz.toml", SPINDRIFT_SOURCE_DIR "/scenes");
    } catch (const spindrift::SceneError& e) {
        if (e.line() <= 0) {
            std::fprintf(stderr, "an error without a location: %s\n", e.what());
            std::abort();
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "not a SceneError: %s\n", e.what());
        std::abort();
    }
    scene.world.backend = spindrift::Backend::Cpu;
    scene.world.threads = 1;
    // What passes the loader must build and step (one validation path).
    const spindrift::WorldId world = spindrift::buildWorld(scene);
    if (fluidWork(world, scene) <= kStepWorkBudget) {
        spindrift::stepWorld(world, scene.run.dt);
        spindrift::stepWorld(world, scene.run.dt);
    }
    checkFinite(world);
    spindrift::destroyWorld(world);
    return 0;
}
