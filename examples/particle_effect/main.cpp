// A particle effect built in code: sparks sprayed upward from a cone, pulled
// down by gravity, bouncing on the ground. Stepped for two seconds at 60 steps
// per second, then read back.
#include <spindrift/world.h>

#include <algorithm>
#include <cstdio>
#include <limits>

int main() {
    using namespace spindrift;
    try {
        WorldDef worldDef;
        worldDef.backend = Backend::Cpu;
        const WorldId world = createWorld(worldDef);

        createForce(world, ForceDef{});  // default: gravity, 9.81 m/s^2 down

        ColliderDef ground;  // default: the plane y = 0, facing up
        ground.resilience = 0.4f;
        createCollider(world, ground);

        EmitterDef sparks;
        sparks.name = "sparks";
        sparks.rate = 600.0f;      // particles per second
        sparks.capacity = 2000;    // most alive at once
        sparks.shape.kind = SpawnShapeKind::Cone;
        sparks.shape.center = {0.0f, 0.1f, 0.0f};
        sparks.shape.radius = 0.05f;
        sparks.shape.spreadAngle = 0.3f;  // rad, around +y
        sparks.speed = {3.0f, 5.0f};      // m/s
        sparks.lifetime = {1.5f, 2.5f};   // s
        sparks.color = {{1.0f, 0.6f, 0.1f, 1.0f}, {1.0f, 0.9f, 0.4f, 1.0f}};
        const EmitterId emitter = createEmitter(world, sparks);

        const float dt = 1.0f / 60.0f;
        std::uint64_t collisions = 0;
        for (int step = 1; step <= 120; ++step) {
            const StepStats stats = stepWorld(world, dt);
            collisions += stats.collisions;
            if (step % 30 == 0) {
                std::printf("t=%.2f s alive=%llu born=%llu died=%llu\n", stats.time,
                            static_cast<unsigned long long>(stats.alive), static_cast<unsigned long long>(stats.born),
                            static_cast<unsigned long long>(stats.died));
            }
        }

        const ParticleSnapshot particles = readParticles(world, emitter);
        float lowest = std::numeric_limits<float>::infinity(), highest = -lowest;
        for (const glm::vec3& p : particles.position) {
            lowest = std::min(lowest, p.y);
            highest = std::max(highest, p.y);
        }
        std::printf("particles=%zu collisions=%llu lowest_y=%.4f highest_y=%.4f\n", particles.count(),
                    static_cast<unsigned long long>(collisions), lowest, highest);
        destroyWorld(world);
    } catch (const Error& e) {
        std::fprintf(stderr, "particle_effect: %s\n", e.what());
        return 1;
    }
    return 0;
}
