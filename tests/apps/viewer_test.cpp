// `spindrift view` under Xvfb: the window, swapchain, blit and ImGui overlay
// run for a few frames with Vulkan validation on and report no message.
#include "apps/app_test_util.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

const fs::path kCli = SPINDRIFT_CLI_PATH;
const fs::path kSource = SPINDRIFT_SOURCE_DIR;

using spindrift::test::quoted;
using spindrift::test::Result;

class ViewerTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) {
            GTEST_SKIP() << "xvfb-run is not installed (package xvfb)";
        }
        dir_ = fs::temp_directory_path() / ("spindrift-view-" + std::to_string(::getpid()) + "-" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    /// `spindrift view ARGS` in a virtual X server, validation on. Leaks that
    /// LeakSanitizer finds inside libX11, Mesa and GLFW (caches they keep
    /// for the process's life) are suppressed by tests/apps/lsan_viewer.supp;
    /// our own code is not listed there.
    Result view(const std::string& args) {
        return spindrift::test::runCaptured(
            "cd " + quoted(kSource) + " && SPINDRIFT_VULKAN_VALIDATION=1 LSAN_OPTIONS=suppressions=" +
                quoted(kSource / "tests/apps/lsan_viewer.supp") + " xvfb-run -a -s '-screen 0 1024x768x24' " +
                quoted(kCli) + " view " + args,
            dir_);
    }

private:
    fs::path dir_;
};

TEST_F(ViewerTest, ShowsFramesWithoutValidationMessages) {
    const Result r = view("scenes/fluid_dam_break_2d.toml --frames 5 --width 320 --height 180");
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("5 frames shown, 0 validation messages"), std::string::npos) << r.out << r.err;
}

TEST_F(ViewerTest, MissingSceneFailsNamingTheFile) {
    const Result r = view("scenes/no_such_scene.toml --frames 1");
    EXPECT_NE(r.code, 0);
    EXPECT_NE(r.err.find("no_such_scene.toml"), std::string::npos) << r.err;
}

}  // namespace
