// libFuzzer target: the scene parser and world builder (issue 14). Every
// input must either load or be refused with a located SceneError; an
// accepted scene is built on the CPU and stepped twice. Anything else (a
// crash, a sanitizer report, another exception, an error without a line)
// stops the fuzzer with the input saved. docs/fuzzing.md says how to build and
// run it; the bundled scenes are its seed corpus.
#include <spindrift/scene.h>
#include <spindrift/world.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string_view>

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
    spindrift::stepWorld(world, scene.run.dt);
    spindrift::stepWorld(world, scene.run.dt);
    spindrift::destroyWorld(world);
    return 0;
}
