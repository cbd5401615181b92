// spindrift public API: scene files (TOML) and building a world from them.
#pragma once

#include <spindrift/export.h>

#include <spindrift/bodies.h>
#include <spindrift/fires.h>
#include <spindrift/render.h>
#include <spindrift/world.h>

#include <string>
#include <string_view>
#include <vector>

namespace spindrift {

/// A scene file was rejected. what() reads "file:line:col: key.path: message";
/// the parts are also available separately.
class SPINDRIFT_API SceneError : public Error {
public:
    SceneError(std::string file, int line, int column, std::string keyPath, std::string message);
    const std::string& file() const { return file_; }
    int line() const { return line_; }
    int column() const { return column_; }
    const std::string& keyPath() const { return keyPath_; }
    const std::string& message() const { return message_; }

private:
    std::string file_;
    int line_;
    int column_;
    std::string keyPath_;
    std::string message_;
};

struct RunDef {
    float dt = 1.0f / 60.0f;    ///< s
    std::uint32_t steps = 300;  ///< default length of `spindrift run`
};

/// Everything a scene file describes. References between objects (an emitter's
/// forces and colliders, a force's flow field) are stored as the ids that
/// buildWorld() will give them: 1-based creation order per kind.
struct SceneDef {
    std::string source;  ///< file the scene came from
    WorldDef world;
    /// [camera] and [render]: how `spindrift render` and the viewer draw it.
    RenderDef render;
    RunDef run;
    std::vector<FlowFieldDef> flowFields;
    std::vector<ForceDef> forces;
    std::vector<ColliderDef> colliders;
    std::vector<EmitterDef> emitters;
    std::vector<FluidDef> fluids;
    std::vector<BodyDef> bodies;
    /// Bodies referred to by id (1-based position in `bodies`).
    std::vector<JointDef> joints;
    std::vector<FireDef> fires;
};

/// Parses and validates a scene file; throws SceneError on the first problem,
/// before anything is built. Relative data paths resolve against the file.
SPINDRIFT_API SceneDef loadScene(const std::string& path);
/// Same, from text in memory; `sourceName` is used in error messages and
/// `baseDir` to resolve relative data paths.
SPINDRIFT_API SceneDef parseScene(std::string_view text, const std::string& sourceName,
                                  const std::string& baseDir = ".");

/// Creates a world with flow fields, forces, colliders, emitters, bodies,
/// fluids (whose jets may ride on bodies), joints and fires in that order, so their
/// ids match the SceneDef's references.
SPINDRIFT_API WorldId buildWorld(const SceneDef& scene);

}  // namespace spindrift
