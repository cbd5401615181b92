// Plain-text data files referenced by scenes (flow fields, cube maps) and the
// file reading they share. Formats are documented in docs/scene-format.md.
#pragma once

#include <spindrift/effects.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace spindrift::scene {

/// Reads a whole regular file of at most `maxBytes` bytes; on failure
/// returns nullopt and sets `error` to the reason: the system's ("No such file
/// or directory"), not a regular file (a device such as /dev/zero, a pipe, a
/// directory: refused before reading), or larger than `maxBytes`.
std::optional<std::string> readWholeFile(const std::filesystem::path& path, std::size_t maxBytes,
                                         std::string& error);

/// A data file as errors name it: `display` is the path shown, `keyPath` the
/// scene key that referenced it.
struct DataFileRef {
    std::filesystem::path path;
    std::string display;
    std::string keyPath;
};

/// "spindrift-flow 1 nx ny nz minx miny minz maxx maxy maxz", then nx*ny*nz
/// lines "vx vy vz" (m/s), x fastest, then y, then z. Fills bounds, resolution
/// and velocities. Throws SceneError at the file's line and column.
void readFlowFile(const DataFileRef& ref, const std::string& text, FlowFieldDef& field);

/// "spindrift-cubemap 1 res", then 6 * res lines of res depths (m): faces
/// +x, -x, +y, -y, +z, -z, rows j = 0 .. res-1, u (i) fastest within a line.
/// Returns the depths in cubeTexelIndex() order and sets `res`.
std::vector<float> readCubeMapFile(const DataFileRef& ref, const std::string& text,
                                   std::uint32_t& res);

}  // namespace spindrift::scene
