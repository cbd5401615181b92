#include <spindrift/scene.h>

#include <fmt/format.h>

#include <utility>

namespace spindrift {

namespace {

// "file:line:col: key.path: message"; the position and the key path are left
// out when unknown (line 0: e.g. a file that cannot be opened).
std::string composeWhat(const std::string& file, int line, int column, const std::string& keyPath,
                        const std::string& message) {
    std::string what = file;
    if (line > 0) {
        what += fmt::format(":{}:{}", line, column);
    }
    what += ": ";
    if (!keyPath.empty()) {
        what += keyPath + ": ";
    }
    return what + message;
}

}  // namespace

SceneError::SceneError(std::string file, int line, int column, std::string keyPath,
                       std::string message)
    : Error(composeWhat(file, line, column, keyPath, message)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      keyPath_(std::move(keyPath)),
      message_(std::move(message)) {}

}  // namespace spindrift
