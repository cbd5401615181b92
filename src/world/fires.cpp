// Fires put out by water: strikes of fluid on a burning body arrive as
// collision events (fluid_step.cpp), each takes dousePerStrike of the fire's
// strength and makes steam where it hit; flames and smoke scale with the
// strength and ride on the body.
#include "world/fires.h"

#include "world/fire_rules.h"
#include "world/world.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace spindrift {
namespace {

FireState& fireFromId(World& w, FireId id) {
    if (id.index == 0 || id.index > w.fires.size()) {
        throw Error(fmt::format("fire id {} does not exist in this world", id.index));
    }
    return w.fires[id.index - 1];
}

const BodySnapshot& bodyOf(const std::vector<BodySnapshot>& bodies, BodyId id) {
    for (const BodySnapshot& b : bodies) {
        if (b.id.index == id.index) return b;
    }
    throw Error(fmt::format("body id {} does not exist in this world", id.index));
}

glm::vec2 rotate(glm::vec2 v, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

bool hasEmitter(const World& w, EmitterId id) { return id.index >= 1 && id.index <= w.emitters.size(); }

// The emitter's spawn centre carried by the body (offset in the body frame).
void carry(WorldId id, EmitterId emitter, const BodySnapshot& body, glm::vec2 offset, float z) {
    setEmitterPosition(id, emitter, glm::vec3(body.position + rotate(offset, body.angle), z));
}

}  // namespace

void validateFireDef(const FireDef& def) {
    const FieldCheck check(objectLabel("fire", def.name));
    check.number("strength", def.strength, fire_rules::kStrength);
    check.number("douse_per_strike", def.dousePerStrike, fire_rules::kDousePerStrike);
    check.number("steam_per_strike", def.steamPerStrike, fire_rules::kSteamPerStrike);
}

FireId createFire(WorldId id, const FireDef& def) {
    World& w = worldFromId(id);
    validateFireDef(def);
    for (EmitterId e : {def.flames, def.smoke, def.steam}) {
        if (e.index != 0 && (!hasEmitter(w, e) || w.emitters[e.index - 1]->def.stateless)) {
            throw Error(fmt::format("fire '{}': emitter {} does not exist or is stateless", def.name, e.index));
        }
    }
    const std::vector<BodySnapshot> bodies = readBodies(id);
    const BodySnapshot& body = bodyOf(bodies, def.body);
    FireState f;
    f.def = def;
    auto place = [&](EmitterId e, float& rate, glm::vec2& offset, float& z) {
        if (e.index == 0) return;
        const EmitterDef& ed = w.emitters[e.index - 1]->def;
        rate = ed.rate;
        offset = rotate(glm::vec2(ed.shape.center) - body.position, -body.angle);
        z = ed.shape.center.z;
    };
    place(def.flames, f.flamesRate, f.flamesOffset, f.flamesZ);
    place(def.smoke, f.smokeRate, f.smokeOffset, f.smokeZ);
    w.fires.push_back(f);
    const FireId fire{static_cast<std::uint32_t>(w.fires.size())};
    if (def.flames.index != 0) setEmitterRate(id, def.flames, f.flamesRate * def.strength);
    if (def.smoke.index != 0) setEmitterRate(id, def.smoke, f.smokeRate * def.strength);
    if (def.steam.index != 0) setEmitterRate(id, def.steam, 0.0f);
    return fire;
}

namespace {

/// What is left of a fire's strength after its strikes, in [0, def.strength].
float strengthLeft(const FireState& f) {
    // From the count, not taken off step by step: 500 strikes of 0.002 took
    // a fire of strength 1 down to 6.5e-7 in float steps, not 0, and it
    // burned on though its scene says 500 put it out. What is left under a
    // millionth of full strength is rounding: out.
    const double left = static_cast<double>(f.def.strength) -
                        static_cast<double>(f.def.dousePerStrike) * static_cast<double>(f.strikes);
    return left > 1e-6 ? static_cast<float>(left) : 0.0f;
}

}  // namespace

std::uint32_t fireCount(WorldId id) { return static_cast<std::uint32_t>(worldFromId(id).fires.size()); }
float fireStrength(WorldId id, FireId fire) { return strengthLeft(fireFromId(worldFromId(id), fire)); }
std::uint64_t fireStrikes(WorldId id, FireId fire) { return fireFromId(worldFromId(id), fire).strikes; }

void updateFires(World& w, WorldId id, float dt) {
    if (w.fires.empty()) return;
    const std::vector<BodySnapshot> bodies = readBodies(id);
    for (FireState& f : w.fires) {
        // Strikes of this step on the fire's body, and where they were.
        std::uint64_t strikes = 0;
        glm::vec3 sum(0.0f);
        for (const ParticleEvent& e : w.events.stepStrikes) {
            if (e.fluid.index != 0 && e.body.index == f.def.body.index) {
                ++strikes;
                sum += e.position;
            }
        }
        f.strikes += strikes;
        const float strength = strengthLeft(f);
        const BodySnapshot& body = bodyOf(bodies, f.def.body);
        if (f.def.flames.index != 0) {
            setEmitterRate(id, f.def.flames, f.flamesRate * strength);
            carry(id, f.def.flames, body, f.flamesOffset, f.flamesZ);
        }
        if (f.def.smoke.index != 0) {
            setEmitterRate(id, f.def.smoke, f.smokeRate * strength);
            carry(id, f.def.smoke, body, f.smokeOffset, f.smokeZ);
        }
        if (f.def.steam.index != 0) {
            // Born next step at the strikes' mean position: steamPerStrike
            // each, spread over the step (rate x dt particles).
            setEmitterRate(id, f.def.steam, f.def.steamPerStrike * static_cast<float>(strikes) / dt);
            if (strikes > 0) setEmitterPosition(id, f.def.steam, sum / static_cast<float>(strikes));
        }
    }
}

}  // namespace spindrift
