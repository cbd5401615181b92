// Rigid body caches: written by src/io, read back by the tests' own readers
// (tests/io/csv_check.h and tests/io/ply_check.h).
#include "io/cache.h"

#include "io/csv_check.h"
#include "io/ply_check.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

using spindrift::BodySnapshot;
using spindrift::io::BodyCacheStep;
using spindrift_test::PlyFile;
using spindrift_test::readCsv;
using spindrift_test::readPlyFile;

BodySnapshot body(std::uint32_t id, std::string name, glm::vec2 position, float angle, glm::vec2 velocity,
                  float spin) {
    BodySnapshot b;
    b.id = {id};
    b.name = std::move(name);
    b.position = position;
    b.angle = angle;
    b.linearVelocity = velocity;
    b.angularVelocity = spin;
    return b;
}

/// Values chosen to need every digit of a float, with names a CSV must quote.
std::vector<BodySnapshot> makeBodies() {
    return {body(1, "floor", {0.0f, -0.0f}, 0.0f, {0.0f, 0.0f}, 0.0f),
            body(2, "crate, big", {0.1f, 1.0f / 3.0f}, -0.7853982f, {1e-7f, -2.5f}, 3.4028235e38f),
            body(3, "say \"hi\"\nthere", {-12.345678f, 1e-38f}, 3.1415927f, {0.3f, 7.0f}, -0.1f)};
}

float parseFloat(const std::string& text) {
    char* end = nullptr;
    const float v = std::strtof(text.c_str(), &end);
    EXPECT_EQ(*end, '\0') << "not a number: " << text;
    return v;
}

bool sameBits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

std::string csvText(const std::vector<BodySnapshot>& bodies, BodyCacheStep at) {
    std::ostringstream out;
    spindrift::io::writeBodyCsv(out, bodies, at);
    return out.str();
}

std::string plyBytes(const std::vector<BodySnapshot>& bodies, BodyCacheStep at) {
    std::ostringstream out;
    spindrift::io::writeBodyPly(out, bodies, at);
    return out.str();
}

// CSV ---------------------------------------------------------------------------------

TEST(IoBodyCsv, TheTestReaderFollowsRfc4180) {
    using Rows = std::vector<std::vector<std::string>>;
    EXPECT_EQ(readCsv("a,b\n\"x, y\",\"say \"\"hi\"\"\"\n\"two\nlines\",\n"),
              (Rows{{"a", "b"}, {"x, y", "say \"hi\""}, {"two\nlines", ""}}));
    for (const char* bad : {"a,\"b\n", "a,b", "a,x\"y\"\n", "\"a\"b,c\n"}) {
        EXPECT_THROW(readCsv(bad), std::runtime_error) << bad;
    }
}

TEST(IoBodyCsv, OneRowPerBodyWithStepTimeAndExactFloats) {
    const std::vector<BodySnapshot> bodies = makeBodies();
    const BodyCacheStep at{42, 0.7000000104308128};
    const auto rows = readCsv(csvText(bodies, at));
    ASSERT_EQ(rows.size(), bodies.size() + 1);
    EXPECT_EQ(rows[0], (std::vector<std::string>{"step", "time", "id", "name", "x", "y", "angle", "vx", "vy",
                                                 "angular_velocity"}));
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const std::vector<std::string>& row = rows[i + 1];
        const BodySnapshot& b = bodies[i];
        ASSERT_EQ(row.size(), 10u) << "row " << i;
        EXPECT_EQ(row[0], "42");
        EXPECT_EQ(std::strtod(row[1].c_str(), nullptr), at.time) << "time reads back to the same double";
        EXPECT_EQ(row[2], std::to_string(b.id.index));
        EXPECT_EQ(row[3], b.name) << "names come back whole, commas, quotes and line breaks included";
        const float expected[] = {b.position.x,       b.position.y,       b.angle,
                                  b.linearVelocity.x, b.linearVelocity.y, b.angularVelocity};
        for (std::size_t k = 0; k < 6; ++k) {
            EXPECT_TRUE(sameBits(parseFloat(row[4 + k]), expected[k])) << "row " << i << " column " << rows[0][4 + k];
        }
    }
}

TEST(IoBodyCsv, NoBodiesIsTheHeaderAlone) {
    EXPECT_EQ(csvText({}, {1, 0.1}), std::string(spindrift::io::kBodyCsvHeader) + "\n");
}

TEST(IoBodyCsv, FieldsAreQuotedOnlyWhenTheyMustBe) {
    using spindrift::io::csvField;
    EXPECT_EQ(csvField("crate"), "crate");
    EXPECT_EQ(csvField("big crate"), "big crate");
    EXPECT_EQ(csvField("a,b"), "\"a,b\"");
    EXPECT_EQ(csvField("6\" pipe"), "\"6\"\" pipe\"");
    EXPECT_EQ(csvField("two\nlines"), "\"two\nlines\"");
    EXPECT_EQ(csvField("cr\r"), "\"cr\r\"");
}

// PLY ---------------------------------------------------------------------------------

TEST(IoBodyPly, TheTestReaderRejectsBrokenFiles) {
    const std::string good = plyBytes(makeBodies(), {1, 0.5});
    ASSERT_NO_THROW(readPlyFile(good));
    const std::string header = good.substr(0, good.find("end_header\n") + 11);
    const std::string bad[] = {
        good.substr(0, good.size() - 1),                                  // data cut short
        good + '\0',                                                      // a byte too many
        "ply\nformat binary_little_endian 1.0\nelement vertex 0\n",       // no end_header
        "plx\nformat binary_little_endian 1.0\nend_header\n",             // bad magic
        "ply\nformat binary_big_endian 1.0\nend_header\n",                // not supported here
        "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty quad x\nend_header\n0000",
        "ply\nformat binary_little_endian 1.0\nproperty float x\nend_header\n",
        "ply\r\nformat binary_little_endian 1.0\r\nend_header\r\n",
        "ply\nformat binary_little_endian 1.0\ncomment caf\xc3\xa9\nend_header\n",
        header.substr(0, header.size() - 11) + "bogus\nend_header\n"};
    for (const std::string& bytes : bad) EXPECT_THROW(readPlyFile(bytes), std::runtime_error) << bytes;
}

TEST(IoBodyPly, OneVertexPerBodyInTheDeclaredTypes) {
    const std::vector<BodySnapshot> bodies = makeBodies();
    const PlyFile ply = readPlyFile(plyBytes(bodies, {42, 0.7000000104308128}));
    EXPECT_EQ(ply.format, "binary_little_endian");
    ASSERT_EQ(ply.elements.size(), 1u) << "one element, so tools take the file as a point cloud";
    const auto& vertex = ply.element("vertex");
    EXPECT_EQ(vertex.count, bodies.size());
    const std::vector<std::pair<std::string, std::string>> properties{
        {"float", "x"},  {"float", "y"},  {"float", "z"},
        {"float", "angle"}, {"float", "vx"}, {"float", "vy"},
        {"float", "angular_velocity"}, {"int", "id"}};
    EXPECT_EQ(vertex.properties, properties);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const BodySnapshot& b = bodies[i];
        const float expected[] = {b.position.x,       b.position.y,       0.0f,
                                  b.angle,            b.linearVelocity.x, b.linearVelocity.y,
                                  b.angularVelocity};
        for (std::size_t k = 0; k < 7; ++k) {
            const std::string& name = properties[k].second;
            EXPECT_TRUE(sameBits(static_cast<float>(vertex.values.at(name)[i]), expected[k])) << i << " " << name;
        }
        EXPECT_EQ(vertex.values.at("id")[i], b.id.index);
    }
}

TEST(IoBodyPly, CommentsGiveTheStepAndEachBodysNameOnOneAsciiLine) {
    const PlyFile ply = readPlyFile(plyBytes(makeBodies(), {42, 0.5}));
    ASSERT_EQ(ply.comments.size(), 5u);
    EXPECT_EQ(ply.comments[1], "step 42 time 0.5");
    EXPECT_EQ(ply.comments[2], "body 1 floor");
    EXPECT_EQ(ply.comments[3], "body 2 crate, big");
    EXPECT_EQ(ply.comments[4], "body 3 say \"hi\"_there") << "a line break would end the comment";
}

TEST(IoBodyPly, NoBodiesIsAValidEmptyFile) {
    const PlyFile ply = readPlyFile(plyBytes({}, {1, 0.1}));
    EXPECT_EQ(ply.element("vertex").count, 0u);
}

}  // namespace
