// The density a wall lends to the particles near it (boundary handling, as the
// ghost particles of Akinci et al. 2012, "Versatile rigid-fluid coupling for
// incompressible SPH", but from a table): a particle next to a collider is
// missing the neighbours the wall displaces, so its kernel density reads low.
// The constraint then lets its neighbours crowd in toward the wall until it
// reads rest density: at the floor of a deep tank 1.35x as many particles per
// area as in the bulk, and the free surface 4 cm low in a 0.5 m tank
// (docs/fluid.md). With the table, the wall counts as the fluid continued
// beyond it, a lattice at the fluid's spacing, motionless: it adds to the
// density and pushes the particle off the wall (an immovable neighbour in the
// Jacobian, solver.cpp), so a block laid against a wall starts exactly at rest
// density and stays so.
#include "fluid/fluid_state.h"

#include <cmath>

namespace spindrift::fluid {

void buildWallTable(FluidState& f) {
    WallTable& t = f.wallTable;
    const float sp = f.def.spacing;
    const float h = f.h;
    const float invH2 = 1.0f / (h * h);
    // From half a spacing inside the wall (an overlapping particle) to the
    // distance beyond which no ghost row is within h.
    t.start = -0.5f * sp;
    t.step = (h - t.start) / static_cast<float>(WallTable::kSize - 1);
    const int lateral = static_cast<int>(std::ceil(h / sp));
    const int lateralZ = f.def.dimension == 3 ? lateral : 0;
    const int rows = static_cast<int>(std::ceil(h / sp)) + 1;
    for (int e = 0; e < WallTable::kSize; ++e) {
        const float s = t.start + t.step * static_cast<float>(e);
        float density = 0.0f;
        float push = 0.0f;
        // Ghost rows continue the lattice through the wall: the particle's
        // row at distance s, the ghosts at s + (k + 1/2) spacing beyond it
        // (a block's first row sits half a spacing inside the wall).
        for (int k = 0; k < rows; ++k) {
            const float normal = s + (static_cast<float>(k) + 0.5f) * sp;
            if (normal <= 0.0f) continue;  // a row behind the particle: not beyond the wall
            for (int j = -lateralZ; j <= lateralZ; ++j) {
                for (int i = -lateral; i <= lateral; ++i) {
                    const float a = static_cast<float>(i) * sp;
                    const float b = static_cast<float>(j) * sp;
                    const float r2 = a * a + b * b + normal * normal;
                    const float w = kernels::fluidWeight(r2, invH2);
                    if (w <= 0.0f) continue;
                    const float r = std::sqrt(r2);
                    density += kernels::fluidDensityKernel(r / h);
                    push += w * normal / r;
                }
            }
        }
        t.density[e] = density;
        t.push[e] = push;
    }
}

WallTerm wallTerm(const WallTable& t, float distance) {
    if (!(distance < wallBeyond(t))) return WallTerm{};
    const kernels::FluidWallPlace w = kernels::fluidWallPlace(distance, t.start, t.step, WallTable::kSize);
    if (w.entry < 0) return WallTerm{};
    const auto e = static_cast<std::size_t>(w.entry);
    WallTerm r;
    r.density = kernels::fluidWallLerp(t.density[e], t.density[e + 1], w.fraction);
    r.push = kernels::fluidWallLerp(t.push[e], t.push[e + 1], w.fraction);
    return r;
}

}  // namespace spindrift::fluid
