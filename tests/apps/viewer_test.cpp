// `spindrift view` under Xvfb: the window, swapchain, blit and ImGui overlay
// run for a few frames with Vulkan validation on and report no message; and
// the viewer as a user meets it, driven by a `--script` of input by frame
// (Xvfb has no mouse or keyboard) and checked by its `report` lines.
#include "apps/app_test_util.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

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
            "cd " + quoted(kSource) + " && SPINDRIFT_VULKAN_VALIDATION=1 LSAN_OPTIONS=print_suppressions=0:suppressions=" +
                quoted(kSource / "tests/apps/lsan_viewer.supp") + " xvfb-run -a -s '-screen 0 1024x768x24' " +
                quoted(kCli) + " view " + args,
            dir_);
    }

    /// `view SCENE ARGS --script` with `script` as the script's text.
    Result viewScripted(const std::string& args, const std::string& script) {
        const fs::path file = dir_ / "script.txt";
        std::ofstream(file) << script;
        return view(args + " --script " + quoted(file));
    }

    const fs::path& dir() const { return dir_; }

private:
    fs::path dir_;
};

/// The value of `report FRAME KEY: VALUE` in the viewer's output; fails the
/// test when the viewer did not report it.
std::string reported(const Result& r, int frame, const std::string& key) {
    const std::string prefix = "report " + std::to_string(frame) + " " + key + ":";
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind(prefix, 0) == 0) return line.size() > prefix.size() ? line.substr(prefix.size() + 1) : "";
    }
    ADD_FAILURE() << "no '" << prefix << "' in the output:\n" << r.out << r.err;
    return "";
}

std::vector<double> numbers(const std::string& text) {
    std::istringstream in(text);
    std::vector<double> values;
    for (double v = 0.0; in >> v;) values.push_back(v);
    return values;
}

double number(const Result& r, int frame, const std::string& key) {
    const std::vector<double> v = numbers(reported(r, frame, key));
    return v.empty() ? -1.0 : v[0];
}

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

// Playback follows the wall clock: the world is never ahead of the time
// since the first frame, pausing stops it and N while paused is exactly one
// step of the scene's dt (1/60 s).
TEST_F(ViewerTest, PlaysByTheClockPausesAndSteps) {
    const Result r = viewScripted("scenes/fluid_dam_break_2d.toml --frames 40 --width 320 --height 180",
                                  "10 report\n"
                                  "11 key space\n"
                                  "13 report\n"
                                  "20 report\n"
                                  "21 key n\n"
                                  "23 report\n");
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    const double dt = 1.0 / 60.0;
    const double at10 = number(r, 10, "time"), wall10 = number(r, 10, "wall");
    EXPECT_GT(at10, 0.0);
    EXPECT_LE(at10, wall10 + 1e-6) << "the world ran ahead of the clock";
    const double speed = number(r, 10, "speed");
    EXPECT_GT(speed, 0.0);
    EXPECT_LE(speed, 1.0 + 1e-9);
    EXPECT_EQ(reported(r, 13, "paused"), "1");
    EXPECT_DOUBLE_EQ(number(r, 20, "time"), number(r, 13, "time"));
    EXPECT_NEAR(number(r, 23, "time") - number(r, 20, "time"), dt, 1e-6);
}

// The panel starts as a narrow column (under a quarter of the window's width
// and area), lists fires and bodies by the showcase's names, and H hides and
// shows it.
TEST_F(ViewerTest, PanelIsNarrowNamesFiresAndBodiesAndHidesWithH) {
    const Result r = viewScripted("scenes/showcase.toml --frames 10",
                                  "4 report\n"
                                  "5 key h\n"
                                  "7 report\n"
                                  "7 key h\n"
                                  "9 report\n");
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    const std::vector<double> window = numbers(reported(r, 4, "window"));
    const std::vector<double> panel = numbers(reported(r, 4, "panel"));  // shown x y width height
    ASSERT_EQ(window.size(), 2u);
    ASSERT_EQ(panel.size(), 5u);
    EXPECT_EQ(window[0], 960.0);
    EXPECT_EQ(panel[0], 1.0);
    EXPECT_LT(panel[3], window[0] / 4);
    EXPECT_LT(panel[3] * panel[4], window[0] * window[1] / 4);
    EXPECT_EQ(reported(r, 4, "fires"), "bonfire, crate fire, barrel fire");
    const std::string bodies = reported(r, 4, "bodies");
    for (const char* name : {"ground", "truck", "log pile", "crate", "gate"}) {
        EXPECT_NE(bodies.find(name), std::string::npos) << name << " in " << bodies;
    }
    EXPECT_EQ(numbers(reported(r, 7, "panel"))[0], 0.0);
    EXPECT_EQ(reported(r, 7, "fires"), "");
    EXPECT_EQ(numbers(reported(r, 9, "panel"))[0], 1.0);
}

// Saving the scene reloads it with the camera as the user left it; a broken
// save shows file:line:col in the window and the old scene keeps playing;
// fixing the file loads it again.
TEST_F(ViewerTest, ReloadsTheSceneKeepingTheCameraAndShowsErrors) {
    const fs::path scene = dir() / "scene.toml";
    const fs::path broken = dir() / "broken.toml";
    const fs::path fixed = dir() / "fixed.toml";
    fs::copy_file(kSource / "scenes/fluid_dam_break_2d.toml", scene);
    fs::copy_file(kSource / "scenes/fluid_dam_break_2d.toml", fixed);
    std::ofstream(broken) << "[camera]\northographic = true\nbogus_key = 1\n";
    const Result r = viewScripted(
        quoted(scene) + " --frames 30 --width 640 --height 360",
        // A left drag of 64 pixels (a fifth of the frame's 360) pans the
        // orthographic camera 2 m x 64 / 360 to the left.
        "2 pointer 400 200\n"
        "3 press left\n"
        "4 pointer 464 200\n"
        "5 release left\n"
        "8 report\n"
        "9 copy " + broken.string() + " " + scene.string() + "\n"
        "12 report\n"
        "14 copy " + fixed.string() + " " + scene.string() + "\n"
        "16 report\n");
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    const std::vector<double> dragged = numbers(reported(r, 8, "camera"));  // eye x y z, ortho height
    ASSERT_EQ(dragged.size(), 4u);
    EXPECT_NEAR(dragged[0], 1.6 - 2.0 * 64.0 / 360.0, 1e-3);
    EXPECT_EQ(reported(r, 8, "error"), "");

    const std::string error = reported(r, 12, "error");
    EXPECT_NE(error.find("scene.toml:3:1:"), std::string::npos) << error;
    EXPECT_NE(error.find("bogus_key"), std::string::npos) << error;
    EXPECT_GT(number(r, 12, "time"), number(r, 8, "time")) << "the old scene stopped playing";

    EXPECT_EQ(reported(r, 16, "error"), "");
    EXPECT_LT(number(r, 16, "time"), number(r, 12, "time")) << "the fixed scene was not loaded afresh";
    EXPECT_EQ(numbers(reported(r, 16, "camera")), dragged);
}

// In fluid_boxes at 640x360 the orthographic camera shows 2 m of height
// centred on (1.6, 0.8): a metre is 180 pixels, window x = 320 + 180 (x -
// 1.6), y = 180 - 180 (y - 0.8). The light crate rests at (1.4, 0.1), window
// (284, 306); dragging it 0.5 m up to window (284, 216) lifts it, held by
// the grab's spring. Then Shift + right removes water at the floor at
// (0.3, 0.1), window (86, 306), and Shift + left pours it back (the scene's
// fluid is at its capacity before) into the empty air at (2.5, 1.4), window
// (482, 72).
TEST_F(ViewerTest, DragsABodyPoursAndRemovesFluid) {
    const Result r = viewScripted("scenes/fluid_boxes.toml --frames 60 --width 640 --height 360",
                                  "2 report\n"
                                  "2 pointer 284 306\n"
                                  "3 press left\n"
                                  "4 pointer 284 216\n"
                                  "30 report\n"
                                  "30 release left\n"
                                  "31 shift on\n"
                                  "31 pointer 86 306\n"
                                  "32 press right\n"
                                  "36 release right\n"
                                  "37 report\n"
                                  "38 pointer 482 72\n"
                                  "39 press left\n"
                                  "43 release left\n"
                                  "44 report\n");
    ASSERT_EQ(r.code, 0) << r.out << r.err;
    const std::vector<double> before = numbers(reported(r, 2, "body light crate"));
    const std::vector<double> held = numbers(reported(r, 30, "body light crate"));
    ASSERT_EQ(before.size(), 2u);
    ASSERT_EQ(held.size(), 2u);
    EXPECT_LT(before[1], 0.2);
    EXPECT_GT(held[1], 0.4) << "the crate was not lifted toward y = 0.6";
    EXPECT_NEAR(held[0], 1.4, 0.1);
    // Camera untouched: the drag moved the crate, not the view.
    EXPECT_EQ(reported(r, 30, "camera"), reported(r, 2, "camera"));

    const double start = number(r, 30, "fluid particles");
    const double erased = number(r, 37, "fluid particles");
    const double poured = number(r, 44, "fluid particles");
    EXPECT_LT(erased, start);
    EXPECT_GT(poured, erased);
}

}  // namespace
