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

AtomicFile::AtomicFile(std::filesystem::path target)
    : target_(std::move(target)), temp_(tempPathFor(target_)) {
    errno = 0;
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_) fail("cannot create", temp_, errno);
}

AtomicFile::~AtomicFile() {
    if (committed_) return;
    out_.close();
    std::error_code ignored;  // best effort: we may already be unwinding an error
    std::filesystem::remove(temp_, ignored);
}

void AtomicFile::commit() {
    errno = 0;
    out_.flush();
    if (!out_) fail("cannot write", temp_, errno);
    out_.close();
    if (out_.fail()) fail("cannot close", temp_, errno);
    std::error_code ec;
    std::filesystem::rename(temp_, target_, ec);
    if (ec) throw Error("cannot rename '" + temp_.string() + "' to '" + target_.string() + "': " + ec.message());
    committed_ = true;
}

}  // namespace spindrift::io
