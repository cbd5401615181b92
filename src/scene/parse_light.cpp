// [[light]]: a point light, fixed or following an emitter's spawn centre
// (include/spindrift/render.h, LightDef).
#include "render/render_rules.h"
#include "scene/parse_internal.h"

namespace spindrift::scene {

LightDef parseLight(const Table& t, NameTable& names, const NameTable& emitters) {
    t.allowOnly({"name", "position", "color", "radius", "emitter", "flicker"}, "a [[light]]");
    LightDef def;
    def.name = names.add(t);
    def.position = t.vec3("position", def.position);
    def.colour = t.vec3("color", def.colour);
    // Type checks here; the ranges are validateLightDef's, checked once.
    def.radius = t.real("radius", def.radius, render_rules::kLightRadius);
    def.flicker = t.real("flicker", def.flicker, render_rules::kLightFlicker);
    if (auto v = t.find("emitter")) def.emitter = EmitterId{emitters.resolve(*v) + 1};
    validateAt(t, [&] { validateLightDef(def); });
    return def;
}

}  // namespace spindrift::scene
