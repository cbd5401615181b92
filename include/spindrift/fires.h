// spindrift public API: fires that water puts out. A fire burns on a rigid
// body: its flame and smoke emitters follow the body, and every strike of
// fluid on the body (a collision event, see ParticleEvent::body) takes some of
// its strength and turns into steam where the water hit, until it goes out.
#pragma once

#include <spindrift/export.h>

#include <spindrift/bodies.h>
#include <spindrift/world.h>

#include <cstdint>
#include <string>

namespace spindrift {

/// 1-based creation serial of a fire in its world.
struct FireId { std::uint32_t index = 0; };

struct FireDef {
    std::string name;
    BodyId body;      ///< what burns; water striking it douses the fire
    /// Emitters the fire drives (0: none). Flames and smoke are born at their
    /// spawn shape as placed at creation, carried with the body since; their
    /// rates are the emitters' own rates times the fire's strength. Steam is
    /// born where the water struck, steamPerStrike particles per strike.
    EmitterId flames, smoke, steam;
    float strength = 1.0f;         ///< in (0, 1] at creation; 0 is out
    float dousePerStrike = 0.002f; ///< strength lost per fluid particle strike
    float steamPerStrike = 0.5f;   ///< steam particles per strike
};

/// Throws FieldError, naming the field as a scene file spells it
/// ("douse_per_strike") and the rule it broke, for a definition createFire
/// rejects whatever the world (ids are checked at creation).
SPINDRIFT_API void validateFireDef(const FireDef& def);
/// Throws Error for a bad definition or ids the world does not have.
SPINDRIFT_API FireId createFire(WorldId world, const FireDef& def);
SPINDRIFT_API std::uint32_t fireCount(WorldId world);
/// Strength now: 1 burning fully, 0 out.
SPINDRIFT_API float fireStrength(WorldId world, FireId fire);
/// Fluid strikes on the fire's body so far.
SPINDRIFT_API std::uint64_t fireStrikes(WorldId world, FireId fire);

}  // namespace spindrift
