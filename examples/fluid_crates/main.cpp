// A 2D fluid pouring onto rigid bodies: three crates drop into a tank while a
// jet of water pours onto them from above. Water and crates push each other
// both ways (Box2D runs the bodies). Prints where the crates ended up.
#include <spindrift/world.h>

#include <cstdio>
#include <string>

int main() {
    using namespace spindrift;
    try {
        const WorldId world = createWorld(WorldDef{});  // CPU backend, gravity -9.81 m/s^2 on bodies

        // A static tank 1.2 m wide: a floor and two walls (box half sizes, offsets in m).
        BodyDef tank;
        tank.name = "tank";
        tank.type = BodyType::Static;
        tank.shapes = {boxShape({0.65f, 0.05f}, {0.6f, -0.05f}), boxShape({0.05f, 0.5f}, {-0.05f, 0.5f}),
                       boxShape({0.05f, 0.5f}, {1.25f, 0.5f})};
        createBody(world, tank);

        // Crates 20 cm square, twice as dense as the water (areal densities, kg/m^2).
        const float startX[] = {0.3f, 0.6f, 0.9f};
        const float startY = 0.5f;
        for (int i = 0; i < 3; ++i) {
            BodyDef crate;
            crate.name = "crate" + std::to_string(i + 1);
            crate.position = {startX[i], startY};
            crate.density = 2000.0f;
            crate.shapes = {boxShape({0.1f, 0.1f})};
            createBody(world, crate);
        }

        // Water: a 2D fluid with one jet pointing down over the middle crate.
        FluidDef water;
        water.name = "water";
        water.dimension = 2;
        water.spacing = 0.02f;   // m between particles
        water.density = 1000.0f; // kg/m^2
        FluidJetDef jet;
        jet.position = {0.6f, 0.95f, 0.0f};
        jet.direction = {0.0f, -1.0f, 0.0f};
        jet.speed = 1.0f;      // m/s
        jet.rate = 400.0f;     // particles per second
        jet.radius = 0.08f;    // m, the nozzle's half width
        water.jets = {jet};
        const FluidId fluid = createFluid(world, water);

        const float dt = 1.0f / 60.0f;
        for (int step = 0; step < 90; ++step) stepWorld(world, dt);

        std::printf("water particles=%zu after %.2f s\n", readFluid(world, fluid).count(), worldTime(world));
        for (const BodySnapshot& body : readBodies(world)) {
            if (!body.dynamic) continue;
            std::printf("%s start_y=%.3f x=%.3f y=%.3f angle=%.3f\n", body.name.c_str(), startY, body.position.x,
                        body.position.y, body.angle);
        }
        destroyWorld(world);
    } catch (const Error& e) {
        std::fprintf(stderr, "fluid_crates: %s\n", e.what());
        return 1;
    }
    return 0;
}
