// A failed write says why (issue 14: a full disk was reported as "I/O error"
// without the reason). The stream only knows that it failed; the buffer keeps
// the errno of the first failed write for commit() to report.
#include "io/atomic_file.h"

#include <spindrift/effects.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

namespace {

// /dev/full is a disk that is always full: every write fails with ENOSPC.
TEST(AtomicFile, BufferKeepsTheErrnoOfAFullDisk) {
    if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
    spindrift::io::ErrnoFileBuf buffer;
    ASSERT_NE(buffer.open("/dev/full", std::ios::out | std::ios::binary), nullptr);
    std::ostream out(&buffer);
    out << std::string(100000, 'x');
    out.flush();
    EXPECT_FALSE(out.good());
    EXPECT_EQ(buffer.error(), ENOSPC) << std::strerror(buffer.error());
}

// Through AtomicFile itself: a file size limit (RLIMIT_FSIZE, set for this
// process and put back at once) makes writes past 4 kB fail with EFBIG, as a
// full disk makes them fail with ENOSPC; commit() must name that reason.
TEST(AtomicFile, CommitReportsTheReasonOfTheFailedWrite) {
    const std::filesystem::path target =
        std::filesystem::temp_directory_path() / ("spindrift-atomic-" + std::to_string(::getpid()) + ".bin");
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    const auto oldSignal = std::signal(SIGXFSZ, SIG_IGN);  // else the write kills the process
    rlimit small = old;
    small.rlim_cur = 4096;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    std::string message;
    try {
        spindrift::io::AtomicFile file(target);
        file.stream() << std::string(1 << 20, 'x');
        file.commit();
    } catch (const spindrift::Error& e) {
        message = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, oldSignal);
    EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
    EXPECT_EQ(message.find("I/O error"), std::string::npos) << message;
    EXPECT_FALSE(std::filesystem::exists(target));
}

}  // namespace
