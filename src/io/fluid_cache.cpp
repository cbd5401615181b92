// Fluid particle caches: position and velocity as the effect caches, plus the
// solver's density (rho / rho0) and pressure (accumulated impulse, m/s), the
// columns a renderer sizes and shades splats by (slides 56-68).
#include "io/atomic_file.h"
#include "io/cache.h"

#include <fmt/format.h>

#include <iterator>
#include <vector>

namespace spindrift::io {

namespace {

void checkFluid(const FluidSnapshot& p) {
    const std::size_t n = p.count();
    if (p.velocity.size() != n || p.density.size() != n || p.pressure.size() != n || p.id.size() != n) {
        throw Error("fluid snapshot: every attribute must have one entry per particle");
    }
}

}  // namespace

void writeFluidCsv(std::ostream& out, const FluidSnapshot& p) {
    checkFluid(p);
    fmt::memory_buffer buffer;
    fmt::format_to(std::back_inserter(buffer), "{}\n", kFluidCsvHeader);
    for (std::size_t i = 0; i < p.count(); ++i) {
        // "{}" is the shortest text that reads back to the same float.
        fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{},{},{},{}\n", p.position[i].x, p.position[i].y,
                       p.position[i].z, p.velocity[i].x, p.velocity[i].y, p.velocity[i].z, p.density[i],
                       p.pressure[i], p.id[i]);
        if (buffer.size() >= (1u << 16)) {
            out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
            buffer.clear();
        }
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
}

void writeFluidPly(std::ostream& out, const FluidSnapshot& p) {
    checkFluid(p);
    const std::string header = fmt::format(
        "ply\n"
        "format binary_little_endian 1.0\n"
        "comment spindrift fluid cache; density is rho / rho0, pressure the accumulated impulse (m/s)\n"
        "element vertex {}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float vx\nproperty float vy\nproperty float vz\n"
        "property float density\nproperty float pressure\n"
        "end_header\n",
        p.count());
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    std::vector<char> bytes;
    bytes.reserve(p.count() * 32);
    for (std::size_t i = 0; i < p.count(); ++i) {
        for (float f : {p.position[i].x, p.position[i].y, p.position[i].z, p.velocity[i].x, p.velocity[i].y,
                        p.velocity[i].z, p.density[i], p.pressure[i]}) {
            putLittleEndianFloat(bytes, f);
        }
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void writeFluidCache(const std::filesystem::path& path, const FluidSnapshot& particles, CacheFormat format) {
    checkFluid(particles);
    AtomicFile file(path);
    if (format == CacheFormat::Ply) {
        writeFluidPly(file.stream(), particles);
    } else {
        writeFluidCsv(file.stream(), particles);
    }
    file.commit();
}

}  // namespace spindrift::io
