// A scene file's world run on one backend for a number of steps: every
// step's statistics and, at the end, every emitter's particles. Shared by the
// cross-backend scene tests.
#pragma once

#include <spindrift/scene.h>
#include <spindrift/world.h>

#include <chrono>
#include <vector>

namespace spindrift::test {

struct SceneRun {
    std::vector<StepStats> steps;
    std::vector<ParticleSnapshot> snapshots;  // every emitter's, stateless ones evaluated
    double seconds = 0.0;                     // wall time, world creation included
};

inline SceneRun runScene(SceneDef scene, Backend backend, int steps) {
    scene.world.backend = backend;
    scene.world.threads = 1;
    scene.world.framesInFlight = 1;  // each StepStats counts its own step
    const auto start = std::chrono::steady_clock::now();
    WorldId w = buildWorld(scene);
    SceneRun r;
    try {
        for (int s = 0; s < steps; ++s) {
            r.steps.push_back(stepWorld(w, scene.run.dt));
        }
        for (std::uint32_t e = 0; e < emitterCount(w); ++e) {
            r.snapshots.push_back(readParticles(w, EmitterId{e + 1}));
        }
    } catch (...) {
        destroyWorld(w);
        throw;
    }
    destroyWorld(w);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

}  // namespace spindrift::test
