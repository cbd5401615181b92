// `spindrift view --script FILE`: input and checks for tests, read from a
// file and played at given frames, so a test under Xvfb (which has no
// mouse or keyboard to press) drives the viewer through the same handlers as
// the user's input and reads back what it did.
#pragma once

#include <spindrift/errors.h>

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace spindrift::app {

/// One line `FRAME COMMAND ARGS...`: run COMMAND at the start of frame FRAME
/// (0-based). Commands: `key NAME` (space, n, r, h, escape), `pointer X Y`
/// (window units), `press BUTTON` / `release BUTTON` (left, right, middle),
/// `shift on|off`, `copy FROM TO` (replace a file, e.g. the scene), `report`
/// (one line of the viewer's state on stdout).
struct ScriptLine {
    std::uint64_t frame = 0;
    std::string command;
    std::vector<std::string> args;
};

inline std::vector<ScriptLine> loadViewScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(fmt::format("view: cannot open script {}", path));
    std::vector<ScriptLine> lines;
    std::string text;
    for (int number = 1; std::getline(in, text); ++number) {
        std::istringstream words(text);
        ScriptLine line;
        if (!(words >> line.frame)) {
            if (text.find_first_not_of(" \t\r") == std::string::npos || text[text.find_first_not_of(" \t")] == '#') {
                continue;  // blank or comment
            }
            throw Error(fmt::format("{}:{}: expected a frame number", path, number));
        }
        if (!(words >> line.command)) throw Error(fmt::format("{}:{}: expected a command", path, number));
        for (std::string word; words >> word;) line.args.push_back(word);
        lines.push_back(std::move(line));
    }
    return lines;
}

}  // namespace spindrift::app
