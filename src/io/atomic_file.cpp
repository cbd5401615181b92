#include "io/atomic_file.h"

#include <spindrift/effects.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

namespace spindrift::io {

namespace {

std::filesystem::path tempPathFor(const std::filesystem::path& target) {
    // Same directory as the target: rename() is only atomic within one file system.
    std::filesystem::path temp = target;
    temp += ".tmp";
    return temp;
}

[[noreturn]] void fail(const std::string& what, const std::filesystem::path& path, int err) {
    // Streams do not promise to set errno; avoid reporting "Success".
    const char* reason = err != 0 ? std::strerror(err) : "I/O error";
    throw Error(what + " '" + path.string() + "': " + reason);
}

}  // namespace

ErrnoFileBuf::int_type ErrnoFileBuf::overflow(int_type c) {
    errno = 0;
    const int_type r = std::filebuf::overflow(c);
    note(traits_type::eq_int_type(r, traits_type::eof()));
    return r;
}

std::streamsize ErrnoFileBuf::xsputn(const char_type* s, std::streamsize n) {
    errno = 0;
    const std::streamsize written = std::filebuf::xsputn(s, n);
    note(written < n);
    return written;
}

int ErrnoFileBuf::sync() {
    errno = 0;
    const int r = std::filebuf::sync();
    note(r != 0);
    return r;
}

void ErrnoFileBuf::note(bool failed) {
    if (failed && error_ == 0) error_ = errno;
}

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temp_(tempPathFor(target_)) {
    errno = 0;
    if (buffer_.open(temp_, std::ios::out | std::ios::binary | std::ios::trunc) == nullptr) {
        fail("cannot create", temp_, errno);
    }
}

AtomicFile::~AtomicFile() {
    if (committed_) return;
    buffer_.close();
    std::error_code ignored;  // best effort: we may already be unwinding an error
    std::filesystem::remove(temp_, ignored);
}

void AtomicFile::commit() {
    // The reason of the first failed write (a full disk: ENOSPC), which
    // insertions long before this call may have met.
    out_.flush();
    if (!out_) fail("cannot write", temp_, buffer_.error());
    errno = 0;
    if (buffer_.close() == nullptr) fail("cannot close", temp_, buffer_.error() != 0 ? buffer_.error() : errno);
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);
    if (ec) throw Error("cannot rename '" + temp_.string() + "' to '" + target_.string() + "': " + ec.message());
    committed_ = true;
}

}  // namespace spindrift::io
