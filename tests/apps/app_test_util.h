// Running the command line tool as users do (a separate process through the
// shell), shared by the CLI and viewer tests.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace spindrift::test {

inline std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// Single quotes for sh; the paths used here hold no single quote.
inline std::string quoted(const std::filesystem::path& path) {
    // Appended piecewise: GCC 12 at -O3 warns falsely (-Wrestrict) on "'" + string.
    std::string text(1, '\'');
    text += path.string();
    text += '\'';
    return text;
}

struct Result {
    int code = -1;  ///< exit status, or -1 if killed by a signal
    std::string out, err;
};

/// Runs `command` in sh with stdout and stderr captured into files in `dir`.
inline Result runCaptured(const std::string& command, const std::filesystem::path& dir) {
    const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
    const std::string full = command + " >" + quoted(out) + " 2>" + quoted(err);
    const int status = std::system(full.c_str());
    Result r;
    if (status != -1 && WIFEXITED(status)) r.code = WEXITSTATUS(status);
    r.out = readFile(out);
    r.err = readFile(err);
    return r;
}

}  // namespace spindrift::test
