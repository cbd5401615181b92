// Writing a file so that no reader ever sees it half written.
#pragma once

#include <filesystem>
#include <fstream>
#include <ostream>

namespace spindrift::io {

/// Writes to a temporary file beside `target` and renames it over `target` on
/// commit(). rename() within one directory replaces the file atomically on
/// POSIX, so a crash or a full disk leaves either the old file or the new one,
/// never a truncated cache that a renderer would silently load.
class AtomicFile {
public:
    /// Opens the temporary file; throws spindrift::Error if it cannot.
    explicit AtomicFile(std::filesystem::path target);
    /// Removes the temporary file unless commit() succeeded.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return out_; }
    /// Flushes, closes and renames into place; throws spindrift::Error on any
    /// write failure (checked here once, not after every insertion).
    void commit();

private:
    std::filesystem::path target_;
    std::filesystem::path temp_;
    std::ofstream out_;
    bool committed_ = false;
};

}  // namespace spindrift::io
