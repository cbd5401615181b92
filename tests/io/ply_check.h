// A PLY 1.0 reader for tests, written from the format's description
// (paulbourke.net/dataformats/ply) and independently of src/io, so a test
// judges the writer's files as another program would: every element and
// property is taken from the header, in its declared type, and the data must
// fill the file exactly. Supports what the caches use: binary_little_endian,
// scalar properties of the eight PLY types (and their sized aliases int32,
// float32 ...), no list properties.
#pragma once

#include <bit>
#include <cstdint>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace spindrift_test {

struct PlyElement {
    std::string name;
    std::size_t count = 0;
    std::vector<std::pair<std::string, std::string>> properties;  ///< (type, name), in order
    std::map<std::string, std::vector<double>> values;           ///< per property, one per item
};

struct PlyFile {
    std::string format;                 ///< "binary_little_endian" (others are refused)
    std::string version;                ///< "1.0"
    std::vector<std::string> comments;  ///< text after "comment ", in order
    std::vector<PlyElement> elements;

    const PlyElement& element(const std::string& name) const {
        for (const PlyElement& e : elements) {
            if (e.name == name) return e;
        }
        throw std::runtime_error("no element " + name);
    }
};

namespace ply_detail {

/// Size in bytes of a PLY scalar type, or 0 for an unknown name.
inline std::size_t typeSize(const std::string& type) {
    static const std::map<std::string, std::size_t> kSizes{
        {"char", 1},  {"uchar", 1},  {"short", 2},  {"ushort", 2},  {"int", 4},     {"uint", 4},
        {"float", 4}, {"double", 8}, {"int8", 1},   {"uint8", 1},   {"int16", 2},   {"uint16", 2},
        {"int32", 4}, {"uint32", 4}, {"float32", 4}, {"float64", 8}};
    const auto it = kSizes.find(type);
    return it == kSizes.end() ? 0 : it->second;
}

/// One little-endian value of `type` at `bytes`, as a double.
inline double decode(const std::string& type, const unsigned char* bytes) {
    std::uint64_t raw = 0;
    const std::size_t size = typeSize(type);
    for (std::size_t k = size; k-- > 0;) raw = (raw << 8) | bytes[k];
    if (type == "float" || type == "float32") return std::bit_cast<float>(static_cast<std::uint32_t>(raw));
    if (type == "double" || type == "float64") return std::bit_cast<double>(raw);
    const bool isSigned = type == "char" || type == "short" || type == "int" || type == "int8" ||
                          type == "int16" || type == "int32";
    if (!isSigned) return static_cast<double>(raw);
    const unsigned shift = static_cast<unsigned>(64 - 8 * size);
    return static_cast<double>(static_cast<std::int64_t>(raw << shift) >> shift);
}

}  // namespace ply_detail

/// Parses a whole PLY file; throws std::runtime_error saying what is wrong.
inline PlyFile readPlyFile(const std::string& bytes) {
    PlyFile ply;
    std::size_t pos = 0;
    bool ended = false, first = true;
    while (!ended) {
        const std::size_t eol = bytes.find('\n', pos);
        if (eol == std::string::npos) throw std::runtime_error("header has no end_header line");
        const std::string line = bytes.substr(pos, eol - pos);
        pos = eol + 1;
        if (line.find('\r') != std::string::npos) throw std::runtime_error("CR in header line: " + line);
        for (char c : line) {
            if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) {
                throw std::runtime_error("header byte outside printable ASCII in: " + line);
            }
        }
        if (first) {
            if (line != "ply") throw std::runtime_error("the first line is not \"ply\"");
            first = false;
            continue;
        }
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "format") {
            words >> ply.format >> ply.version;
        } else if (keyword == "comment" || keyword == "obj_info") {
            if (keyword == "comment") ply.comments.push_back(line.size() > 8 ? line.substr(8) : std::string());
        } else if (keyword == "element") {
            PlyElement e;
            if (!(words >> e.name >> e.count)) throw std::runtime_error("bad element line: " + line);
            ply.elements.push_back(e);
        } else if (keyword == "property") {
            std::string type, name;
            if (!(words >> type >> name)) throw std::runtime_error("bad property line: " + line);
            if (type == "list") throw std::runtime_error("list properties are not supported here");
            if (ply_detail::typeSize(type) == 0) throw std::runtime_error("unknown property type " + type);
            if (ply.elements.empty()) throw std::runtime_error("property before any element: " + line);
            ply.elements.back().properties.emplace_back(type, name);
        } else if (keyword == "end_header") {
            ended = true;
        } else {
            throw std::runtime_error("unknown header keyword in: " + line);
        }
    }
    if (ply.version != "1.0") throw std::runtime_error("format version is not 1.0");
    if (ply.format == "binary_little_endian") {
        const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
        for (PlyElement& e : ply.elements) {
            for (std::size_t i = 0; i < e.count; ++i) {
                for (const auto& [type, name] : e.properties) {
                    const std::size_t size = ply_detail::typeSize(type);
                    if (pos + size > bytes.size()) throw std::runtime_error("data ends inside element " + e.name);
                    e.values[name].push_back(ply_detail::decode(type, data + pos));
                    pos += size;
                }
            }
        }
        if (pos != bytes.size()) {
            throw std::runtime_error(std::to_string(bytes.size() - pos) + " bytes after the last element");
        }
    } else {
        throw std::runtime_error("unsupported format " + ply.format);
    }
    return ply;
}

}  // namespace spindrift_test
