// MP4 through ffmpeg: the video holds every frame at the frame size, and a
// failing encoder is reported with its messages and leaves no file.
#include "io/video_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

namespace fs = std::filesystem;
using spindrift::io::findOnPath;
using spindrift::io::VideoWriter;

fs::path scratchDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("spindrift-video-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

spindrift::Frame greyFrame(std::uint32_t width, std::uint32_t height, std::uint8_t level) {
    spindrift::Frame frame{width, height, std::vector<std::uint8_t>(std::size_t{width} * height * 4, level)};
    return frame;
}

/// stdout of a shell command.
std::string capture(const std::string& command) {
    std::string text;
    if (std::FILE* pipe = ::popen(command.c_str(), "r")) {
        char buffer[256];
        while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) text += buffer;
        ::pclose(pipe);
    }
    return text;
}

TEST(IoVideoWriter, FindOnPathFindsShAndNotNonsense) {
    EXPECT_TRUE(findOnPath("sh").has_value());
    EXPECT_FALSE(findOnPath("spindrift-no-such-program").has_value());
}

TEST(IoVideoWriter, WritesEveryFrameAtTheFrameSize) {
    const auto ffmpeg = findOnPath("ffmpeg");
    if (!ffmpeg) GTEST_SKIP() << "ffmpeg is not installed";
    const auto ffprobe = findOnPath("ffprobe");
    if (!ffprobe) GTEST_SKIP() << "ffprobe is not installed";
    const fs::path dir = scratchDir("frames");
    {
        VideoWriter video(*ffmpeg, dir / "v.mp4", 64, 48, 24.0);
        for (int i = 0; i < 7; ++i) video.write(greyFrame(64, 48, static_cast<std::uint8_t>(30 * i)));
        video.finish();
    }
    ASSERT_TRUE(fs::exists(dir / "v.mp4"));
    EXPECT_FALSE(fs::exists(dir / "v.mp4.tmp"));
    const std::string probe = capture(ffprobe->string() +
                                      " -v error -count_frames -select_streams v:0 -show_entries "
                                      "stream=width,height,nb_read_frames -of csv=p=0 '" +
                                      (dir / "v.mp4").string() + "'");
    EXPECT_EQ(probe, "64,48,7\n");
    fs::remove_all(dir);
}

TEST(IoVideoWriter, FailingEncoderIsReportedAndLeavesNoFile) {
    // A stand-in "ffmpeg" that complains and fails, as a broken install would.
    const fs::path dir = scratchDir("failing");
    const fs::path fake = dir / "ffmpeg";
    std::ofstream(fake) << "#!/bin/sh\necho 'Unknown encoder libx264' >&2\nexit 1\n";
    fs::permissions(fake, fs::perms::owner_all);
    try {
        VideoWriter video(fake, dir / "v.mp4", 16, 16, 30.0);
        for (int i = 0; i < 3; ++i) video.write(greyFrame(16, 16, 0));
        video.finish();
        FAIL() << "a failing ffmpeg was not reported";
    } catch (const spindrift::Error& e) {
        EXPECT_NE(std::string(e.what()).find("Unknown encoder libx264"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / "v.mp4"));
    EXPECT_FALSE(fs::exists(dir / "v.mp4.tmp"));
    fs::remove_all(dir);
}

}  // namespace
