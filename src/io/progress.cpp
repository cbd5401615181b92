#include "io/progress.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace spindrift::io {

namespace {

std::string clockText(double seconds) {
    const auto s = static_cast<std::uint64_t>(std::llround(std::max(seconds, 0.0)));
    if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
    return fmt::format("{}:{:02}", s / 60, s % 60);
}

}  // namespace

ProgressReporter::ProgressReporter(std::ostream& out, std::uint64_t totalSteps, Options options)
    : out_(out), total_(totalSteps), options_(options) {}

std::string ProgressReporter::line(std::uint64_t done, std::uint64_t total, std::uint64_t alive,
                                   double secondsPerStep) {
    const double percent = total == 0 ? 100.0 : 100.0 * static_cast<double>(done) / static_cast<double>(total);
    const double eta = secondsPerStep * static_cast<double>(total - std::min(done, total));
    return fmt::format("step {}/{} ({:.0f}%)  alive {}  {:.2f} ms/step  ETA {}", done, total,
                       std::floor(percent), alive, 1000.0 * secondsPerStep, clockText(eta));
}

std::string ProgressReporter::frameLine(std::uint64_t done, std::uint64_t total, double secondsPerFrame) {
    const double percent = total == 0 ? 100.0 : 100.0 * static_cast<double>(done) / static_cast<double>(total);
    const double eta = secondsPerFrame * static_cast<double>(total - std::min(done, total));
    const double fps = secondsPerFrame > 0.0 ? 1.0 / secondsPerFrame : 0.0;
    return fmt::format("frame {}/{} ({:.0f}%)  {:.1f} fps  ETA {}", done, total, std::floor(percent), fps,
                       clockText(eta));
}

void ProgressReporter::show(std::uint64_t done, std::uint64_t alive, double secondsPerStep,
                            double elapsed) {
    const std::string text = options_.unit == Unit::Frames ? frameLine(done, total_, secondsPerStep)
                                                           : line(done, total_, alive, secondsPerStep);
    if (options_.terminal) {
        // Pad over the tail of a longer previous line instead of relying on
        // terminal escape codes.
        const std::size_t pad = lastLength_ > text.size() ? lastLength_ - text.size() : 0;
        lastLength_ = text.size();
        out_ << fmt::format("\r{}{:{}}", text, "", pad) << std::flush;  // one write per report
    } else {
        out_ << text + '\n' << std::flush;
    }
    shown_ = true;
    lastShown_ = elapsed;
    lastDone_ = done;
}

double ProgressReporter::recentSecondsPerStep(std::uint64_t done, double elapsed) const {
    // Steps get slower as an emitter fills up, so the rate since the last
    // report predicts the rest of the run better than the average since start.
    // Wall time includes cache writes, so the ETA accounts for them too.
    if (shown_ && done > lastDone_) return (elapsed - lastShown_) / static_cast<double>(done - lastDone_);
    return done == 0 ? 0.0 : elapsed / static_cast<double>(done);
}

void ProgressReporter::update(std::uint64_t done, std::uint64_t alive, double elapsed) {
    if (elapsed < options_.quietStart) return;
    const double interval = options_.terminal ? options_.redrawInterval : options_.plainInterval;
    // The first plain line waits a full interval too: a 1 s run logs nothing.
    const double since = shown_ ? elapsed - lastShown_ : (options_.terminal ? interval : elapsed);
    if (since >= interval) show(done, alive, recentSecondsPerStep(done, elapsed), elapsed);
}

void ProgressReporter::finish(std::uint64_t done, std::uint64_t alive, double elapsed) {
    if (!shown_) return;
    // The last report gives the whole run's average.
    show(done, alive, done == 0 ? 0.0 : elapsed / static_cast<double>(done), elapsed);
    if (options_.terminal) out_ << '\n' << std::flush;  // leave the final line in place
}

}  // namespace spindrift::io
