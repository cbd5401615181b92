#include "io/cache.h"

#include "io/atomic_file.h"

#include <fmt/format.h>

namespace spindrift::io {

namespace {

bool isSafeFileChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '.' || c == '_' || c == '-';
}

void checkSize(std::size_t size, std::size_t count, const char* attribute) {
    if (size == count) return;
    throw Error(fmt::format("particle snapshot: '{}' has {} entries, expected {} (one per particle)",
                            attribute, size, count));
}

}  // namespace

std::string_view cacheExtension(CacheFormat format) {
    return format == CacheFormat::Ply ? "ply" : "csv";
}

std::string cacheFileName(std::string_view emitterName, std::uint64_t step, CacheFormat format) {
    std::string name = emitterName.empty() ? std::string("emitter") : std::string(emitterName);
    for (char& c : name) {
        if (!isSafeFileChar(c)) c = '_';
    }
    // A leading dot would hide the file; ".." would name the parent directory.
    if (name.front() == '.') name.front() = '_';
    return fmt::format("{}_{:06}.{}", name, step, cacheExtension(format));
}

void checkSnapshot(const ParticleSnapshot& particles) {
    const std::size_t n = particles.count();
    checkSize(particles.velocity.size(), n, "velocity");
    checkSize(particles.age.size(), n, "age");
    checkSize(particles.lifetime.size(), n, "lifetime");
    checkSize(particles.size.size(), n, "size");
    checkSize(particles.rotation.size(), n, "rotation");
    checkSize(particles.color.size(), n, "color");
    checkSize(particles.birth.size(), n, "birth");
}

void writeCache(const std::filesystem::path& path, const ParticleSnapshot& particles,
                CacheFormat format) {
    checkSnapshot(particles);  // before creating anything on disk
    AtomicFile file(path);
    if (format == CacheFormat::Ply) {
        writePly(file.stream(), particles);
    } else {
        writeCsv(file.stream(), particles);
    }
    file.commit();
}

}  // namespace spindrift::io
