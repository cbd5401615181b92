// Data behind flow fields, terrain and cube maps: generated fields have the
// properties their physics promises (curl noise is divergence-free, a vortex
// turns the right way at the right speed), cube maps follow Vulkan's face
// convention, and files and PNG height maps load with the documented layout.
#include "scene/cube_map.h"
#include "scene/field_sources.h"

#include <spindrift/scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>
#include <vector>

namespace {

using namespace spindrift;

SceneDef parse(const std::string& text, const std::string& baseDir = ".") {
    return parseScene(text, "test.toml", baseDir);
}

// --- Flow fields -----------------------------------------------------------------

glm::vec3 at(const FlowFieldDef& f, std::uint32_t i, std::uint32_t j, std::uint32_t k) {
    return f.velocities.at((static_cast<std::size_t>(k) * f.ny + j) * f.nx + i);
}

struct DivergenceStats {
    double meanAbsDivergence = 0.0;
    double meanGradientNorm = 0.0;  ///< mean Frobenius norm of the velocity Jacobian
};

// Central differences over interior samples (vertex grid, spacing h per axis).
DivergenceStats divergence(const FlowFieldDef& f) {
    const glm::vec3 h =
        (f.boundsMax - f.boundsMin) / glm::vec3(f.nx - 1, f.ny - 1, f.nz > 1 ? f.nz - 1 : 1);
    const bool planar = f.nz == 1;
    DivergenceStats s;
    std::size_t count = 0;
    for (std::uint32_t k = planar ? 0 : 1; k < (planar ? 1 : f.nz - 1); ++k) {
        for (std::uint32_t j = 1; j + 1 < f.ny; ++j) {
            for (std::uint32_t i = 1; i + 1 < f.nx; ++i) {
                const glm::vec3 dx = (at(f, i + 1, j, k) - at(f, i - 1, j, k)) / (2.0f * h.x);
                const glm::vec3 dy = (at(f, i, j + 1, k) - at(f, i, j - 1, k)) / (2.0f * h.y);
                const glm::vec3 dz = planar
                                         ? glm::vec3(0.0f)
                                         : (at(f, i, j, k + 1) - at(f, i, j, k - 1)) / (2.0f * h.z);
                s.meanAbsDivergence += std::abs(dx.x + dy.y + dz.z);
                s.meanGradientNorm +=
                    std::sqrt(glm::dot(dx, dx) + glm::dot(dy, dy) + glm::dot(dz, dz));
                ++count;
            }
        }
    }
    s.meanAbsDivergence /= static_cast<double>(count);
    s.meanGradientNorm /= static_cast<double>(count);
    return s;
}

const char* kCurl3d = R"([[flow_field]]
name = "curl"
generate = "curl_noise"
bounds_min = [0, 0, 0]
bounds_max = [2, 2, 2]
resolution = [48, 48, 48]
frequency = 1.0
strength = 1.5
octaves = 1
seed = 9
)";

TEST(SceneFlowField, CurlNoiseIsDivergenceFree) {
    const FlowFieldDef f = parse(kCurl3d).flowFields.at(0);
    ASSERT_EQ(f.velocities.size(), 48u * 48u * 48u);
    const DivergenceStats s = divergence(f);
    // Central differences at h = 2/47 m of noise with 1 cell per metre have a
    // truncation error of order (pi h)^2 / 6, about 0.3 %; a field that is
    // not solenoidal has divergence of the order of its gradient (ratio ~0.5).
    EXPECT_GT(s.meanGradientNorm, 0.5);
    EXPECT_LT(s.meanAbsDivergence, 0.01 * s.meanGradientNorm)
        << "divergence " << s.meanAbsDivergence << " vs |grad v| " << s.meanGradientNorm;
}

TEST(SceneFlowField, DivergenceCheckDetectsACompressibleField) {
    // The same check on a field that is not divergence-free must fail, or the
    // test above proves nothing: v = grad of the potential's first component.
    FlowFieldDef f = parse(kCurl3d).flowFields.at(0);
    scene::CurlNoiseParams params;
    params.frequency = 1.0f;
    params.seed = 9;
    for (std::uint32_t k = 0; k < f.nz; ++k) {
        for (std::uint32_t j = 0; j < f.ny; ++j) {
            for (std::uint32_t i = 0; i < f.nx; ++i) {
                const glm::vec3 p = scene::flowSamplePosition(f, i, j, k);
                // A radial source: div = 3 everywhere.
                f.velocities[(static_cast<std::size_t>(k) * f.ny + j) * f.nx + i] =
                    p + scene::curlNoise(p, params, false);
            }
        }
    }
    const DivergenceStats s = divergence(f);
    EXPECT_NEAR(s.meanAbsDivergence, 3.0, 0.05);
    EXPECT_GT(s.meanAbsDivergence, 0.01 * s.meanGradientNorm);
}

TEST(SceneFlowField, CurlNoiseContinuousFunctionIsDivergenceFree) {
    scene::CurlNoiseParams params;
    params.frequency = 0.7f;
    params.octaves = 3;
    params.seed = 123;
    const float h = 1e-3f;
    for (int n = 0; n < 50; ++n) {
        const glm::vec3 p(0.37f * n, 1.3f - 0.11f * n, 0.05f * n * n);
        const auto d = [&](glm::vec3 e) {
            return (scene::curlNoise(p + e, params, false) -
                    scene::curlNoise(p - e, params, false)) /
                   (2.0f * h);
        };
        const glm::vec3 dx = d({h, 0, 0});
        const glm::vec3 dy = d({0, h, 0});
        const glm::vec3 dz = d({0, 0, h});
        const float gradient = std::sqrt(glm::dot(dx, dx) + glm::dot(dy, dy) + glm::dot(dz, dz));
        // Float rounding in the differences is ~1e-7 / 1e-3 relative to |v|.
        EXPECT_LT(std::abs(dx.x + dy.y + dz.z), 2e-3f * (gradient + 1.0f)) << "at sample " << n;
    }
}

TEST(SceneFlowField, PlanarCurlNoiseIsDivergenceFreeInThePlane) {
    const FlowFieldDef f = parse(R"([[flow_field]]
name = "curl2d"
generate = "curl_noise"
bounds_min = [-1, -1, -0.1]
bounds_max = [1, 1, 0.1]
resolution = [96, 96]
frequency = 2.0
strength = 1.0
seed = 4
)")
                               .flowFields.at(0);
    EXPECT_EQ(f.nz, 1u);
    for (const glm::vec3& v : f.velocities) {
        ASSERT_EQ(v.z, 0.0f);
    }
    const DivergenceStats s = divergence(f);
    EXPECT_GT(s.meanGradientNorm, 0.5);
    EXPECT_LT(s.meanAbsDivergence, 0.01 * s.meanGradientNorm);
}

TEST(SceneFlowField, CurlNoiseStrengthIsTheRmsSpeed) {
    const FlowFieldDef f = parse(kCurl3d).flowFields.at(0);
    double sum = 0.0;
    for (const glm::vec3& v : f.velocities) {
        sum += glm::dot(v, v);
    }
    EXPECT_NEAR(std::sqrt(sum / f.velocities.size()), 1.5, 1e-4);
}

TEST(SceneFlowField, CurlNoiseIsDeterministicAndSeeded) {
    const FlowFieldDef a = parse(kCurl3d).flowFields.at(0);
    const FlowFieldDef b = parse(kCurl3d).flowFields.at(0);
    EXPECT_EQ(a.velocities, b.velocities);
    std::string other = kCurl3d;
    other.replace(other.find("seed = 9"), 8, "seed = 8");
    EXPECT_NE(parse(other).flowFields.at(0).velocities, a.velocities);
}

TEST(SceneFlowField, SamplesSitAtGridVertices) {
    FlowFieldDef f;
    f.boundsMin = glm::vec3(-1, 0, 2);
    f.boundsMax = glm::vec3(1, 4, 3);
    f.nx = 3;
    f.ny = 5;
    f.nz = 1;
    EXPECT_EQ(scene::flowSamplePosition(f, 0, 0, 0), glm::vec3(-1, 0, 2.5));
    EXPECT_EQ(scene::flowSamplePosition(f, 2, 4, 0), glm::vec3(1, 4, 2.5));
    EXPECT_EQ(scene::flowSamplePosition(f, 1, 3, 0), glm::vec3(0, 3, 2.5));
}

TEST(SceneFlowField, UniformField) {
    const FlowFieldDef f = parse(R"([[flow_field]]
name = "u"
generate = "uniform"
velocity = [1, -2, 3]
bounds_min = [0, 0, 0]
bounds_max = [1, 1, 1]
resolution = [2, 3, 4]
)")
                               .flowFields.at(0);
    EXPECT_EQ(f.nx * f.ny * f.nz, 24u);
    ASSERT_EQ(f.velocities.size(), 24u);
    for (const glm::vec3& v : f.velocities) {
        EXPECT_EQ(v, glm::vec3(1, -2, 3));
    }
}

TEST(SceneFlowField, VortexTurnsCounterClockwiseWithRankineProfile) {
    // Axis +y through the origin, 2 m/s at the 1 m core edge. Vertices at
    // x = -2 .. 2 step 0.5, z = 0 (odd count keeps a vertex on the axis).
    const FlowFieldDef f = parse(R"([[flow_field]]
name = "v"
generate = "vortex"
center = [0, 0, 0]
axis = [0, 1, 0]
speed = 2
radius = 1
bounds_min = [-2, -1, -1]
bounds_max = [2, 1, 1]
resolution = [9, 3, 3]
)")
                               .flowFields.at(0);
    // y x (x e_x) = -x e_z: at +x the flow heads to -z. Vertex i is at x = -2 + 0.5 i.
    EXPECT_NEAR(at(f, 5, 1, 1).z, -1.0f, 1e-5);  // x = 0.5, inside the core: 2 * 0.5 / 1
    EXPECT_NEAR(at(f, 5, 1, 1).x, 0.0f, 1e-6);
    EXPECT_NEAR(at(f, 5, 1, 1).y, 0.0f, 1e-6);
    EXPECT_NEAR(at(f, 6, 1, 1).z, -2.0f, 1e-5);  // x = 1, the core's edge
    EXPECT_NEAR(at(f, 8, 1, 1).z, -1.0f, 1e-5);  // x = 2, outside: 2 * 1 / 2
    EXPECT_NEAR(at(f, 5, 0, 1).z, -1.0f, 1e-5);  // same at another height
    EXPECT_NEAR(at(f, 0, 1, 1).z, 1.0f, 1e-5);   // x = -2: the other way round
    EXPECT_EQ(at(f, 4, 1, 1), glm::vec3(0.0f));  // on the axis
}

// A fresh directory per test and process: ctest runs tests in parallel.
std::filesystem::path uniqueTempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return std::filesystem::temp_directory_path() /
           (std::string("spindrift-") + info->test_suite_name() + "-" + info->name() + "-" +
            std::to_string(::getpid()));
}

class SceneDataFiles : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = uniqueTempDir();
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    void write(const std::string& name, const std::string& bytes) {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
    }
    std::filesystem::path dir_;
};

TEST_F(SceneDataFiles, FlowFileLayoutXFastest) {
    write("f.flow",
          "# two by two by two\n"
          "spindrift-flow 1 2 2 2 -1 -2 -3 1 2 3\n"
          "\n"
          "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1.5\n");
    const FlowFieldDef f =
        parse("[[flow_field]]\nname = \"f\"\nfile = \"f.flow\"\n", dir_.string()).flowFields.at(0);
    EXPECT_EQ(f.name, "f");
    EXPECT_EQ(f.boundsMin, glm::vec3(-1, -2, -3));
    EXPECT_EQ(f.boundsMax, glm::vec3(1, 2, 3));
    EXPECT_EQ(f.nx, 2u);
    EXPECT_EQ(f.ny, 2u);
    EXPECT_EQ(f.nz, 2u);
    EXPECT_EQ(at(f, 1, 0, 0), glm::vec3(1, 0, 0));
    EXPECT_EQ(at(f, 0, 1, 0), glm::vec3(0, 1, 0));
    EXPECT_EQ(at(f, 0, 0, 1), glm::vec3(0, 0, 1));
    EXPECT_EQ(at(f, 1, 1, 1), glm::vec3(1, 1, 1.5));
}

TEST_F(SceneDataFiles, CubeMapFileLayout) {
    std::string text = "spindrift-cubemap 1 2\n";
    // Depth = 10 * face + 2 * row + column + 1, so each texel is identifiable.
    for (int face = 0; face < 6; ++face) {
        for (int row = 0; row < 2; ++row) {
            text += std::to_string(10 * face + 2 * row + 1) + " " +
                    std::to_string(10 * face + 2 * row + 2) + "\n";
        }
    }
    write("c.cube", text);
    const ColliderDef c = parse(
                              "[[collider]]\nname = \"c\"\nkind = \"cube_map\"\n"
                              "center = [1, 2, 3]\nfile = \"c.cube\"\n",
                              dir_.string())
                              .colliders.at(0);
    EXPECT_EQ(c.cubeResolution, 2u);
    EXPECT_EQ(c.position, glm::vec3(1, 2, 3));
    ASSERT_EQ(c.cubeDepths.size(), 24u);
    EXPECT_EQ(c.cubeDepths[cubeTexelIndex(0, 1, 0, 2)], 2.0f);
    EXPECT_EQ(c.cubeDepths[cubeTexelIndex(3, 0, 1, 2)], 33.0f);
    EXPECT_EQ(c.cubeDepths[cubeTexelIndex(5, 1, 1, 2)], 54.0f);
}

// --- PNG height maps ---------------------------------------------------------------
// A minimal PNG writer (stored, uncompressed deflate blocks), written here from
// the PNG and zlib specifications so the test does not depend on the decoder's
// own library.

std::uint32_t crc32(const std::string& bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
        c ^= b;
        for (int k = 0; k < 8; ++k) {
            c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        }
    }
    return c ^ 0xFFFFFFFFu;
}

std::string be32(std::uint32_t v) {
    return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
            static_cast<char>(v)};
}

std::string chunk(const std::string& type, const std::string& data) {
    return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc32(type + data));
}

// `samples` are row-major grey values with the given bit depth (8 or 16).
std::string greyPng(std::uint32_t w, std::uint32_t h, int bits, const std::vector<int>& samples) {
    std::string raw;
    for (std::uint32_t y = 0; y < h; ++y) {
        raw += '\0';  // filter: none
        for (std::uint32_t x = 0; x < w; ++x) {
            const int s = samples[y * w + x];
            if (bits == 16) {
                raw += static_cast<char>(s >> 8);
            }
            raw += static_cast<char>(s & 0xFF);
        }
    }
    std::uint32_t a = 1, b = 0;  // Adler-32
    for (unsigned char c : raw) {
        a = (a + c) % 65521u;
        b = (b + a) % 65521u;
    }
    const auto len = static_cast<std::uint16_t>(raw.size());
    std::string zlib = "\x78\x01";
    zlib += '\x01';  // final stored block
    zlib += static_cast<char>(len & 0xFF);
    zlib += static_cast<char>(len >> 8);
    zlib += static_cast<char>(~len & 0xFF);
    zlib += static_cast<char>((~len >> 8) & 0xFF);
    zlib += raw + be32((b << 16) | a);
    const std::string header = be32(w) + be32(h) + static_cast<char>(bits) + std::string(4, '\0');
    return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", zlib) +
           chunk("IEND", "");
}

TEST_F(SceneDataFiles, SixteenBitPngHeights) {
    write("h.png", greyPng(3, 2, 16, {0, 65535, 32768, 13107, 0, 65535}));
    const ColliderDef t = parse(
                              "[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [3, 2]\n"
                              "image = \"h.png\"\nheight_scale = 2.0\n",
                              dir_.string())
                              .colliders.at(0);
    EXPECT_EQ(t.terrainNx, 3u);
    EXPECT_EQ(t.terrainNz, 2u);
    ASSERT_EQ(t.heights.size(), 6u);
    EXPECT_FLOAT_EQ(t.heights[0], 0.0f);
    EXPECT_FLOAT_EQ(t.heights[1], 2.0f);
    EXPECT_NEAR(t.heights[2], 2.0f * 32768.0f / 65535.0f, 1e-6);
    EXPECT_NEAR(t.heights[3], 2.0f * 0.2f, 1e-6);  // 13107 = 65535 / 5
}

TEST_F(SceneDataFiles, EightBitPngHeights) {
    write("h8.png", greyPng(2, 2, 8, {0, 255, 51, 102}));
    const ColliderDef t = parse(
                              "[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\n"
                              "image = \"h8.png\"\nheight_scale = 10\n",
                              dir_.string())
                              .colliders.at(0);
    ASSERT_EQ(t.heights.size(), 4u);
    EXPECT_FLOAT_EQ(t.heights[1], 10.0f);
    EXPECT_NEAR(t.heights[2], 2.0f, 1e-5);  // 51 / 255 * 10
    EXPECT_NEAR(t.heights[3], 4.0f, 1e-5);
}

TEST_F(SceneDataFiles, CorruptPngIsAnErrorAtTheImageKey) {
    write("bad.png", "not a png at all");
    try {
        parse(
            "[[collider]]\nname = \"t\"\nkind = \"terrain\"\nsize = [1, 1]\nimage = \"bad.png\"\n",
            dir_.string());
        FAIL() << "a corrupt PNG was accepted";
    } catch (const SceneError& e) {
        EXPECT_EQ(e.line(), 5);
        EXPECT_EQ(e.column(), 9);
        EXPECT_EQ(e.keyPath(), "collider[0].image");
    }
}

// --- Terrain from noise ---------------------------------------------------------------

const char* kHills = R"([[collider]]
name = "hills"
kind = "terrain"
origin = [-5, 0, -5]
size = [10, 10]
generate = "hills"
resolution = [33, 17]
amplitude = 1.25
frequency = 0.4
octaves = 3
seed = 2
)";

TEST(SceneTerrain, HillsPeakAtTheAmplitude) {
    const ColliderDef t = parse(kHills).colliders.at(0);
    EXPECT_EQ(t.terrainNx, 33u);
    EXPECT_EQ(t.terrainNz, 17u);
    ASSERT_EQ(t.heights.size(), 33u * 17u);
    float largest = 0.0f;
    float smallest = 0.0f;
    for (float h : t.heights) {
        largest = std::max(largest, std::abs(h));
        smallest = std::min(smallest, h);
    }
    EXPECT_FLOAT_EQ(largest, 1.25f);
    EXPECT_LT(smallest, 0.0f);  // hills and valleys
}

TEST(SceneTerrain, HillsAreSmoothNotWhiteNoise) {
    // For independent random heights neighbours differ by about sqrt(2) times
    // the spread of the heights; smooth hills sampled finer than their feature
    // size (0.31 m steps, 2.5 m noise cells) differ by much less.
    const ColliderDef t = parse(kHills).colliders.at(0);
    double mean = 0.0;
    for (float h : t.heights) {
        mean += h;
    }
    mean /= static_cast<double>(t.heights.size());
    double variance = 0.0;
    for (float h : t.heights) {
        variance += (h - mean) * (h - mean);
    }
    const double spread = std::sqrt(variance / static_cast<double>(t.heights.size()));
    double step = 0.0;
    std::size_t count = 0;
    for (std::uint32_t j = 0; j < t.terrainNz; ++j) {
        for (std::uint32_t i = 1; i < t.terrainNx; ++i) {
            step += std::abs(t.heights[j * t.terrainNx + i] - t.heights[j * t.terrainNx + i - 1]);
            ++count;
        }
    }
    EXPECT_GT(spread, 0.1);
    EXPECT_LT(step / static_cast<double>(count), 0.35 * spread);
}

TEST(SceneTerrain, HillsAreSeeded) {
    const ColliderDef a = parse(kHills).colliders.at(0);
    EXPECT_EQ(a.heights, parse(kHills).colliders.at(0).heights);
    std::string other = kHills;
    other.replace(other.find("seed = 2"), 8, "seed = 3");
    EXPECT_NE(parse(other).colliders.at(0).heights, a.heights);
}

// --- Cube maps ---------------------------------------------------------------------------

TEST(SceneCubeMap, FaceUvRoundTrip) {
    const std::uint32_t res = 16;
    for (std::uint32_t face = 0; face < 6; ++face) {
        for (std::uint32_t j = 0; j < res; ++j) {
            for (std::uint32_t i = 0; i < res; ++i) {
                const float u = (i + 0.5f) / res;
                const float v = (j + 0.5f) / res;
                const glm::vec3 d = cubeTexelDirection(face, u, v);
                ASSERT_NEAR(glm::length(d), 1.0f, 1e-6);
                const CubeFaceUv back = cubeFaceUv(d * 3.0f);  // any length
                ASSERT_EQ(back.face, face) << i << "," << j;
                ASSERT_NEAR(back.u, u, 1e-6);
                ASSERT_NEAR(back.v, v, 1e-6);
            }
        }
    }
}

TEST(SceneCubeMap, FollowsTheVulkanFaceTable) {
    // Worked by hand from the table in the Vulkan specification, "Cube Map
    // Face Selection": u = (sc / |ma| + 1) / 2, v = (tc / |ma| + 1) / 2.
    struct Case {
        glm::vec3 dir;
        std::uint32_t face;
        float u, v;
    };
    const Case cases[] = {
        {{1.0f, 0.5f, 0.25f}, 0, 0.375f, 0.25f},   // +x: sc = -rz, tc = -ry
        {{-1.0f, 0.5f, 0.25f}, 1, 0.625f, 0.25f},  // -x: sc = +rz, tc = -ry
        {{0.25f, 1.0f, 0.5f}, 2, 0.625f, 0.75f},   // +y: sc = +rx, tc = +rz
        {{0.25f, -1.0f, 0.5f}, 3, 0.625f, 0.25f},  // -y: sc = +rx, tc = -rz
        {{0.25f, 0.5f, 1.0f}, 4, 0.625f, 0.25f},   // +z: sc = +rx, tc = -ry
        {{0.25f, 0.5f, -1.0f}, 5, 0.375f, 0.25f},  // -z: sc = -rx, tc = -ry
        {{0.0f, 0.0f, -2.0f}, 5, 0.5f, 0.5f},
    };
    for (const Case& c : cases) {
        const CubeFaceUv f = cubeFaceUv(c.dir);
        EXPECT_EQ(f.face, c.face);
        EXPECT_FLOAT_EQ(f.u, c.u);
        EXPECT_FLOAT_EQ(f.v, c.v);
        const glm::vec3 back = cubeTexelDirection(c.face, c.u, c.v);
        EXPECT_NEAR(glm::length(back - glm::normalize(c.dir)), 0.0f, 1e-6);
    }
}

TEST(SceneCubeMap, SphereAtTheCentreHasItsRadiusEverywhere) {
    const ColliderDef c = parse(R"([[collider]]
name = "ball"
kind = "cube_map"
center = [1, 2, 3]
resolution = 12
shapes = [{kind = "sphere", center = [1, 2, 3], radius = 0.75}]
)")
                              .colliders.at(0);
    EXPECT_EQ(c.cubeResolution, 12u);
    ASSERT_EQ(c.cubeDepths.size(), 6u * 12u * 12u);
    for (float depth : c.cubeDepths) {
        ASSERT_NEAR(depth, 0.75f, 1e-6f);
    }
}

TEST(SceneCubeMap, BoxDepthIsTheSlabExit) {
    // A box centred on the collider: along unit d the exit is at
    // min over axes of h_a / |d_a|.
    const glm::vec3 h(0.5f, 1.0f, 2.0f);
    const ColliderDef c = parse(R"([[collider]]
name = "box"
kind = "cube_map"
resolution = 8
shapes = [{kind = "box", center = [0, 0, 0], half_extents = [0.5, 1.0, 2.0]}]
)")
                              .colliders.at(0);
    for (std::uint32_t face = 0; face < 6; ++face) {
        for (std::uint32_t j = 0; j < 8; ++j) {
            for (std::uint32_t i = 0; i < 8; ++i) {
                const glm::vec3 d = cubeTexelDirection(face, (i + 0.5f) / 8, (j + 0.5f) / 8);
                float exit = 1e30f;
                for (int a = 0; a < 3; ++a) {
                    if (d[a] != 0.0f) {
                        exit = std::min(exit, h[a] / std::abs(d[a]));
                    }
                }
                ASSERT_NEAR(c.cubeDepths[cubeTexelIndex(face, i, j, 8)], exit, 1e-5f);
            }
        }
    }
}

TEST(SceneCubeMap, UnionKeepsTheOutermostSurface) {
    // Unit sphere at the centre plus a small sphere poking out along +x: the
    // +x face's centre texel (odd resolution: exactly +x) sees 1.2 + 0.5.
    const ColliderDef c = parse(R"([[collider]]
name = "u"
kind = "cube_map"
resolution = 9
shapes = [
    {kind = "sphere", center = [0, 0, 0], radius = 1},
    {kind = "sphere", center = [1.2, 0, 0], radius = 0.5},
]
)")
                              .colliders.at(0);
    EXPECT_NEAR(c.cubeDepths[cubeTexelIndex(0, 4, 4, 9)], 1.7f, 1e-5f);
    EXPECT_NEAR(c.cubeDepths[cubeTexelIndex(1, 4, 4, 9)], 1.0f, 1e-5f);
    EXPECT_NEAR(c.cubeDepths[cubeTexelIndex(2, 4, 4, 9)], 1.0f, 1e-5f);
}

}  // namespace
