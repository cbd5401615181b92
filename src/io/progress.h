// Progress of a long run or render on stderr.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

namespace spindrift::io {

/// Reports "step i/N (p%)  alive A  x ms/step  ETA m:ss" while a run goes
/// (ms/step measured since the previous report), or "frame i/N (p%)
/// x.x fps  ETA m:ss" while a render goes.
/// On a terminal one line is redrawn in place with '\r'; in a log (not a
/// terminal) a plain line is written at most every `plainInterval` seconds, so
/// CI logs stay short. Short runs print nothing: the first report comes only
/// after `quietStart` seconds. Time is passed in, which keeps this testable.
class ProgressReporter {
public:
    /// What is counted: simulation steps (`run`) or video frames (`render`).
    enum class Unit { Steps, Frames };

    struct Options {
        Unit unit = Unit::Steps;
        bool terminal = false;
        double quietStart = 0.5;     ///< s before anything is shown
        double redrawInterval = 0.1; ///< s between terminal redraws
        double plainInterval = 2.0;  ///< s between plain lines
    };

    ProgressReporter(std::ostream& out, std::uint64_t totalSteps, Options options);

    /// After each step (frame): `done` steps (frames) taken, `elapsed` wall
    /// seconds since start; `alive` is not shown for frames.
    void update(std::uint64_t done, std::uint64_t alive, double elapsed);
    /// At the end: a last report, only if progress was shown at all.
    void finish(std::uint64_t done, std::uint64_t alive, double elapsed);

    /// The report text, without '\r' or newline; the ETA assumes the
    /// remaining steps take `secondsPerStep` each.
    static std::string line(std::uint64_t done, std::uint64_t total, std::uint64_t alive,
                            double secondsPerStep);
    /// The same for frames: rate in frames per second of wall time.
    static std::string frameLine(std::uint64_t done, std::uint64_t total, double secondsPerFrame);

private:
    void show(std::uint64_t done, std::uint64_t alive, double secondsPerStep, double elapsed);
    double recentSecondsPerStep(std::uint64_t done, double elapsed) const;

    std::ostream& out_;
    std::uint64_t total_;
    Options options_;
    bool shown_ = false;
    double lastShown_ = 0.0;     ///< elapsed time of the last report
    std::uint64_t lastDone_ = 0; ///< steps done at the last report
    std::size_t lastLength_ = 0;
};

}  // namespace spindrift::io
