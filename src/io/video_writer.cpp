#include "io/video_writer.h"

#include <fmt/format.h>
#include <spindrift/effects.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>

namespace spindrift::io {

namespace fs = std::filesystem;

namespace {

/// One word for sh: single-quoted, with embedded quotes closed and escaped.
std::string shellQuoted(const std::string& text) {
    std::string quoted(1, '\'');
    for (char c : text) {
        if (c == '\'') {
            quoted += "'\\''";
        } else {
            quoted += c;
        }
    }
    quoted += '\'';
    return quoted;
}

/// A fresh, empty file in the temporary directory for ffmpeg's messages.
fs::path makeLogFile() {
    std::string pattern = (fs::temp_directory_path() / "spindrift-ffmpeg-XXXXXX").string();
    const int fd = ::mkstemp(pattern.data());
    if (fd < 0) throw Error(fmt::format("cannot create a log file for ffmpeg: {}", std::strerror(errno)));
    ::close(fd);
    return pattern;
}

}  // namespace

std::optional<fs::path> findOnPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    if (path == nullptr) return std::nullopt;
    std::string_view rest(path);
    while (true) {
        const std::size_t colon = rest.find(':');
        const std::string_view dir = rest.substr(0, colon);
        const fs::path candidate = (dir.empty() ? fs::path(".") : fs::path(dir)) / name;
        std::error_code ec;
        if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return candidate;
        if (colon == std::string_view::npos) return std::nullopt;
        rest.remove_prefix(colon + 1);
    }
}

VideoWriter::VideoWriter(const fs::path& ffmpeg, const fs::path& target, std::uint32_t width, std::uint32_t height,
                         double fps)
    : target_(target), temp_(fs::path(target) += ".tmp"), log_(makeLogFile()), width_(width), height_(height) {
    // A write to a pipe whose reader (ffmpeg) has died raises SIGPIPE, which
    // would kill the process without a word; ignored, the write fails with
    // EPIPE and we report ffmpeg's own messages instead.
    std::signal(SIGPIPE, SIG_IGN);
    // -f mp4: the temporary name's extension does not say which container.
    // The pad filter rounds odd sizes up to even ones, which yuv420p needs.
    const std::string command = fmt::format(
        "{} -y -loglevel error -f rawvideo -pix_fmt rgba -s {}x{} -r {} -i - "
        "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p -crf 20 -f mp4 {} >{} 2>&1",
        shellQuoted(ffmpeg.string()), width, height, fps, shellQuoted(temp_.string()), shellQuoted(log_.string()));
    pipe_ = ::popen(command.c_str(), "w");
    if (pipe_ == nullptr) {
        std::error_code ignored;
        fs::remove(log_, ignored);
        throw Error(fmt::format("cannot start ffmpeg ({}): {}", ffmpeg.string(), std::strerror(errno)));
    }
}

VideoWriter::~VideoWriter() {
    if (pipe_ != nullptr) closePipe();
    std::error_code ignored;  // best effort: we may be unwinding an error
    if (!finished_) fs::remove(temp_, ignored);
    fs::remove(log_, ignored);
}

int VideoWriter::closePipe() {
    const int status = ::pclose(pipe_);
    pipe_ = nullptr;
    if (status == -1 || !WIFEXITED(status)) return -1;
    return WEXITSTATUS(status);
}

std::string VideoWriter::readLog() const {
    std::ifstream in(log_);
    std::ostringstream text;
    text << in.rdbuf();
    std::string log = text.str();
    while (!log.empty() && (log.back() == '\n' || log.back() == '\r')) log.pop_back();
    return log.empty() ? std::string("(ffmpeg printed nothing)") : log;
}

void VideoWriter::failWithLog(const std::string& what) {
    const int code = pipe_ != nullptr ? closePipe() : -1;
    const std::string exit = code >= 0 ? fmt::format("exit status {}", code) : std::string("killed by a signal");
    throw Error(fmt::format("ffmpeg {} writing '{}' ({}): {}", what, target_.string(), exit, readLog()));
}

void VideoWriter::write(const Frame& frame) {
    if (pipe_ == nullptr) throw Error(fmt::format("video '{}' is already finished", target_.string()));
    if (frame.width != width_ || frame.height != height_ || frame.rgba.size() != std::size_t{width_} * height_ * 4) {
        throw Error(fmt::format("video '{}' is {} x {}, got a {} x {} frame", target_.string(), width_, height_,
                                frame.width, frame.height));
    }
    if (std::fwrite(frame.rgba.data(), 1, frame.rgba.size(), pipe_) != frame.rgba.size()) {
        failWithLog("stopped reading frames");
    }
}

void VideoWriter::finish() {
    if (pipe_ == nullptr) throw Error(fmt::format("video '{}' is already finished", target_.string()));
    // pclose flushes the last frames and waits for ffmpeg to write the file.
    const bool flushed = std::fflush(pipe_) == 0;
    const int code = closePipe();
    if (!flushed || code != 0) {
        const std::string exit = code >= 0 ? fmt::format("exit status {}", code) : std::string("killed by a signal");
        throw Error(fmt::format("ffmpeg failed writing '{}' ({}): {}", target_.string(), exit, readLog()));
    }
    std::error_code ec;
    fs::rename(temp_, target_, ec);
    if (ec) {
        throw Error(fmt::format("cannot rename '{}' to '{}': {}", temp_.string(), target_.string(), ec.message()));
    }
    finished_ = true;
}

}  // namespace spindrift::io
