// Writing a file so that no reader ever sees it half written.
#pragma once

#include <filesystem>
#include <fstream>
#include <ostream>

namespace spindrift::io {

/// A file buffer that keeps the errno of its first failed write, flush or
/// close: a stream only says that it failed, and by the time a caller looks
/// (commit) errno is long gone, so a full disk read "I/O error" instead of
/// "No space left on device".
class ErrnoFileBuf : public std::filebuf {
public:
    /// errno of the first failure, 0 if none.
    int error() const { return error_; }

protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char_type* s, std::streamsize n) override;
    int sync() override;

private:
    void note(bool failed);
    int error_ = 0;
};

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
    ErrnoFileBuf buffer_;
    std::ostream out_{&buffer_};
    bool committed_ = false;
};

}  // namespace spindrift::io
