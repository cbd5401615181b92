// CSV particle cache.
#include "io/cache.h"

#include <fmt/format.h>

#include <iterator>

namespace spindrift::io {

namespace {

// Rows are formatted into memory and written in blocks: one ostream call per
// value would dominate the cost of a million-particle dump.
constexpr std::size_t kFlushBytes = 1 << 16;

void flush(std::ostream& out, fmt::memory_buffer& buffer) {
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    buffer.clear();
}

void appendRow(fmt::memory_buffer& buffer, const ParticleSnapshot& p, std::size_t i) {
    // fmt's "{}" prints the shortest text that parses back to the same float
    // (Dragonbox), so a cache reloads bit-exactly without 9-digit noise.
    const glm::vec3 x = p.position[i];
    const glm::vec3 v = p.velocity[i];
    const glm::vec4 c = p.color[i];
    fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
                   x.x, x.y, x.z, v.x, v.y, v.z, p.age[i], p.lifetime[i], p.size[i],
                   p.rotation[i], c.r, c.g, c.b, c.a, p.birth[i]);
}

}  // namespace

void writeCsv(std::ostream& out, const ParticleSnapshot& particles) {
    checkSnapshot(particles);
    fmt::memory_buffer buffer;
    fmt::format_to(std::back_inserter(buffer), "{}\n", kCsvHeader);
    for (std::size_t i = 0; i < particles.count(); ++i) {
        appendRow(buffer, particles, i);
        if (buffer.size() >= kFlushBytes) flush(out, buffer);
    }
    flush(out, buffer);
}

}  // namespace spindrift::io
