// Rigid body caches: each body's transform and velocities after a step, one
// row (CSV) or one vertex (PLY) per body, so tools that already load the
// particle caches can place and animate the bodies beside them.
#include "io/atomic_file.h"
#include "io/cache.h"

#include <fmt/format.h>

#include <iterator>
#include <vector>

namespace spindrift::io {

namespace {

// 7 floats + 1 int32, packed: PLY has no padding between properties.
constexpr std::size_t kBodyVertexBytes = 7 * 4 + 4;

/// A body name as a PLY comment can hold it: the header is ASCII lines, so a
/// line break would end the comment and other bytes may upset a reader. The
/// CSV keeps the exact name.
std::string commentText(std::string_view name) {
    std::string text(name);
    for (char& c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte >= 0x7f) c = '_';
    }
    return text;
}

void putLittleEndianInt(std::vector<char>& bytes, std::uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((value >> shift) & 0xffu));
}

}  // namespace

std::string csvField(std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
    std::string quoted = "\"";
    for (char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    quoted += '"';
    return quoted;
}

void writeBodyCsv(std::ostream& out, const std::vector<BodySnapshot>& bodies, BodyCacheStep at) {
    fmt::memory_buffer buffer;
    fmt::format_to(std::back_inserter(buffer), "{}\n", kBodyCsvHeader);
    for (const BodySnapshot& b : bodies) {
        // "{}" is the shortest text that reads back to the same float (time:
        // the same double), as in the particle caches and summary.json.
        fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{},{},{},{},{}\n", at.step, at.time, b.id.index,
                       csvField(b.name), b.position.x, b.position.y, b.angle, b.linearVelocity.x,
                       b.linearVelocity.y, b.angularVelocity);
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

void writeBodyPly(std::ostream& out, const std::vector<BodySnapshot>& bodies, BodyCacheStep at) {
    fmt::memory_buffer header;
    fmt::format_to(std::back_inserter(header),
                   "ply\n"
                   "format binary_little_endian 1.0\n"
                   "comment spindrift rigid body cache: body origins in the xy plane, angle in rad, velocity of "
                   "the centre of mass\n"
                   "comment step {} time {}\n",
                   at.step, at.time);
    for (const BodySnapshot& b : bodies) {
        fmt::format_to(std::back_inserter(header), "comment body {} {}\n", b.id.index, commentText(b.name));
    }
    fmt::format_to(std::back_inserter(header),
                   "element vertex {}\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   "property float angle\n"
                   "property float vx\nproperty float vy\n"
                   "property float angular_velocity\n"
                   "property int id\n"
                   "end_header\n",
                   bodies.size());
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    std::vector<char> bytes;
    bytes.reserve(bodies.size() * kBodyVertexBytes);
    for (const BodySnapshot& b : bodies) {
        for (float f : {b.position.x, b.position.y, 0.0f, b.angle, b.linearVelocity.x, b.linearVelocity.y,
                        b.angularVelocity}) {
            putLittleEndianFloat(bytes, f);
        }
        putLittleEndianInt(bytes, b.id.index);
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void writeBodyCache(const std::filesystem::path& path, const std::vector<BodySnapshot>& bodies, BodyCacheStep at,
                    CacheFormat format) {
    AtomicFile file(path);
    if (format == CacheFormat::Ply) {
        writeBodyPly(file.stream(), bodies, at);
    } else {
        writeBodyCsv(file.stream(), bodies, at);
    }
    file.commit();
}

}  // namespace spindrift::io
