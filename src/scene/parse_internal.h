// Shared by the parsers of the scene's parts (scene_parse.cpp, parse_*.cpp).
#pragma once

#include "scene/data_files.h"
#include "scene/toml_read.h"

#include <spindrift/fires.h>
#include <spindrift/scene.h>

#include <cstdint>
#include <map>
#include <string>

namespace spindrift::scene {

/// The names of one kind of object ("force", "collider" ...): unique per kind,
/// and what references in other objects resolve against.
class NameTable {
public:
    explicit NameTable(std::string kind) : kind_(std::move(kind)) {}

    /// Reads the required `name` of the next object of this kind and records it.
    std::string add(const Table& table);
    /// 0-based creation index of the object `reference` (a string) names.
    std::uint32_t resolve(const Value& reference) const;
    std::size_t size() const { return entries_.size(); }

private:
    struct Entry {
        std::uint32_t index;
        std::uint32_t line;
    };
    std::string kind_;
    std::map<std::string, Entry, std::less<>> entries_;
};

/// Reads a data file named by a string value (relative to the scene's
/// directory). A file that cannot be read is an error at the value.
std::string readDataFile(const Value& value, DataFileRef& ref);
/// A PNG named by a string value (sprite texture, background image): read
/// and checked now, so a missing or broken file is an error at the value and
/// not a failure mid-render. Returns the resolved path.
std::string readPngPath(const Value& value);
/// `texture` and `texture_scale` of a [[collider]] or [[body]] (the scale's
/// type only; its range is the Def validator's).
SurfaceTexture readSurfaceTexture(const Table& table);

/// Refuses a generated field whose cost (noise evaluations, see
/// kMaxNoiseEvaluations) is over the limit, before it is generated: at
/// `octaves` if given, else at `resolution`, else at the table. `what`
/// describes the field ("curl noise of 512 x 512 x 16 samples").
void checkNoiseCost(const Table& table, std::uint64_t evaluations, const std::string& what);

FlowFieldDef parseFlowField(const Table& table, NameTable& names);
ForceDef parseForce(const Table& table, NameTable& names, const NameTable& flowFields);
ColliderDef parseCollider(const Table& table, NameTable& names);
/// `bodies`: the names jets may ride on.
FluidDef parseFluid(const Table& table, NameTable& names, const NameTable& bodies);
BodyDef parseBody(const Table& table, NameTable& names);
JointDef parseJoint(const Table& table, NameTable& names, const NameTable& bodies);
FireDef parseFire(const Table& table, NameTable& names, const NameTable& bodies, const NameTable& emitters);
/// `emitters`: the names a light may follow.
LightDef parseLight(const Table& table, NameTable& names, const NameTable& emitters);
/// [render] with its [render.background] and [render.fluid]; the camera is
/// left at its default ([camera] is read separately).
RenderDef parseRender(const Table& table);
/// `earlier`: the emitters read before this one (a sub-emitter's parent is
/// one of them).
EmitterDef parseEmitter(const Table& table, NameTable& names, const NameTable& forces,
                        const NameTable& colliders, const NameTable& bodies, const std::vector<EmitterDef>& earlier);

}  // namespace spindrift::scene
