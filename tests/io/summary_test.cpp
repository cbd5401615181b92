// summary.json: valid JSON, the right numbers, safe strings.
#include "io/json_writer.h"
#include "io/summary.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

namespace spindrift_test {  // tests/io/json_check.cpp
std::string jsonError(std::string_view text);
std::optional<std::string> jsonQuery(std::string_view text, std::string_view path);
}  // namespace spindrift_test

namespace {

using spindrift::StepStats;
using spindrift::io::RunSummary;
using spindrift_test::jsonError;
using spindrift_test::jsonQuery;

/// `steps` steps where step i (0-based) has born = i + 1, died = i, and hits
/// on collider 2 only (collider 1 is never mentioned, as a library may do).
RunSummary makeSummary(std::size_t steps) {
    RunSummary s;
    s.scene = "scenes/fountain.toml";
    s.backend = "cpu";
    s.threads = 4;
    s.seed = 7;
    s.dt = 1.0f / 60.0f;
    s.every = 10;
    s.formats = {"csv", "ply"};
    s.emitterNames = {"jet", "mist"};
    s.colliderNames = {"floor", "ball"};
    for (std::size_t i = 0; i < steps; ++i) {
        StepStats st;
        st.step = i;
        st.time = static_cast<double>(i + 1) * s.dt;
        st.born = i + 1;
        st.died = i;
        st.alive = i + 1;
        st.collisions = 2 * i;
        st.clamped = i % 3 == 0 ? 1 : 0;
        st.colliderHits.push_back({spindrift::ColliderId{2}, 2 * i});
        st.milliseconds = 0.25;
        s.steps.push_back(st);
    }
    s.wallSeconds = 1.5;
    s.cacheFiles = 12;
    return s;
}

std::string toJson(const RunSummary& s) {
    std::ostringstream out;
    spindrift::io::writeSummaryJson(out, s);
    return out.str();
}

std::string query(const std::string& json, std::string_view path) {
    return jsonQuery(json, path).value_or("<missing " + std::string(path) + ">");
}

TEST(IoJsonCheck, TheTestReaderRejectsInvalidJson) {
    // The summary tests are only as good as this reader: make sure it says no.
    const char* bad[] = {"{\"a\": NaN}", "[1,]", "{'a': 1}", "[\"a\nb\"]", "01", "[1.]", "[.5]",
                         "{\"a\": 1, \"a\": 2}", "\"\xff\"", "[inf]", "{\"a\" 1}", "[1] [2]", "",
                         "\"\\ud800\"", "[-]", "[1e]", "\"\xed\xa0\x80\""};
    for (const char* text : bad) EXPECT_NE(jsonError(text), "") << text;
    EXPECT_EQ(jsonError(" {\"a\": [1, -0.5e+3, 0, true, false, null, \"\\u00e9\\ud83d\\ude00\", {}]} "), "");
    EXPECT_EQ(jsonQuery("{\"a\": [1, {\"b\": \"\\u00e9\"}]}", "a/1/b"), "\xc3\xa9");
}

TEST(IoSummary, IsValidJsonWithOneEntryPerStep) {
    const std::string json = toJson(makeSummary(25));
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(query(json, "steps"), "25");
    EXPECT_EQ(query(json, "per_step/#"), "25");
    EXPECT_EQ(query(json, "per_step/0/step"), "1");
    EXPECT_EQ(query(json, "per_step/24/step"), "25");
    EXPECT_EQ(query(json, "per_step/24/alive"), "25");
    EXPECT_EQ(query(json, "per_step/7/collider_hits/#"), "2");
    EXPECT_EQ(query(json, "per_step/7/collider_hits/0"), "0");
    EXPECT_EQ(query(json, "per_step/7/collider_hits/1"), "14");
    EXPECT_EQ(query(json, "scene"), "scenes/fountain.toml");
    EXPECT_EQ(query(json, "backend"), "cpu");
    EXPECT_EQ(query(json, "threads"), "4");
    EXPECT_EQ(query(json, "colliders/1"), "ball");
    EXPECT_EQ(query(json, "emitters/#"), "2");
    EXPECT_EQ(query(json, "formats/1"), "ply");
}

TEST(IoSummary, TotalsAddUpTheSteps) {
    const std::string json = toJson(makeSummary(25));
    // Sums of 1..25 and 0..24 and 2*(0..24); clamped at i = 0, 3, ..., 24.
    EXPECT_EQ(query(json, "totals/born"), "325");
    EXPECT_EQ(query(json, "totals/died"), "300");
    EXPECT_EQ(query(json, "totals/collisions"), "600");
    EXPECT_EQ(query(json, "totals/clamped"), "9");
    EXPECT_EQ(query(json, "totals/collider_hits/0"), "0");
    EXPECT_EQ(query(json, "totals/collider_hits/1"), "600");
    EXPECT_EQ(query(json, "totals/final_alive"), "25");
    EXPECT_EQ(std::strtod(query(json, "totals/step_ms").c_str(), nullptr), 6.25);
    EXPECT_EQ(std::strtod(query(json, "totals/wall_seconds").c_str(), nullptr), 1.5);
    EXPECT_EQ(query(json, "totals/cache_files"), "12");
}

// Particles removed as non-finite and bodies frozen (issue 14): per step
// where they happen, summed in the totals (each body counted once).
TEST(IoSummary, NonFiniteRemovalsAndFrozenBodiesArePerStepAndSummed) {
    RunSummary s = makeSummary(4);
    s.steps[1].nonFinite = 5;
    s.steps[3].nonFinite = 2;
    s.steps[2].frozenBodies = {spindrift::BodyId{3}, spindrift::BodyId{1}};
    const std::string json = toJson(s);
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(query(json, "per_step/0/non_finite"), "0");
    EXPECT_EQ(query(json, "per_step/1/non_finite"), "5");
    EXPECT_EQ(query(json, "per_step/2/frozen_bodies/#"), "2");
    EXPECT_EQ(query(json, "per_step/2/frozen_bodies/0"), "3");
    EXPECT_EQ(query(json, "totals/non_finite"), "7");
    EXPECT_EQ(query(json, "totals/frozen_bodies"), "2");
}

TEST(IoSummary, FluidNumberDensityOnTheMeasuredFramesAndInTheTotals) {
    RunSummary s = makeSummary(25);
    s.fluidNames = {"water"};
    for (spindrift::StepStats& st : s.steps) {
        spindrift::FluidStepStats f;
        f.fluid = spindrift::FluidId{1};
        f.particles = 100;
        // What each substep rule asked for, the count taken the most of them.
        f.substepsForSpeed = 2;
        f.substepsForDepth = 3;
        f.substepsForCompression = 4;
        f.substeps = 4;
        st.fluids.push_back(f);
    }
    // Measured after steps 10, 20 and 25 (every = 10, and the last step).
    const double median[3] = {1.0, 1.25, 1.5}, p95[3] = {1.5, 2.5, 2.0};
    const std::uint64_t frames[3] = {10, 20, 25};
    for (int i = 0; i < 3; ++i) {
        spindrift::FluidNumberDensity d;
        d.median = median[i];
        d.p95 = p95[i];
        d.reference = 45;
        s.numberDensity.push_back({frames[i], {d}});
    }
    const std::string json = toJson(s);
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(query(json, "per_step/9/fluids/0/number_density_median"), "1");
    EXPECT_EQ(query(json, "per_step/19/fluids/0/number_density_p95"), "2.5");
    EXPECT_EQ(query(json, "per_step/24/fluids/0/number_density_median"), "1.5");
    EXPECT_FALSE(jsonQuery(json, "per_step/10/fluids/0/number_density_median").has_value());
    EXPECT_EQ(query(json, "per_step/10/fluids/0/particles"), "100");
    EXPECT_EQ(query(json, "per_step/3/fluids/0/substeps"), "4");
    EXPECT_EQ(query(json, "per_step/3/fluids/0/substeps_for_speed"), "2");
    EXPECT_EQ(query(json, "per_step/3/fluids/0/substeps_for_depth"), "3");
    EXPECT_EQ(query(json, "per_step/3/fluids/0/substeps_for_compression"), "4");
    EXPECT_EQ(query(json, "totals/fluids/0/number_density_reference"), "45");
    EXPECT_EQ(query(json, "totals/fluids/0/final_number_density_median"), "1.5");
    EXPECT_EQ(query(json, "totals/fluids/0/final_number_density_p95"), "2");
    EXPECT_EQ(query(json, "totals/fluids/0/max_number_density_p95"), "2.5");
}

TEST(IoSummary, BodiesByNameAndTheirFinalState) {
    RunSummary s = makeSummary(3);
    EXPECT_FALSE(jsonQuery(toJson(s), "bodies").has_value()) << "no bodies, no members";
    EXPECT_FALSE(jsonQuery(toJson(s), "totals/final_bodies").has_value());
    s.bodyNames = {"floor", "crate \"A\""};
    spindrift::BodySnapshot floor, crate;
    floor.id = {1};
    floor.name = s.bodyNames[0];
    crate.id = {2};
    crate.name = s.bodyNames[1];
    crate.position = {0.1f, -2.5f};
    crate.angle = 1.0f / 3.0f;
    crate.linearVelocity = {1e-7f, -9.81f};
    crate.angularVelocity = -0.75f;
    s.finalBodies = {floor, crate};
    const std::string json = toJson(s);
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(query(json, "bodies/#"), "2");
    EXPECT_EQ(query(json, "bodies/1"), "crate \"A\"");
    EXPECT_EQ(query(json, "totals/final_bodies/#"), "2");
    EXPECT_EQ(query(json, "totals/final_bodies/0/x"), "0");
    EXPECT_EQ(query(json, "totals/final_bodies/1/id"), "2");
    EXPECT_EQ(query(json, "totals/final_bodies/1/name"), "crate \"A\"");
    // Each float reads back to the same float: the CSV's text, digit for digit.
    const std::pair<const char*, float> members[] = {{"x", 0.1f},  {"y", -2.5f},   {"angle", 1.0f / 3.0f},
                                                     {"vx", 1e-7f}, {"vy", -9.81f}, {"angular_velocity", -0.75f}};
    for (const auto& [name, value] : members) {
        const std::string text = query(json, std::string("totals/final_bodies/1/") + name);
        EXPECT_EQ(std::bit_cast<std::uint32_t>(std::strtof(text.c_str(), nullptr)), std::bit_cast<std::uint32_t>(value))
            << name << " = " << text;
    }
}

TEST(IoSummary, NumbersRoundTrip) {
    RunSummary s = makeSummary(2);
    s.steps[1].time = 0.1 + 0.2;  // 0.30000000000000004
    s.steps[0].milliseconds = 1e-300;
    const std::string json = toJson(s);
    ASSERT_EQ(jsonError(json), "");
    const float dt = std::strtof(query(json, "dt").c_str(), nullptr);
    EXPECT_EQ(std::bit_cast<std::uint32_t>(dt), std::bit_cast<std::uint32_t>(1.0f / 60.0f));
    EXPECT_EQ(std::strtod(query(json, "per_step/1/time").c_str(), nullptr), 0.1 + 0.2);
    EXPECT_EQ(std::strtod(query(json, "per_step/0/ms").c_str(), nullptr), 1e-300);
    EXPECT_EQ(query(json, "seed"), "7");
}

TEST(IoSummary, NonFiniteNumbersBecomeNull) {
    RunSummary s = makeSummary(3);
    s.steps[0].milliseconds = std::numeric_limits<double>::quiet_NaN();
    s.steps[1].time = std::numeric_limits<double>::infinity();
    s.dt = std::numeric_limits<float>::quiet_NaN();
    s.wallSeconds = -std::numeric_limits<double>::infinity();
    const std::string json = toJson(s);
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(query(json, "per_step/0/ms"), "null");
    EXPECT_EQ(query(json, "per_step/1/time"), "null");
    EXPECT_EQ(query(json, "dt"), "null");
    EXPECT_EQ(query(json, "totals/step_ms"), "null");  // the NaN spreads to the sum
    EXPECT_EQ(query(json, "totals/wall_seconds"), "null");
    EXPECT_EQ(json.find("nan"), std::string::npos);
    EXPECT_EQ(json.find("inf"), std::string::npos);
}

TEST(IoSummary, StringsAreEscaped) {
    RunSummary s = makeSummary(1);
    s.scene = std::string("dir \"quoted\"\\back\nline\ttab\x01\x1f caf\xc3\xa9 \xf0\x9f\x8c\x8a");
    s.emitterNames = {std::string("bad \xff byte"), std::string("cut \xe2\x82", 6)};
    const std::string json = toJson(s);
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(query(json, "scene"), s.scene);
    EXPECT_EQ(query(json, "emitters/0"), "bad \xef\xbf\xbd byte");  // U+FFFD
    EXPECT_EQ(query(json, "emitters/1"), "cut \xef\xbf\xbd\xef\xbf\xbd");
}

TEST(IoSummary, EmptyRunIsValid) {
    RunSummary s = makeSummary(0);
    s.colliderNames.clear();
    s.formats.clear();
    const std::string json = toJson(s);
    ASSERT_EQ(jsonError(json), "") << json;
    EXPECT_EQ(query(json, "per_step/#"), "0");
    EXPECT_EQ(query(json, "colliders/#"), "0");
    EXPECT_EQ(query(json, "totals/final_alive"), "0");
    EXPECT_EQ(query(json, "totals/collider_hits/#"), "0");
}

TEST(IoSummary, WritesTheFile) {
    const auto dir = std::filesystem::temp_directory_path() / ("spindrift-io-summary-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto file = dir / "summary.json";
    spindrift::io::writeSummary(file, makeSummary(4));
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(jsonError(text.str()), "");
    EXPECT_EQ(query(text.str(), "per_step/#"), "4");
    std::filesystem::remove_all(dir);
}

TEST(IoJsonWriter, NestsAndSeparates) {
    std::ostringstream out;
    spindrift::io::JsonWriter json(out);
    json.beginObject();
    json.key("a");
    json.beginArray(true);
    json.beginObject();
    json.endObject();
    json.beginArray();
    json.value(1.5);
    json.endArray();
    json.null();
    json.endArray();
    json.key("b");
    json.beginObject();
    json.endObject();
    json.endObject();
    json.finish();
    ASSERT_EQ(jsonError(out.str()), "") << out.str();
    EXPECT_EQ(jsonQuery(out.str(), "a/#"), "3");
    EXPECT_EQ(jsonQuery(out.str(), "a/1/0"), "1.5");
    EXPECT_EQ(jsonQuery(out.str(), "a/2"), "null");
}

}  // namespace
