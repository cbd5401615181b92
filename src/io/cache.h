// Particle caches: one file per emitter (and per fluid, and one for the rigid
// bodies) per dumped step, for Houdini, Blender, ParaView, MeshLab, pandas or
// a spreadsheet to load.
#pragma once

#include <spindrift/world.h>

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace spindrift::io {

enum class CacheFormat : std::uint32_t {
    Csv = 0,  ///< text, every attribute, floats that round-trip exactly
    Ply = 1,  ///< binary little-endian point cloud for 3D tools
};

/// "csv" or "ply".
std::string_view cacheExtension(CacheFormat format);

/// "<emitter>_<step, at least 6 digits>.<ext>". Characters of the emitter name
/// outside [A-Za-z0-9._-] become '_' so any name gives one safe file name; an
/// empty name becomes "emitter".
std::string cacheFileName(std::string_view emitterName, std::uint64_t step, CacheFormat format);

/// Throws spindrift::Error unless every attribute the caches write (all but
/// `slot`) has count() entries.
void checkSnapshot(const ParticleSnapshot& particles);

/// CSV columns, in order.
inline constexpr std::string_view kCsvHeader =
    "x,y,z,vx,vy,vz,age,lifetime,size,rotation,r,g,b,a,birth";

/// Header row, then one row per particle in snapshot order.
void writeCsv(std::ostream& out, const ParticleSnapshot& particles);

/// Appends `value` to `bytes` least significant byte first: PLY's
/// binary_little_endian whatever the host is.
void putLittleEndianFloat(std::vector<char>& bytes, float value);

/// PLY 1.0, binary_little_endian; vertex properties: float x y z vx vy vz age
/// size, uchar red green blue alpha. Colour is clamped to [0, 1] and encoded
/// sRGB (alpha stays linear) because the tools that read PLY treat byte colours
/// as display colours.
void writePly(std::ostream& out, const ParticleSnapshot& particles);

/// Writes `particles` to `path` in `format` atomically (see AtomicFile);
/// throws spindrift::Error on failure.
void writeCache(const std::filesystem::path& path, const ParticleSnapshot& particles,
                CacheFormat format);

/// Fluid cache CSV columns, in order: density is rho / rho0, pressure the
/// accumulated constraint impulse (m/s), id the creation serial.
inline constexpr std::string_view kFluidCsvHeader = "x,y,z,vx,vy,vz,density,pressure,id";

/// Header row, then one row per fluid particle in creation order.
void writeFluidCsv(std::ostream& out, const FluidSnapshot& particles);

/// PLY 1.0, binary_little_endian; vertex properties: float x y z vx vy vz
/// density pressure.
void writeFluidPly(std::ostream& out, const FluidSnapshot& particles);

/// Writes a fluid's particles to `path` atomically; throws spindrift::Error.
void writeFluidCache(const std::filesystem::path& path, const FluidSnapshot& particles, CacheFormat format);

/// Which state a body cache holds: after `step` steps (1-based, as "step" of
/// summary.json's per_step), at simulated time `time` (s).
struct BodyCacheStep {
    std::uint64_t step = 0;
    double time = 0.0;
};

/// Rigid body cache CSV columns, in order. Every row carries its step and
/// time, so the per-step files of a run concatenate into one table.
inline constexpr std::string_view kBodyCsvHeader = "step,time,id,name,x,y,angle,vx,vy,angular_velocity";

/// `text` as one CSV field: as it is, or in double quotes with its quotes
/// doubled (RFC 4180) when it holds a comma, a quote or a line break.
std::string csvField(std::string_view text);

/// Header row, then one row per body in the given (id) order.
void writeBodyCsv(std::ostream& out, const std::vector<BodySnapshot>& bodies, BodyCacheStep at);

/// PLY 1.0, binary_little_endian; one vertex per body with float x y z (z =
/// 0) angle vx vy angular_velocity and int id; the step, time and each body's
/// name in comment lines.
void writeBodyPly(std::ostream& out, const std::vector<BodySnapshot>& bodies, BodyCacheStep at);

/// Writes the bodies to `path` atomically; throws spindrift::Error.
void writeBodyCache(const std::filesystem::path& path, const std::vector<BodySnapshot>& bodies, BodyCacheStep at,
                    CacheFormat format);

}  // namespace spindrift::io
