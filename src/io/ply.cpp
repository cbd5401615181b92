// Binary PLY particle cache.
#include "io/cache.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace spindrift::io {

namespace {

// 8 floats + 4 bytes, packed: PLY has no padding between properties.
constexpr std::size_t kVertexBytes = 8 * 4 + 4;

double clamp01(float value) {
    // NaN compares false both ways and would survive std::clamp; make it black.
    if (!(value > 0.0f)) return 0.0;
    return std::min(static_cast<double>(value), 1.0);
}

char srgbByte(float linear) {
    // IEC 61966-2-1 transfer function: viewers show byte colours as sRGB.
    const double c = clamp01(linear);
    const double encoded = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return static_cast<char>(std::lround(255.0 * encoded));
}

char linearByte(float value) { return static_cast<char>(std::lround(255.0 * clamp01(value))); }

void putVertex(std::vector<char>& bytes, const ParticleSnapshot& p, std::size_t i) {
    const float floats[8] = {p.position[i].x, p.position[i].y, p.position[i].z, p.velocity[i].x,
                             p.velocity[i].y, p.velocity[i].z, p.age[i], p.size[i]};
    for (float f : floats) putLittleEndianFloat(bytes, f);
    const glm::vec4 c = p.color[i];
    bytes.push_back(srgbByte(c.r));
    bytes.push_back(srgbByte(c.g));
    bytes.push_back(srgbByte(c.b));
    bytes.push_back(linearByte(c.a));
}

std::string plyHeader(std::size_t count) {
    return fmt::format(
        "ply\n"
        "format binary_little_endian 1.0\n"
        "comment spindrift particle cache; colour is sRGB, alpha linear\n"
        "element vertex {}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property float vx\nproperty float vy\nproperty float vz\n"
        "property float age\nproperty float size\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
        "end_header\n",
        count);
}

}  // namespace

void writePly(std::ostream& out, const ParticleSnapshot& particles) {
    checkSnapshot(particles);
    const std::string header = plyHeader(particles.count());
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    // Vertices go out in blocks so memory stays bounded for huge emitters.
    constexpr std::size_t kBlock = 4096;
    std::vector<char> bytes;
    bytes.reserve(kBlock * kVertexBytes);
    for (std::size_t i = 0; i < particles.count(); ++i) {
        putVertex(bytes, particles, i);
        if (bytes.size() >= kBlock * kVertexBytes) {
            out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
            bytes.clear();
        }
    }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void putLittleEndianFloat(std::vector<char>& bytes, float value) {
    const auto bits = std::bit_cast<std::uint32_t>(value);
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<char>((bits >> shift) & 0xffu));
}

}  // namespace spindrift::io
