// [[fire]]: a fire on a body, driving flame, smoke and steam emitters
// (include/spindrift/fires.h).
#include "scene/parse_internal.h"
#include "world/fire_rules.h"

namespace spindrift::scene {

FireDef parseFire(const Table& t, NameTable& names, const NameTable& bodies, const NameTable& emitters) {
    t.allowOnly({"name", "body", "flames", "smoke", "steam", "strength", "douse_per_strike", "steam_per_strike"},
                "a [[fire]]");
    FireDef def;
    def.name = names.add(t);
    def.body = {bodies.resolve(t.require("body", "the name of the [[body]] that burns")) + 1};
    auto emitter = [&](const char* key) {
        if (auto v = t.find(key)) return EmitterId{emitters.resolve(*v) + 1};
        return EmitterId{};
    };
    def.flames = emitter("flames");
    def.smoke = emitter("smoke");
    def.steam = emitter("steam");
    // Type checks here; the ranges are validateFireDef's, checked once.
    def.strength = t.real("strength", def.strength, fire_rules::kStrength);
    def.dousePerStrike = t.real("douse_per_strike", def.dousePerStrike, fire_rules::kDousePerStrike);
    def.steamPerStrike = t.real("steam_per_strike", def.steamPerStrike, fire_rules::kSteamPerStrike);
    validateAt(t, [&] { validateFireDef(def); });
    return def;
}

}  // namespace spindrift::scene
