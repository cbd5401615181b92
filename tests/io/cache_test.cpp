// Particle caches: written by src/io, read back here by independent readers.
#include "io/cache.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using spindrift::ParticleSnapshot;
using spindrift::io::CacheFormat;

/// A fresh directory per test, removed afterwards.
class TempDir {
public:
    TempDir() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() /
                ("spindrift-io-" + std::to_string(::getpid()) + "-" + test->test_suite_name() + "-" + test->name());
        fs::remove_all(path_);
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

/// Floats chosen to break naive printing: values with no short decimal form,
/// subnormals, the extremes, negative zero, numbers next to round ones.
std::vector<float> awkwardFloats() {
    constexpr auto lim = std::numeric_limits<float>::max;
    return {0.1f, -0.0f, 0.0f, 1.0f / 3.0f, std::numeric_limits<float>::denorm_min(),
            std::numeric_limits<float>::min(), lim(), -lim(), std::nextafter(1.0f, 2.0f),
            16777217.0f, 123456.789f, -2.5e-7f, 3.14159265f, 1e-38f, 9.999999e37f, -1.0f};
}

ParticleSnapshot makeParticles(std::size_t n) {
    const std::vector<float> f = awkwardFloats();
    const auto at = [&](std::size_t k) { return f[k % f.size()]; };
    ParticleSnapshot p;
    for (std::size_t i = 0; i < n; ++i) {
        p.position.push_back({at(i), at(i + 1), at(i + 2)});
        p.velocity.push_back({at(i + 3), at(i + 4), at(i + 5)});
        p.age.push_back(at(i + 6));
        p.lifetime.push_back(at(i + 7));
        p.size.push_back(at(i + 8));
        p.rotation.push_back(at(i + 9));
        p.color.push_back({at(i + 10), at(i + 11), at(i + 12), at(i + 13)});
        p.birth.push_back(i == 0 ? std::numeric_limits<std::uint32_t>::max() : static_cast<std::uint32_t>(i * 7919));
        p.slot.push_back(static_cast<std::uint32_t>(i));
    }
    return p;
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        if (i == text.size() || text[i] == separator) {
            parts.push_back(text.substr(start, i - start));
            start = i + 1;
        }
    }
    return parts;
}

float parseFloat(const std::string& field) {
    char* end = nullptr;
    const float value = std::strtof(field.c_str(), &end);
    EXPECT_TRUE(!field.empty() && *end == '\0') << "not a number: '" << field << "'";
    return value;
}

::testing::AssertionResult sameBits(float expected, float actual) {
    if (std::bit_cast<std::uint32_t>(expected) == std::bit_cast<std::uint32_t>(actual)) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "expected " << expected << " got " << actual;
}

/// The values of row i in the column order the CSV promises.
std::vector<float> expectedRow(const ParticleSnapshot& p, std::size_t i) {
    return {p.position[i].x, p.position[i].y, p.position[i].z, p.velocity[i].x, p.velocity[i].y,
            p.velocity[i].z, p.age[i], p.lifetime[i], p.size[i], p.rotation[i],
            p.color[i].r, p.color[i].g, p.color[i].b, p.color[i].a};
}

// CSV ----------------------------------------------------------------------------

TEST(IoCsv, RoundTripsEveryValueBitExactly) {
    TempDir dir;
    const ParticleSnapshot particles = makeParticles(40);
    const fs::path file = dir.path() / "sparks_000010.csv";
    spindrift::io::writeCache(file, particles, CacheFormat::Csv);

    std::vector<std::string> lines = split(readFile(file), '\n');
    ASSERT_EQ(lines.back(), "") << "file must end with a newline";
    lines.pop_back();
    ASSERT_EQ(lines.size(), particles.count() + 1);
    EXPECT_EQ(lines[0], "x,y,z,vx,vy,vz,age,lifetime,size,rotation,r,g,b,a,birth");
    for (std::size_t i = 0; i < particles.count(); ++i) {
        const std::vector<std::string> fields = split(lines[i + 1], ',');
        ASSERT_EQ(fields.size(), 15u) << "row " << i;
        const std::vector<float> expected = expectedRow(particles, i);
        for (std::size_t k = 0; k < expected.size(); ++k) {
            EXPECT_TRUE(sameBits(expected[k], parseFloat(fields[k]))) << "row " << i << " column " << k;
        }
        EXPECT_EQ(std::stoull(fields[14]), particles.birth[i]) << "row " << i;
    }
}

TEST(IoCsv, EmptySnapshotGivesHeaderOnly) {
    std::ostringstream out;
    spindrift::io::writeCsv(out, ParticleSnapshot{});
    EXPECT_EQ(out.str(), "x,y,z,vx,vy,vz,age,lifetime,size,rotation,r,g,b,a,birth\n");
}

TEST(IoCsv, LargeSnapshotHasEveryRow) {
    // More than one internal block of output.
    const ParticleSnapshot particles = makeParticles(5000);
    std::ostringstream out;
    spindrift::io::writeCsv(out, particles);
    const std::vector<std::string> lines = split(out.str(), '\n');
    ASSERT_EQ(lines.size(), particles.count() + 2);  // header, rows, "" after the last newline
    const std::vector<std::string> last = split(lines[particles.count()], ',');
    EXPECT_EQ(std::stoull(last[14]), particles.birth.back());
}

// Writing safely ------------------------------------------------------------------

TEST(IoCache, MismatchedSnapshotIsRejectedBeforeWriting) {
    TempDir dir;
    ParticleSnapshot particles = makeParticles(3);
    particles.birth.pop_back();
    const fs::path file = dir.path() / "bad.csv";
    EXPECT_THROW(spindrift::io::writeCache(file, particles, CacheFormat::Csv), spindrift::Error);
    EXPECT_TRUE(fs::is_empty(dir.path())) << "nothing may be left behind";
}

TEST(IoCache, UnwritableDirectoryThrowsAndLeavesNoFile) {
    TempDir dir;
    const fs::path file = dir.path() / "missing" / "x.csv";
    EXPECT_THROW(spindrift::io::writeCache(file, makeParticles(2), CacheFormat::Ply), spindrift::Error);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(IoCache, ReplacesAnOldFileAndLeavesNoTemporary) {
    TempDir dir;
    const fs::path file = dir.path() / "a.csv";
    spindrift::io::writeCache(file, makeParticles(10), CacheFormat::Csv);
    spindrift::io::writeCache(file, makeParticles(2), CacheFormat::Csv);
    EXPECT_EQ(split(readFile(file), '\n').size(), 4u);  // header, 2 rows, ""
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir.path())) names.push_back(entry.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"a.csv"});
}

TEST(IoCache, FileNamesAreSafeAndNumbered) {
    using spindrift::io::cacheFileName;
    EXPECT_EQ(cacheFileName("sparks", 10, CacheFormat::Csv), "sparks_000010.csv");
    EXPECT_EQ(cacheFileName("sparks", 1234567, CacheFormat::Ply), "sparks_1234567.ply");
    EXPECT_EQ(cacheFileName("fire/smoke ok", 0, CacheFormat::Csv), "fire_smoke_ok_000000.csv");
    EXPECT_EQ(cacheFileName("..", 1, CacheFormat::Csv), "_._000001.csv");
    EXPECT_EQ(cacheFileName("", 2, CacheFormat::Csv), "emitter_000002.csv");
}

// PLY -----------------------------------------------------------------------------

/// What the test's own PLY reader found: header facts and every property of
/// every vertex, as doubles, by property name.
struct PlyData {
    std::string format;
    std::size_t vertexCount = 0;
    std::vector<std::pair<std::string, std::string>> properties;  // (type, name)
    std::map<std::string, std::vector<double>> values;
    std::size_t trailingBytes = 0;
};

std::uint32_t littleEndian32(const std::string& bytes, std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(k)]);
    return v;
}

/// Header: ASCII lines up to "end_header"; only the keywords the writer may use.
std::size_t readPlyHeader(const std::string& bytes, PlyData& ply) {
    std::size_t pos = 0;
    std::vector<std::string> lines;
    for (;;) {
        const std::size_t eol = bytes.find('\n', pos);
        if (eol == std::string::npos) throw std::runtime_error("no end_header");
        lines.push_back(bytes.substr(pos, eol - pos));
        pos = eol + 1;
        if (lines.back() == "end_header") break;
    }
    if (lines.front() != "ply") throw std::runtime_error("missing magic");
    for (const std::string& line : lines) {
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "format") std::getline(words >> std::ws, ply.format);
        if (keyword == "element") {
            std::string name;
            words >> name >> ply.vertexCount;
            if (name != "vertex") throw std::runtime_error("unexpected element " + name);
        }
        if (keyword == "property") {
            std::string type, name;
            words >> type >> name;
            ply.properties.emplace_back(type, name);
        }
    }
    return pos;
}

PlyData readPly(const fs::path& path) {
    const std::string bytes = readFile(path);
    PlyData ply;
    std::size_t pos = readPlyHeader(bytes, ply);
    for (std::size_t v = 0; v < ply.vertexCount; ++v) {
        for (const auto& [type, name] : ply.properties) {
            if (type == "float") {
                if (pos + 4 > bytes.size()) throw std::runtime_error("file too short");
                ply.values[name].push_back(std::bit_cast<float>(littleEndian32(bytes, pos)));
                pos += 4;
            } else if (type == "uchar") {
                if (pos + 1 > bytes.size()) throw std::runtime_error("file too short");
                ply.values[name].push_back(static_cast<unsigned char>(bytes[pos]));
                pos += 1;
            } else {
                throw std::runtime_error("unexpected type " + type);
            }
        }
    }
    ply.trailingBytes = bytes.size() - pos;
    return ply;
}

TEST(IoPly, HeaderDeclaresBinaryLittleEndianVertices) {
    TempDir dir;
    const fs::path file = dir.path() / "p.ply";
    spindrift::io::writeCache(file, makeParticles(7), CacheFormat::Ply);
    const PlyData ply = readPly(file);
    EXPECT_EQ(ply.format, "binary_little_endian 1.0");
    EXPECT_EQ(ply.vertexCount, 7u);
    const std::vector<std::pair<std::string, std::string>> expected{
        {"float", "x"}, {"float", "y"}, {"float", "z"}, {"float", "vx"}, {"float", "vy"},
        {"float", "vz"}, {"float", "age"}, {"float", "size"}, {"uchar", "red"},
        {"uchar", "green"}, {"uchar", "blue"}, {"uchar", "alpha"}};
    EXPECT_EQ(ply.properties, expected);
    EXPECT_EQ(ply.trailingBytes, 0u);
}

TEST(IoPly, RoundTripsFloatsBitExactly) {
    TempDir dir;
    const ParticleSnapshot p = makeParticles(33);
    const fs::path file = dir.path() / "p.ply";
    spindrift::io::writeCache(file, p, CacheFormat::Ply);
    const PlyData ply = readPly(file);
    ASSERT_EQ(ply.vertexCount, p.count());
    for (std::size_t i = 0; i < p.count(); ++i) {
        const float expected[] = {p.position[i].x, p.position[i].y, p.position[i].z, p.velocity[i].x,
                                  p.velocity[i].y, p.velocity[i].z, p.age[i], p.size[i]};
        const char* names[] = {"x", "y", "z", "vx", "vy", "vz", "age", "size"};
        for (int k = 0; k < 8; ++k) {
            EXPECT_TRUE(sameBits(expected[k], static_cast<float>(ply.values.at(names[k])[i])))
                << "vertex " << i << " " << names[k];
        }
    }
}

TEST(IoPly, ColoursAreSrgbBytesAndAlphaLinear) {
    // Expected bytes worked out by hand from the sRGB transfer function
    // (IEC 61966-2-1), e.g. linear 0.5 -> 0.7354 -> 187.5 -> 188.
    struct Case { float linear; double srgb; float alpha; double alphaByte; };
    const Case cases[] = {{0.0f, 0, 0.0f, 0},      {1.0f, 255, 1.0f, 255}, {0.5f, 188, 0.25f, 64},
                          {0.2f, 124, 0.75f, 191}, {0.001f, 3, 0.6f, 153}, {2.0f, 255, 7.0f, 255},
                          {-1.0f, 0, -0.5f, 0},    {std::nanf(""), 0, std::nanf(""), 0}};
    ParticleSnapshot p = makeParticles(std::size(cases));
    for (std::size_t i = 0; i < std::size(cases); ++i) {
        p.color[i] = {cases[i].linear, cases[i].linear, cases[i].linear, cases[i].alpha};
    }
    TempDir dir;
    const fs::path file = dir.path() / "c.ply";
    spindrift::io::writeCache(file, p, CacheFormat::Ply);
    const PlyData ply = readPly(file);
    for (std::size_t i = 0; i < std::size(cases); ++i) {
        EXPECT_EQ(ply.values.at("red")[i], cases[i].srgb) << "case " << i;
        EXPECT_EQ(ply.values.at("green")[i], cases[i].srgb) << "case " << i;
        EXPECT_EQ(ply.values.at("blue")[i], cases[i].srgb) << "case " << i;
        EXPECT_EQ(ply.values.at("alpha")[i], cases[i].alphaByte) << "case " << i;
    }
}

TEST(IoPly, EmptySnapshotIsAValidFile) {
    TempDir dir;
    const fs::path file = dir.path() / "e.ply";
    spindrift::io::writeCache(file, ParticleSnapshot{}, CacheFormat::Ply);
    const PlyData ply = readPly(file);
    EXPECT_EQ(ply.vertexCount, 0u);
    EXPECT_EQ(ply.trailingBytes, 0u);
}

}  // namespace
