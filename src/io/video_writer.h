// Frames as an H.264 MP4 video, encoded by an ffmpeg child process.
#pragma once

#include <spindrift/render.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

namespace spindrift::io {

/// The first executable file called `name` in the directories of $PATH, or
/// nullopt. An empty $PATH entry means the current directory, as in sh.
std::optional<std::filesystem::path> findOnPath(const std::string& name);

/// Pipes raw RGBA frames into `ffmpeg ... -c:v libx264 -pix_fmt yuv420p`.
/// The video is written under a temporary name (`<target>.tmp`) and renamed
/// to `target` by finish() only when ffmpeg succeeded, so a failed or
/// interrupted render never leaves a truncated video behind.
class VideoWriter {
  public:
    /// Starts ffmpeg (the executable `ffmpeg`, e.g. from findOnPath) for
    /// frames of width x height at `fps`. Odd sizes are padded by one black
    /// row or column: yuv420p needs even sizes. Throws spindrift::Error if
    /// ffmpeg cannot be started.
    VideoWriter(const std::filesystem::path& ffmpeg, const std::filesystem::path& target, std::uint32_t width,
                std::uint32_t height, double fps);
    /// Stops ffmpeg and removes the temporary file unless finish() succeeded.
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    /// Sends one frame; it must have the size given to the constructor.
    /// Throws spindrift::Error (with ffmpeg's messages) if ffmpeg has failed.
    void write(const Frame& frame);
    /// Closes the pipe, waits for ffmpeg and renames the video into place.
    /// Throws spindrift::Error with ffmpeg's stderr if it failed.
    void finish();

    const std::filesystem::path& target() const { return target_; }

  private:
    [[noreturn]] void failWithLog(const std::string& what);
    int closePipe();
    std::string readLog() const;

    std::filesystem::path target_;
    std::filesystem::path temp_;
    std::filesystem::path log_;  ///< ffmpeg's stderr
    std::uint32_t width_;
    std::uint32_t height_;
    std::FILE* pipe_ = nullptr;
    bool finished_ = false;
};

}  // namespace spindrift::io
