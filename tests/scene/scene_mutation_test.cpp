// A deterministic mutation test of the scene loader (issue 14): mutants of
// every bundled scene (fixed seed, so every run and every machine tries the
// same ones) are parsed; each must either load or be refused with a located
// SceneError (a line > 0). A crash fails the test by ending the process (and
// ASan and UBSan, in the sanitizer pass, make memory errors crashes); a hang
// fails on the per-mutant time bound. Accepted mutants are built (CPU) and
// stepped once, which reaches Box2D and the solvers.
//
// This is the small, fast cousin of the libFuzzer target (fuzz/, see
// docs/fuzzing.md): it keeps the bugs that a fuzz campaign found fixed, in
// every CI run, in a few seconds.
#include <spindrift/scene.h>
#include <spindrift/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::filesystem::path kScenes = std::filesystem::path(SPINDRIFT_SOURCE_DIR) / "scenes";

// SplitMix64: the same sequence on every platform (std::uniform_*_distribution
// are not specified bit for bit).
class Random {
public:
    explicit Random(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
    template <class T>
    const T& pick(const std::vector<T>& v) {
        return v[below(v.size())];
    }

private:
    std::uint64_t state_;
};

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

std::string joinLines(const std::vector<std::string>& lines) {
    std::string text;
    for (const std::string& line : lines) {
        text += line;
        text += '\n';
    }
    return text;
}

// Values the fuzzer found troublesome, in place of a number or a string.
const std::vector<std::string> kNumbers = {
    "0",    "-0",    "-1",   "1e308", "-1e308", "nan",  "inf",   "-inf", "1e-50", "1e-45", "9223372036854775807",
    "9223372036854775808", "-9223372036854775808", "3e38", "1e30", "1e18", "4294967296", "16777217", "1e12",
    "\"x\"", "true", "[]",   "{}",    "[1, 2]", "[1e30, 1e30, 1e30]", "[nan, 0, 0]"};
const std::vector<std::string> kStrings = {
    "\"\"", "\" \"", "\"/dev/zero\"", "\"/dev/urandom\"", "\"data/swirl.flow\\u0000.txt\"",
    "\"data/rock.cube\\u0000.txt\"", "\"data\"", "\"../../../../../../etc/passwd\"", "\"data/hills.png\"",
    "\"data/rock.cube\"", "\"data/swirl.flow\"", "\"a\\nb\"", "1", "[\"x\"]"};

// One mutation of the lines of a scene; what the campaign used.
std::string mutate(const std::string& text, Random& random) {
    std::vector<std::string> lines = splitLines(text);
    if (lines.empty()) {
        return text;
    }
    std::string& line = lines[random.below(lines.size())];
    switch (random.below(10)) {
        case 0: {  // flip a byte
            std::string t = text;
            t[random.below(t.size())] ^= static_cast<char>(1u << random.below(8));
            return t;
        }
        case 1:  // delete a line
            lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(random.below(lines.size())));
            break;
        case 2: {  // duplicate a line
            const std::size_t i = random.below(lines.size());
            lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
            break;
        }
        case 3:
        case 4:
        case 5: {  // replace the value of a `key = value` line
            const std::size_t eq = line.find(" = ");
            if (eq == std::string::npos) {
                line += " = " + random.pick(kNumbers);
                break;
            }
            const bool isString = line.find('"', eq) != std::string::npos;
            line = line.substr(0, eq + 3) + (isString ? random.pick(kStrings) : random.pick(kNumbers));
            break;
        }
        case 6:  // truncate
            return text.substr(0, random.below(text.size()));
        case 7:  // an unknown key, or a known one out of place
            line += random.below(2) == 0 ? "\nunknown_key = 1" : "\ncapacity = 1";
            break;
        case 8: {  // deep nesting or a long dotted key
            const std::size_t n = 20 + random.below(60);
            std::string deep = "x = ";
            deep.append(n, '[');
            deep.append(n, ']');
            std::string dotted = "a";
            for (std::size_t i = 1; i < n; ++i) {
                dotted += ".a";
            }
            line = random.below(2) == 0 ? deep : (random.below(2) == 0 ? dotted + " = 1" : "[" + dotted + "]");
            break;
        }
        default: {  // a huge count somewhere it is a count
            for (const char* key : {"capacity", "count", "resolution", "octaves", "steps", "threads", "substeps",
                                    "iterations"}) {
                const std::size_t at = line.find(key);
                if (at != std::string::npos && line.find(" = ", at) != std::string::npos) {
                    line = line.substr(0, line.find(" = ", at) + 3) +
                           (random.below(2) == 0 ? "4294967295" : "[4096, 4096, 4096]");
                    break;
                }
            }
            break;
        }
    }
    return joinLines(lines);
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What a world shows after its steps holds no NaN or infinity (issue 14:
// particles turned NaN, counted alive and written "-nan" to the caches);
// returns what it found, empty when all is finite.
std::string nonFiniteOutput(spindrift::WorldId world, const spindrift::StepStats& stats) {
    for (std::uint32_t e = 1; e <= spindrift::emitterCount(world); ++e) {
        const spindrift::ParticleSnapshot p = spindrift::readParticles(world, spindrift::EmitterId{e});
        for (std::size_t i = 0; i < p.count(); ++i) {
            if (!finite(p.position[i]) || !finite(p.velocity[i]) || !std::isfinite(p.size[i]) ||
                !std::isfinite(p.rotation[i]) || !finite(glm::vec3(p.color[i])) || !std::isfinite(p.color[i].a)) {
                return "emitter " + std::to_string(e) + " particle " + std::to_string(i);
            }
        }
    }
    for (std::uint32_t f = 1; f <= spindrift::fluidCount(world); ++f) {
        const spindrift::FluidSnapshot s = spindrift::readFluid(world, spindrift::FluidId{f});
        for (std::size_t i = 0; i < s.position.size(); ++i) {
            if (!finite(s.position[i]) || !finite(s.velocity[i])) {
                return "fluid " + std::to_string(f) + " particle " + std::to_string(i);
            }
        }
    }
    for (const spindrift::BodySnapshot& b : spindrift::readBodies(world)) {
        if (!finite(glm::vec3(b.position, b.angle)) || !finite(glm::vec3(b.linearVelocity, b.angularVelocity))) {
            return "body " + b.name;
        }
    }
    for (const spindrift::FluidStepStats& f : stats.fluids) {
        if (!std::isfinite(f.meanDensityError) || !std::isfinite(f.maxDensityError) || !std::isfinite(f.maxSpeed)) {
            return "fluid step statistics";
        }
    }
    return {};
}

// The campaign of issue 14 runs this test with more mutants and steps:
// SPINDRIFT_MUTANTS_PER_SCENE=200 SPINDRIFT_MUTANT_STEPS=20 (docs/fuzzing.md).
int fromEnvironment(const char* name, int fallback) {
    const char* text = std::getenv(name);
    return text != nullptr && std::atoi(text) > 0 ? std::atoi(text) : fallback;
}

std::vector<std::filesystem::path> bundledScenes() {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(kScenes)) {
        if (entry.path().extension() == ".toml") {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// 300 mutants (20 per bundled scene, a quarter of them mutated twice). The
// time bound per mutant is 2 s of CPU time: a parse, build and step take
// milliseconds (tens under ASan); the hangs this guards against took 8 s or
// more. CPU time, not the wall clock: the suite shares its machine (ctest -j,
// CI's 2 cores), and a process waiting for a core is not hanging. The world
// runs on one thread, so the process's CPU time is the mutant's work.
TEST(SceneMutation, MutantsOfTheBundledScenesLoadOrFailWithALocation) {
    const std::vector<std::filesystem::path> files = bundledScenes();
    ASSERT_GE(files.size(), 10u);
    Random random(20261202);
    const int perScene = fromEnvironment("SPINDRIFT_MUTANTS_PER_SCENE", 20);
    const int steps = fromEnvironment("SPINDRIFT_MUTANT_STEPS", 1);
    // A hang as the campaign counts one: 10 s of CPU time; the normal
    // suite's single step must take under 2 s.
    const double limit = steps > 1 ? 10.0 : 2.0;
    int nonFinite = 0, unlocated = 0, otherErrors = 0, slow = 0;
    int accepted = 0, refused = 0;
    double worst = 0.0;
    std::string worstMutant;
    for (const std::filesystem::path& file : files) {
        const std::string original = readText(file);
        for (int m = 0; m < perScene; ++m) {
            std::string text = mutate(original, random);
            if (random.below(4) == 0) {
                text = mutate(text, random);  // some get two mutations
            }
            const std::clock_t start = std::clock();
            try {
                spindrift::SceneDef scene = spindrift::parseScene(text, "mutant.toml", kScenes.string());
                ++accepted;
                scene.world.backend = spindrift::Backend::Cpu;
                scene.world.threads = 1;
                const spindrift::WorldId world = spindrift::buildWorld(scene);
                spindrift::StepStats stats;
                for (int k = 0; k < steps; ++k) stats = spindrift::stepWorld(world, scene.run.dt);
                const std::string bad = nonFiniteOutput(world, stats);
                spindrift::destroyWorld(world);
                nonFinite += bad.empty() ? 0 : 1;
                EXPECT_EQ(bad, "") << "not finite after " << steps << " steps; mutant of " << file << ":\n" << text;
            } catch (const spindrift::SceneError& e) {
                ++refused;
                unlocated += e.line() > 0 ? 0 : 1;
                EXPECT_GT(e.line(), 0) << "an error without a location: " << e.what() << "\nmutant of " << file
                                       << ":\n" << text;
                EXPECT_EQ(std::string(e.what()).find('\0'), std::string::npos);
            } catch (const std::exception& e) {
                ++otherErrors;
                ADD_FAILURE() << "not a SceneError: " << e.what() << "\nmutant of " << file << ":\n" << text;
            }
            const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
            slow += seconds >= limit ? 1 : 0;
            if (seconds > worst) {
                worst = seconds;
                worstMutant = text;
            }
        }
    }
    EXPECT_LT(worst, limit) << "slowest mutant:\n" << worstMutant;
    // The mutations are not all fatal, nor all harmless: both paths are taken.
    EXPECT_GT(accepted, perScene);
    EXPECT_GT(refused, 5 * perScene);
    std::printf("%d mutants: %d accepted (%d steps each, %d with non-finite output, %d failed to build or step), "
                "%d refused (%d without a location), %d over %.0f s of CPU; slowest %.3f s of CPU\n",
                accepted + refused, accepted, steps, nonFinite, otherErrors, refused, unlocated, slow,
                limit, worst);
}

}  // namespace
