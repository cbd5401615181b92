// [[force]]: gravity, wind, attractors, repulsors, vortices, damping,
// undamping, flow-field drag and animated curl noise.
//
// Values are read with type checks only; their ranges are validateForceDef's
// rules (src/particles/force_rules.h), checked once through validateAt. What
// is checked here is what only a file says: a repulsor is an attractor with
// its strength negated, so both strengths are written >= 0.
#include "particles/force_rules.h"
#include "particles/params.h"
#include "scene/parse_internal.h"

#include <fmt/format.h>

namespace spindrift::scene {

namespace {

// "repulsor" is an attractor with its strength negated: files say what they
// mean and keep strengths positive.
enum class ForceName { Gravity, Wind, Attractor, Repulsor, Vortex, Damping, Undamping, Flow, CurlNoise };

ForceName readKind(const Table& t) {
    return t
        .require("kind",
                 "a force kind: \"gravity\", \"wind\", \"attractor\", "
                 "\"repulsor\", \"vortex\", \"damping\", \"undamping\", "
                 "\"flow_field\" or \"curl_noise\"")
        .choice<ForceName>({{"gravity", ForceName::Gravity},
                            {"wind", ForceName::Wind},
                            {"attractor", ForceName::Attractor},
                            {"repulsor", ForceName::Repulsor},
                            {"vortex", ForceName::Vortex},
                            {"damping", ForceName::Damping},
                            {"undamping", ForceName::Undamping},
                            {"flow_field", ForceName::Flow},
                            {"curl_noise", ForceName::CurlNoise}});
}

std::vector<std::string_view> allowedKeys(ForceName kind) {
    std::vector<std::string_view> keys = {"name", "kind"};
    switch (kind) {
        case ForceName::Gravity:
            keys.push_back("acceleration");
            break;
        case ForceName::Wind:
            keys.insert(keys.end(), {"velocity", "strength"});
            break;
        case ForceName::Attractor:
        case ForceName::Repulsor:
            keys.insert(keys.end(), {"position", "strength", "radius", "falloff", "range"});
            break;
        case ForceName::Vortex:
            keys.insert(keys.end(), {"position", "axis", "strength", "radius", "falloff", "range"});
            break;
        case ForceName::Damping:
            keys.insert(keys.end(), {"strength", "position", "range"});
            break;
        case ForceName::Undamping:
            keys.insert(keys.end(), {"strength", "target_speed", "position", "range"});
            break;
        case ForceName::Flow:
            keys.insert(keys.end(), {"field", "viscosity"});
            break;
        case ForceName::CurlNoise:
            keys.insert(keys.end(), {"strength", "frequency", "speed", "octaves", "seed", "viscosity"});
            break;
    }
    return keys;
}

ForceKind apiKind(ForceName kind) {
    switch (kind) {
        case ForceName::Gravity:
            return ForceKind::Gravity;
        case ForceName::Wind:
            return ForceKind::Wind;
        case ForceName::Attractor:
        case ForceName::Repulsor:
            return ForceKind::Attractor;
        case ForceName::Vortex:
            return ForceKind::Vortex;
        case ForceName::Damping:
            return ForceKind::Damping;
        case ForceName::Undamping:
            return ForceKind::Undamping;
        case ForceName::Flow:
            return ForceKind::FlowField;
        case ForceName::CurlNoise:
            return ForceKind::CurlNoise;
    }
    return ForceKind::Gravity;
}

// Position, radius, falloff and range of the distance law of attractors,
// repulsors and vortices: |F| = strength (radius / d)^falloff within range.
void readFalloffLaw(const Table& t, ForceDef& def) {
    def.position = t.vec3("position", def.position);
    def.radius = t.real("radius", def.radius, force_rules::kRadius);
    def.falloff = t.real("falloff", def.falloff, force_rules::kFalloff);
    def.range = t.real("range", def.range, force_rules::kRange);
}

void readAttractor(const Table& t, ForceDef& def, bool repulsor) {
    readFalloffLaw(t, def);
    if (auto v = t.find("strength")) {
        if (!v->node().is_number() || v->number() < 0.0) {
            v->failExpected(repulsor ? "a number >= 0 (N); a repulsor always pushes away"
                                     : "a number >= 0 (N); use kind = \"repulsor\" to push away");
        }
        def.strength = v->real();
    }
    def.strength = repulsor ? -def.strength : def.strength;
}

void readKindFields(const Table& t, ForceName kind, ForceDef& def, const NameTable& flowFields) {
    switch (kind) {
        case ForceName::Gravity:
            def.vector = t.vec3("acceleration", def.vector);
            break;
        case ForceName::Wind:
            def.vector = t.require("velocity", "[vx, vy, vz] (m/s)").vec3();
            def.strength = t.real("strength", def.strength, force_rules::kRate);
            break;
        case ForceName::Attractor:
            readAttractor(t, def, false);
            break;
        case ForceName::Repulsor:
            readAttractor(t, def, true);
            break;
        case ForceName::Vortex:
            readFalloffLaw(t, def);
            def.axis = t.direction("axis", def.axis);
            def.strength = t.real("strength", def.strength, force_rules::kStrength);
            break;
        case ForceName::Undamping:
            def.targetSpeed = t.real("target_speed", def.targetSpeed, force_rules::kTargetSpeed);
            [[fallthrough]];
        case ForceName::Damping:
            def.strength = t.real("strength", def.strength, force_rules::kRate);
            def.position = t.vec3("position", def.position);
            def.range = t.real("range", def.range, force_rules::kRange);
            break;
        case ForceName::Flow: {
            const Value field = t.require("field", "the name of a [[flow_field]]");
            def.flowField = FlowFieldId{flowFields.resolve(field) + 1};
            def.viscosity = t.real("viscosity", def.viscosity, force_rules::kViscosity);
            break;
        }
        case ForceName::CurlNoise:
            def.strength = t.real("strength", def.strength, force_rules::kNoiseStrength);
            def.frequency = t.real("frequency", def.frequency, force_rules::kFrequency);
            def.speed = t.real("speed", def.speed, force_rules::kSpeed);
            def.octaves = t.whole("octaves", def.octaves, force_rules::kOctaves);
            def.seed = t.whole("seed", def.seed, force_rules::kSeed);
            def.viscosity = t.real("viscosity", def.viscosity, force_rules::kViscosity);
            break;
    }
}

}  // namespace

ForceDef parseForce(const Table& t, NameTable& names, const NameTable& flowFields) {
    const ForceName kind = readKind(t);
    t.allowOnly(allowedKeys(kind), fmt::format("a force of kind \"{}\"", t.find("kind")->string()));
    ForceDef def;
    def.name = names.add(t);
    def.kind = apiKind(kind);
    readKindFields(t, kind, def, flowFields);
    validateAt(t, [&] { validateForceDef(def); });
    return def;
}

}  // namespace spindrift::scene
