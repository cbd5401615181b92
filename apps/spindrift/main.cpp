// spindrift: the command line tool. `validate` checks scene files, `run`
// simulates one and writes particle caches plus a JSON summary, `render`
// draws one into PNG frames and an MP4 video. Usage and the file formats are
// documented in docs/cli.md.
// Over 500 lines: each command's options, checks and loop are straight-line
// code read top to bottom; the viewer, which has state, is viewer.cpp.
#include "io/cache.h"
#include "io/frame_schedule.h"
#include "io/png_writer.h"
#include "io/progress.h"
#include "io/summary.h"
#include "io/video_writer.h"
#include "validation_report.h"
#include "viewer.h"

#include <spindrift/render.h>
#include <spindrift/scene.h>
#include <spindrift/world.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace spindrift;

// Exit codes: 0 success, 1 the scene or the run failed, 2 bad usage (CLI11's
// own codes are folded into 2 so scripts see one "you called me wrong" value).
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

struct RunOptions {
    std::string scene;
    std::uint32_t steps = 0;
    double seconds = 0.0;
    double dt = 0.0;
    std::string backend;
    std::uint32_t threads = 0;
    std::uint32_t seed = 0;
    std::string out;
    std::uint32_t every = 1;
    std::vector<std::string> formats{"csv"};
    bool quiet = false;
    // Which options were given, so the scene's own values stay otherwise.
    bool hasSteps = false, hasSeconds = false, hasDt = false, hasBackend = false;
    bool hasThreads = false, hasSeed = false;
};

struct RenderOptions {
    std::string scene;
    std::string out;
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    double fps = 0.0;
    double seconds = 0.0;
    double start = 0.0;  ///< world time (s) of the first frame
    std::uint64_t frames = 0;
    std::vector<std::string> formats;  ///< empty: the default (see chooseOutputs)
    int fluidSteps = 0;
    std::string backend;
    std::uint32_t threads = 0;
    bool quiet = false;
    // Which options were given, so the scene's own values stay otherwise.
    bool hasWidth = false, hasHeight = false, hasFps = false, hasSeconds = false, hasFrames = false;
    bool hasFluidSteps = false, hasBackend = false, hasThreads = false;
};

/// CLI11 validator for a finite number > 0 ("inf" and "nan" parse as doubles).
/// An output directory: `--out ''` used to write nothing and exit 0.
CLI::Validator nonEmptyPath() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            return text.empty() ? std::string("must name a directory, got an empty path") : std::string();
        },
        "DIR");
}

CLI::Validator positiveFinite() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            double value = 0.0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
            if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
                value <= 0.0) {
                return "must be a finite number > 0, got '" + text + "'";
            }
            return {};
        },
        "POSITIVE");
}

/// CLI11 validator for a step the world takes: kMinStep to kMaxStep seconds,
/// the same range as the scene's run.dt.
CLI::Validator stepLength() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            double value = 0.0;
            const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
            if (ec != std::errc() || end != text.data() + text.size() || !(value >= kMinStep && value <= kMaxStep)) {
                return fmt::format("must be a time step of {} to {} s, got '{}'", kMinStep, kMaxStep, text);
            }
            return {};
        },
        "SECONDS");
}

std::string backendName(Backend backend) {
    switch (backend) {
        case Backend::Cpu: return "cpu";
        case Backend::Vulkan: return "vulkan";
        case Backend::Auto: return "auto";
    }
    return "unknown";
}

Backend parseBackend(const std::string& name) {
    static const std::map<std::string, Backend> kByName{
        {"cpu", Backend::Cpu}, {"vulkan", Backend::Vulkan}, {"auto", Backend::Auto}};
    return kByName.at(name);  // CLI11 has already checked membership
}

/// Destroys the renderer on every exit path, before its world.
class RendererGuard {
public:
    explicit RendererGuard(RendererId id) : id_(id) {}
    ~RendererGuard() {
        try {
            destroyRenderer(id_);
        } catch (...) {  // nothing useful to do while already leaving
        }
    }
    RendererGuard(const RendererGuard&) = delete;
    RendererGuard& operator=(const RendererGuard&) = delete;
    RendererId id() const { return id_; }

private:
    RendererId id_;
};

/// Destroys the world on every exit path, errors included.
class WorldGuard {
public:
    explicit WorldGuard(WorldId id) : id_(id) {}
    ~WorldGuard() {
        try {
            destroyWorld(id_);
        } catch (...) {  // nothing useful to do while already leaving
        }
    }
    WorldGuard(const WorldGuard&) = delete;
    WorldGuard& operator=(const WorldGuard&) = delete;
    WorldId id() const { return id_; }

private:
    WorldId id_;
};

// validate ---------------------------------------------------------------------

int validateCommand(const std::string& path) {
    const SceneDef scene = loadScene(path);
    std::size_t jets = 0;
    for (const FluidDef& fluid : scene.fluids) jets += fluid.jets.size();
    // Emitters, forces and colliders are always counted; the kinds an effect
    // scene has none of are left out to keep its line short.
    std::string others;
    const std::pair<const char*, std::size_t> counts[] = {{"fluids", scene.fluids.size()}, {"jets", jets},
                                                          {"bodies", scene.bodies.size()},
                                                          {"joints", scene.joints.size()},
                                                          {"fires", scene.fires.size()},
                                                          {"lights", scene.render.lights.size()}};
    for (const auto& [kind, count] : counts) {
        if (count > 0) others += fmt::format(", {}: {}", kind, count);
    }
    fmt::print("{}: ok (emitters: {}, forces: {}, colliders: {}{})\n", path, scene.emitters.size(),
               scene.forces.size(), scene.colliders.size(), others);
    return 0;
}

// run ----------------------------------------------------------------------------

/// Options override the scene; --seconds becomes a step count at the final dt.
void applyOverrides(SceneDef& scene, const RunOptions& o) {
    if (o.hasBackend) scene.world.backend = parseBackend(o.backend);
    // The summary lists every step's own counts: the GPU may not run ahead of
    // the host here (an offline run; caches read the particles back anyway).
    scene.world.framesInFlight = 1;
    if (o.hasThreads) scene.world.threads = o.threads;
    if (o.hasSeed) scene.world.seed = o.seed;
    if (o.hasDt) scene.run.dt = static_cast<float>(o.dt);
    if (o.hasSteps) scene.run.steps = o.steps;
    if (o.hasSeconds) {
        // dt is a float (1/60 is not exact): allow for rounding so that
        // 1 s at 1/60 gives 60 steps, not 61.
        const double steps = std::ceil(o.seconds / static_cast<double>(scene.run.dt) - 1e-6);
        if (steps > std::numeric_limits<std::uint32_t>::max()) {
            throw Error(fmt::format("--seconds {} at dt {} needs more than 2^32 steps", o.seconds, scene.run.dt));
        }
        scene.run.steps = static_cast<std::uint32_t>(std::max(steps, 1.0));
    }
}

/// File stem per emitter (index i = id i + 1): its name, made unique by
/// appending the id when two names would give the same file.
std::vector<std::string> cacheStems(WorldId world) {
    std::vector<std::string> names;
    std::map<std::string, int> uses;
    for (std::uint32_t i = 0; i < emitterCount(world); ++i) {
        names.push_back(emitterDef(world, EmitterId{i + 1}).name);
        ++uses[io::cacheFileName(names.back(), 0, io::CacheFormat::Csv)];
    }
    for (std::uint32_t i = 0; i < names.size(); ++i) {
        if (uses[io::cacheFileName(names[i], 0, io::CacheFormat::Csv)] > 1) names[i] += fmt::format("_{}", i + 1);
    }
    return names;
}

/// File stem per fluid: its name, or "<name>_fluid" when an emitter's stem
/// (or an earlier fluid's) already uses it; then made unique with its id.
std::vector<std::string> fluidStems(WorldId world, const std::vector<std::string>& emitterStems) {
    std::set<std::string> used;
    for (const std::string& stem : emitterStems) used.insert(io::cacheFileName(stem, 0, io::CacheFormat::Csv));
    std::vector<std::string> stems;
    for (std::uint32_t i = 0; i < fluidCount(world); ++i) {
        std::string stem = fluidDef(world, FluidId{i + 1}).name;
        if (stem.empty()) stem = "fluid";
        if (used.count(io::cacheFileName(stem, 0, io::CacheFormat::Csv)) > 0) stem += "_fluid";
        if (used.count(io::cacheFileName(stem, 0, io::CacheFormat::Csv)) > 0) stem += fmt::format("_{}", i + 1);
        used.insert(io::cacheFileName(stem, 0, io::CacheFormat::Csv));
        stems.push_back(stem);
    }
    return stems;
}

/// File stem of the rigid bodies' caches: "bodies", unless an emitter's or a
/// fluid's file already has that name; then "rigid_bodies", then with a number.
std::string bodyStem(const std::vector<std::string>& emitterStems, const std::vector<std::string>& fluidStems) {
    std::set<std::string> used;
    for (const auto* stems : {&emitterStems, &fluidStems}) {
        for (const std::string& stem : *stems) used.insert(io::cacheFileName(stem, 0, io::CacheFormat::Csv));
    }
    std::string stem = "bodies";
    for (int n = 1; used.count(io::cacheFileName(stem, 0, io::CacheFormat::Csv)) > 0; ++n) {
        stem = n == 1 ? std::string("rigid_bodies") : fmt::format("rigid_bodies_{}", n);
    }
    return stem;
}

std::vector<io::CacheFormat> cacheFormats(const std::vector<std::string>& names) {
    std::set<std::string> seen;
    std::vector<io::CacheFormat> formats;
    for (const std::string& name : names) {
        if (!seen.insert(name).second) continue;
        formats.push_back(name == "ply" ? io::CacheFormat::Ply : io::CacheFormat::Csv);
    }
    return formats;
}

/// The file stems of one run's caches: one per emitter and per fluid (index i
/// = id i + 1), and the bodies' (empty: the world has no bodies).
struct CacheStems {
    std::vector<std::string> emitters;
    std::vector<std::string> fluids;
    std::string bodies;
};

/// Writes every emitter's and fluid's particles and the bodies in every
/// format; returns files written.
std::uint64_t dumpCaches(WorldId world, const fs::path& dir, io::BodyCacheStep at, const CacheStems& stems,
                         const std::vector<io::CacheFormat>& formats) {
    const std::uint64_t step = at.step;
    std::uint64_t files = 0;
    for (std::uint32_t i = 0; i < stems.fluids.size(); ++i) {
        const FluidSnapshot particles = readFluid(world, FluidId{i + 1});
        for (io::CacheFormat format : formats) {
            io::writeFluidCache(dir / io::cacheFileName(stems.fluids[i], step, format), particles, format);
            ++files;
        }
    }
    for (std::uint32_t i = 0; i < stems.emitters.size(); ++i) {
        const ParticleSnapshot particles = readParticles(world, EmitterId{i + 1});
        for (io::CacheFormat format : formats) {
            io::writeCache(dir / io::cacheFileName(stems.emitters[i], step, format), particles, format);
            ++files;
        }
    }
    if (!stems.bodies.empty()) {
        const std::vector<BodySnapshot> bodies = readBodies(world);
        for (io::CacheFormat format : formats) {
            io::writeBodyCache(dir / io::cacheFileName(stems.bodies, step, format), bodies, at, format);
            ++files;
        }
    }
    return files;
}

void createOutputDir(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
        throw Error(fmt::format("cannot create output directory '{}': {}", dir.string(),
                                ec ? ec.message() : "a file of that name exists"));
    }
}

io::RunSummary startSummary(const RunOptions& o, const SceneDef& scene, WorldId world) {
    io::RunSummary s;
    s.scene = o.scene;
    s.backend = backendName(scene.world.backend);
    s.threads = scene.world.threads;
    s.seed = scene.world.seed;
    s.dt = scene.run.dt;
    s.every = o.out.empty() ? 0 : o.every;
    if (!o.out.empty()) {
        for (io::CacheFormat f : cacheFormats(o.formats)) s.formats.emplace_back(io::cacheExtension(f));
    }
    for (std::uint32_t i = 0; i < emitterCount(world); ++i) s.emitterNames.push_back(emitterDef(world, EmitterId{i + 1}).name);
    for (const ColliderDef& c : scene.colliders) s.colliderNames.push_back(c.name);
    for (const FluidDef& f : scene.fluids) s.fluidNames.push_back(f.name);
    for (const BodyDef& b : scene.bodies) s.bodyNames.push_back(b.name);
    return s;
}

/// Every fluid's number-density ratio now, for summary.json (each written frame).
io::RunSummary::NumberDensityFrame measureNumberDensity(WorldId world, std::uint64_t step) {
    io::RunSummary::NumberDensityFrame frame;
    frame.step = step;
    for (std::uint32_t i = 0; i < fluidCount(world); ++i) {
        frame.fluids.push_back(measureFluidNumberDensity(world, FluidId{i + 1}));
    }
    return frame;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Steps the world, dumping caches every `every` steps and after the last;
/// fills summary.steps, wallSeconds, cacheFiles and finalBodies. Without
/// --out no summary is written, so only the last step's stats are kept:
/// memory stays flat however long the run.
void simulate(WorldId world, const SceneDef& scene, const RunOptions& o, io::RunSummary& summary) {
    const std::uint64_t total = scene.run.steps;
    const bool dump = !o.out.empty();
    if (dump) summary.steps.reserve(std::min<std::uint64_t>(total, 1u << 20));
    CacheStems stems;
    stems.emitters = cacheStems(world);
    stems.fluids = fluidStems(world, stems.emitters);
    if (bodyCount(world) > 0) stems.bodies = bodyStem(stems.emitters, stems.fluids);
    const auto formats = cacheFormats(o.formats);
    io::ProgressReporter::Options progressOptions;
    progressOptions.terminal = isatty(STDERR_FILENO) != 0;
    io::ProgressReporter progress(std::cerr, total, progressOptions);
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t done = 1; done <= total; ++done) {
        StepStats stats = stepWorld(world, scene.run.dt);
        const io::BodyCacheStep at{done, stats.time};
        if (!dump) summary.steps.clear();
        summary.steps.push_back(std::move(stats));
        if (dump && (done % o.every == 0 || done == total)) {
            summary.cacheFiles += dumpCaches(world, o.out, at, stems, formats);
            if (fluidCount(world) > 0) summary.numberDensity.push_back(measureNumberDensity(world, done));
        }
        if (!o.quiet) progress.update(done, summary.steps.back().alive, secondsSince(start));
    }
    summary.wallSeconds = secondsSince(start);
    summary.finalBodies = readBodies(world);
    const std::uint64_t alive = summary.steps.empty() ? 0 : summary.steps.back().alive;
    if (!o.quiet) progress.finish(total, alive, summary.wallSeconds);
}

void printResult(const io::RunSummary& s, std::uint64_t steps, WorldId world, const RunOptions& o,
                 std::uint64_t files) {
    const std::uint64_t alive = s.steps.empty() ? 0 : s.steps.back().alive;
    const std::string where = o.out.empty() ? std::string() : fmt::format(" to {}", o.out);
    std::uint64_t fluidParticles = 0;
    if (!s.steps.empty()) {
        for (const FluidStepStats& f : s.steps.back().fluids) fluidParticles += f.particles;
    }
    const std::string fluids = fluidCount(world) == 0 ? std::string()
                                                      : fmt::format(", {} fluid particles", fluidParticles);
    fmt::print("{} steps, {:.3f} s simulated, {:.3f} s wall, {} alive{}, {} files written{}\n", steps,
               worldTime(world), s.wallSeconds, alive, fluids, files, where);
}

int runCommand(const RunOptions& o) {
    SceneDef scene = loadScene(o.scene);
    applyOverrides(scene, o);
    // Build first: a scene or backend that fails leaves no empty directory.
    WorldGuard world(buildWorld(scene));
    if (!o.out.empty()) createOutputDir(o.out);
    io::RunSummary summary = startSummary(o, scene, world.id());
    simulate(world.id(), scene, o, summary);
    std::uint64_t files = summary.cacheFiles;
    if (!o.out.empty()) {
        io::writeSummary(fs::path(o.out) / "summary.json", summary);
        ++files;
    }
    printResult(summary, scene.run.steps, world.id(), o, files);
    return 0;
}

// render -------------------------------------------------------------------------------

/// Options override the scene's [world] and [render] values.
void applyRenderOverrides(SceneDef& scene, const RenderOptions& o) {
    if (o.hasBackend) scene.world.backend = parseBackend(o.backend);
    if (o.hasThreads) scene.world.threads = o.threads;
    RenderDef& r = scene.render;
    if (o.hasWidth) r.width = o.width;
    if (o.hasHeight) r.height = o.height;
    if (o.hasFps) r.fps = static_cast<float>(o.fps);
    if (o.hasSeconds) r.seconds = static_cast<float>(o.seconds);
    if (o.hasFluidSteps) {
        // The preset selects the splat style and switches its six steps; the
        // scene's colour, opacity and radius stay.
        const FluidRenderDef steps = FluidRenderDef::upTo(o.fluidSteps);
        r.fluid.style = steps.style;
        r.fluid.sizeFromDensity = steps.sizeFromDensity;
        r.fluid.stretch = steps.stretch;
        r.fluid.refraction = steps.refraction;
        r.fluid.edges = steps.edges;
        r.fluid.splashes = steps.splashes;
        r.fluid.bubbles = steps.bubbles;
    }
}

struct RenderOutputs {
    bool png = false;
    std::optional<fs::path> ffmpeg;  ///< set when an MP4 is written
};

/// MP4 by default when ffmpeg is on PATH; PNG frames when asked for, and
/// instead of a video that cannot be made.
RenderOutputs chooseOutputs(const std::vector<std::string>& formats) {
    const bool wantPng = std::find(formats.begin(), formats.end(), "png") != formats.end();
    const bool wantMp4 = formats.empty() || std::find(formats.begin(), formats.end(), "mp4") != formats.end();
    RenderOutputs outputs;
    outputs.png = wantPng;
    if (wantMp4) {
        outputs.ffmpeg = io::findOnPath("ffmpeg");
        if (!outputs.ffmpeg) {
            std::fprintf(stderr, "ffmpeg not found: writing PNG frames only; install it with tools/install-deps.sh\n");
            outputs.png = true;
        }
    }
    return outputs;
}

std::string frameFileName(std::uint64_t frame) { return fmt::format("frame_{:05}.png", frame); }

int renderCommand(const RenderOptions& o) {
    SceneDef scene = loadScene(o.scene);
    applyRenderOverrides(scene, o);
    validateRenderDef(scene.render);
    const RenderDef& def = scene.render;
    const std::uint64_t frames = o.hasFrames ? o.frames : io::FrameSchedule::frameCount(def.seconds, def.fps);
    const io::FrameSchedule schedule(def.fps, scene.run.dt, o.start);
    const RenderOutputs outputs = chooseOutputs(o.formats);

    // World and renderer first: a scene or a missing Vulkan driver that fails
    // leaves no empty directory.
    WorldGuard world(buildWorld(scene));
    RendererGuard renderer(createRenderer(world.id(), def));
    createOutputDir(o.out);
    const fs::path dir(o.out);
    std::optional<io::VideoWriter> video;
    if (outputs.ffmpeg) {
        video.emplace(*outputs.ffmpeg, dir / (fs::path(o.scene).stem().string() + ".mp4"), def.width, def.height,
                      def.fps);
    }

    io::ProgressReporter::Options progressOptions;
    progressOptions.unit = io::ProgressReporter::Unit::Frames;
    progressOptions.terminal = isatty(STDERR_FILENO) != 0;
    io::ProgressReporter progress(std::cerr, frames, progressOptions);
    const auto start = std::chrono::steady_clock::now();
    std::uint64_t steps = 0;
    // Frames of the second before --start are drawn and dropped: splashes
    // and orientation smoothing advance with drawn frames, so the first kept
    // frame shows them under way.
    const double warmUp = std::min(o.start, 1.0);
    const io::FrameSchedule warmUpSchedule(def.fps, scene.run.dt, o.start - warmUp);
    const auto warmUpFrames = static_cast<std::uint64_t>(std::floor(warmUp * def.fps));
    for (std::uint64_t k = 0; k < warmUpFrames; ++k) {
        for (const std::uint64_t target = warmUpSchedule.stepsBefore(k); steps < target; ++steps) {
            stepWorld(world.id(), scene.run.dt);
        }
        renderFrame(renderer.id());
    }
    for (std::uint64_t k = 0; k < frames; ++k) {
        for (const std::uint64_t target = schedule.stepsBefore(k); steps < target; ++steps) {
            stepWorld(world.id(), scene.run.dt);
        }
        const Frame frame = renderFrame(renderer.id());
        if (outputs.png) io::writePng(dir / frameFileName(k), frame);
        if (video) video->write(frame);
        if (!o.quiet) progress.update(k + 1, 0, secondsSince(start));
    }
    if (video) video->finish();
    const double wall = secondsSince(start);
    if (!o.quiet) progress.finish(frames, 0, wall);

    std::vector<std::string> written;
    if (video) written.push_back(video->target().string());
    if (outputs.png) {
        written.push_back((dir / frameFileName(0)).string() +
                          (frames > 1 ? " .. " + frameFileName(frames - 1) : std::string()));
    }
    return app::finishWithValidationReport(
        fmt::format("{} frames of {}x{} at {:g} fps ({:.3f} s simulated in {} steps), {:.1f} s wall: {}", frames,
                    def.width, def.height, def.fps, worldTime(world.id()), steps, wall, fmt::join(written, ", ")));
}

// command line ---------------------------------------------------------------------

void addRunOptions(CLI::App& run, RunOptions& o) {
    run.add_option("scene", o.scene, "Scene file (TOML)")->required();
    auto* steps = run.add_option("--steps,-n", o.steps, "Number of steps (default: the scene's run.steps)")
                      ->check(CLI::Range(1u, std::numeric_limits<std::uint32_t>::max()));
    auto* seconds = run.add_option("--seconds,-s", o.seconds, "Simulated time in seconds, rounded up to whole steps")
                        ->check(positiveFinite());
    steps->excludes(seconds);
    run.add_option("--dt", o.dt, "Time step in seconds (default: the scene's run.dt)")->check(stepLength());
    run.add_option("--backend,-b", o.backend, "cpu, vulkan or auto (default: the scene's)")
        ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
    run.add_option("--threads,-j", o.threads, "CPU worker threads, 0 = all (default: the scene's)");
    run.add_option("--seed", o.seed, "Seed of the random streams (default: the scene's)");
    auto* out = run.add_option("--out,-o", o.out, "Directory for particle caches and summary.json")->check(nonEmptyPath());
    run.add_option("--every,-e", o.every, "Write caches every K steps and after the last")
        ->capture_default_str()
        ->check(CLI::Range(1u, std::numeric_limits<std::uint32_t>::max()))
        ->needs(out);
    run.add_option("--format,-f", o.formats, "Cache formats, comma separated: csv, ply")
        ->capture_default_str()
        ->delimiter(',')
        ->check(CLI::IsMember({"csv", "ply"}))
        ->needs(out);
    run.add_flag("--quiet,-q", o.quiet, "No progress line on stderr");
}

void noteGiven(const CLI::App& run, RunOptions& o) {
    o.hasSteps = run.count("--steps") > 0;
    o.hasSeconds = run.count("--seconds") > 0;
    o.hasDt = run.count("--dt") > 0;
    o.hasBackend = run.count("--backend") > 0;
    o.hasThreads = run.count("--threads") > 0;
    o.hasSeed = run.count("--seed") > 0;
}

void addRenderOptions(CLI::App& render, RenderOptions& o) {
    render.add_option("scene", o.scene, "Scene file (TOML)")->required();
    render.add_option("--out,-o", o.out, "Directory for the video and the PNG frames")->required()->check(nonEmptyPath());
    render.add_option("--width", o.width, "Frame width in pixels (default: the scene's render.width)")
        ->check(CLI::Range(1u, 16384u));
    render.add_option("--height", o.height, "Frame height in pixels (default: the scene's render.height)")
        ->check(CLI::Range(1u, 16384u));
    render.add_option("--fps", o.fps, "Frames per second (default: the scene's render.fps)")->check(positiveFinite());
    auto* seconds = render.add_option("--seconds,-s", o.seconds, "Video length in seconds (default: render.seconds)")
                        ->check(positiveFinite());
    auto* frames = render.add_option("--frames,-n", o.frames, "Number of frames instead of --seconds")
                       ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{100'000'000}));
    frames->excludes(seconds);
    render.add_option("--start", o.start, "World time (s) of the first frame; earlier steps are simulated, not drawn")
        ->check(CLI::Range(0.0, 1e6));
    render.add_option("--format,-f", o.formats, "Outputs, comma separated: mp4, png (default: mp4 if ffmpeg is found)")
        ->delimiter(',')
        ->check(CLI::IsMember({"png", "mp4"}));
    render.add_option("--fluid-steps", o.fluidSteps, "Fluid splat steps 1..7 of the Sprinkle slides (selects the splat style)")
        ->check(CLI::Range(1, 7));
    render.add_option("--backend,-b", o.backend, "Simulation backend: cpu, vulkan or auto (default: the scene's)")
        ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
    render.add_option("--threads,-j", o.threads, "CPU worker threads, 0 = all (default: the scene's)");
    render.add_flag("--quiet,-q", o.quiet, "No progress line on stderr");
}

void noteRenderGiven(const CLI::App& render, RenderOptions& o) {
    o.hasWidth = render.count("--width") > 0;
    o.hasHeight = render.count("--height") > 0;
    o.hasFps = render.count("--fps") > 0;
    o.hasSeconds = render.count("--seconds") > 0;
    o.hasFrames = render.count("--frames") > 0;
    o.hasFluidSteps = render.count("--fluid-steps") > 0;
    o.hasBackend = render.count("--backend") > 0;
    o.hasThreads = render.count("--threads") > 0;
}

/// Runs a command, turning errors into a message on stderr and exit code 1.
template <class Command>
int reportErrors(Command&& command) {
    try {
        return command();
    } catch (const SceneError& e) {
        std::fprintf(stderr, "%s\n", e.what());  // already "file:line:col: key: message"
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
    }
    return kExitFailure;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"spindrift: simulate and render particle effects and fluids from scene files"};
    app.set_version_flag("--version", fmt::format("spindrift {}", versionString()));
    app.require_subcommand(1);

    std::string validatePath;
    CLI::App* validate = app.add_subcommand("validate", "Check a scene file and report what it holds");
    validate->add_option("scene", validatePath, "Scene file (TOML)")->required();

    RunOptions runOptions;
    CLI::App* run = app.add_subcommand("run", "Simulate a scene, optionally writing caches and a summary");
    addRunOptions(*run, runOptions);

    spindrift::app::ViewOptions viewOptions;
    CLI::App* view = app.add_subcommand("view", "Show a scene in a window as it simulates (docs/cli.md)");
    view->add_option("scene", viewOptions.scene, "Scene file (TOML)")->required();
    view->add_option("--frames", viewOptions.frames, "Show N frames, then exit (0: until closed)");
    view->add_option("--width", viewOptions.width, "Frame width in pixels (default: the scene's)")
        ->check(CLI::Range(1u, 16384u));
    view->add_option("--height", viewOptions.height, "Frame height in pixels (default: the scene's)")
        ->check(CLI::Range(1u, 16384u));
    view->add_option("--backend,-b", viewOptions.backend, "cpu, vulkan or auto (default: the scene's)")
        ->check(CLI::IsMember({"cpu", "vulkan", "auto"}));
    view->add_option("--script", viewOptions.script, "Tests: input and reports by frame (docs/cli.md)")
        ->check(CLI::ExistingFile);
    RenderOptions renderOptions;
    CLI::App* render = app.add_subcommand("render", "Draw a scene into an MP4 video and/or PNG frames");
    addRenderOptions(*render, renderOptions);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : kExitUsage;
    }
    if (validate->parsed()) return reportErrors([&] { return validateCommand(validatePath); });
    if (view->parsed()) return reportErrors([&] { return spindrift::app::viewCommand(viewOptions); });
    if (render->parsed()) {
        noteRenderGiven(*render, renderOptions);
        return reportErrors([&] { return renderCommand(renderOptions); });
    }
    noteGiven(*run, runOptions);
    return reportErrors([&] { return runCommand(runOptions); });
}
