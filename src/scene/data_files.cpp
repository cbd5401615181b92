#include "scene/data_files.h"

#include "scene/limits.h"

#include <spindrift/scene.h>

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace spindrift::scene {

namespace {

struct Token {
    std::string_view text;
    int column = 1;  ///< 1-based
};

// Walks the meaningful lines of a data file: blank lines and lines whose first
// non-blank character is '#' are skipped. Errors carry file, line and column.
class LineReader {
public:
    LineReader(const DataFileRef& ref, const std::string& text) : ref_(ref), text_(text) {}

    bool next() {
        while (pos_ < text_.size()) {
            const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
            std::string_view line(text_.data() + pos_, end - pos_);
            pos_ = end + 1;
            ++line_;
            split(line);
            if (!tokens_.empty() && tokens_[0].text[0] != '#') {
                return true;
            }
        }
        tokens_.clear();
        // Errors about a missing line point at the file's last line (a line
        // past the end is one an editor cannot show), line 1 when it is empty.
        line_ = std::max(line_, 1);
        return false;
    }

    int line() const { return line_; }
    std::size_t size() const { return tokens_.size(); }
    const Token& token(std::size_t i) const { return tokens_[i]; }

    [[noreturn]] void fail(int column, const std::string& message) const {
        throw SceneError(ref_.display, line_, column, ref_.keyPath, message);
    }

    void expectCount(std::size_t n, const std::string& what) const {
        if (tokens_.size() != n) {
            const int column = tokens_.size() > n ? tokens_[n].column : 1;
            fail(column,
                 fmt::format("expected {} ({} values), got {} values", what, n, tokens_.size()));
        }
    }

    double number(std::size_t i) const {
        const Token& t = tokens_[i];
        double v = 0.0;
        const char* end = t.text.data() + t.text.size();
        const auto [ptr, ec] = std::from_chars(t.text.data(), end, v);
        if (ec != std::errc() || ptr != end) {
            fail(t.column, fmt::format("expected a number, got \"{}\"", t.text));
        }
        if (!std::isfinite(v) || !std::isfinite(static_cast<float>(v))) {
            fail(t.column, fmt::format("expected a finite number, got {}", t.text));
        }
        return v;
    }

    std::int64_t integer(std::size_t i, std::int64_t lo, std::int64_t hi) const {
        const Token& t = tokens_[i];
        std::int64_t v = 0;
        const char* end = t.text.data() + t.text.size();
        const auto [ptr, ec] = std::from_chars(t.text.data(), end, v);
        if (ec != std::errc() || ptr != end || v < lo || v > hi) {
            fail(t.column,
                 fmt::format("expected an integer in [{}, {}], got \"{}\"", lo, hi, t.text));
        }
        return v;
    }

private:
    void split(std::string_view line) {
        tokens_.clear();
        std::size_t i = 0;
        while (i < line.size()) {
            while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) {
                ++i;
            }
            const std::size_t begin = i;
            while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') {
                ++i;
            }
            if (i > begin) {
                tokens_.push_back({line.substr(begin, i - begin), static_cast<int>(begin) + 1});
            }
        }
    }

    const DataFileRef& ref_;
    const std::string& text_;
    std::size_t pos_ = 0;
    int line_ = 0;
    std::vector<Token> tokens_;
};

void expectMagic(LineReader& in, std::string_view magic, std::size_t count,
                 const std::string& layout) {
    if (!in.next()) {
        in.fail(1, fmt::format("empty file: expected the header \"{}\"", layout));
    }
    if (in.token(0).text != magic) {
        in.fail(1, fmt::format("expected the header \"{}\", got \"{}\"", layout, in.token(0).text));
    }
    in.expectCount(count, "the header \"" + layout + "\"");
    if (in.token(1).text != "1") {
        in.fail(in.token(1).column,
                fmt::format("unsupported {} version \"{}\" (this build reads 1)", magic,
                            in.token(1).text));
    }
}

void readFlowHeader(LineReader& in, FlowFieldDef& field) {
    const std::string layout = "spindrift-flow 1 nx ny nz minx miny minz maxx maxy maxz";
    expectMagic(in, "spindrift-flow", 11, layout);
    field.nx = static_cast<std::uint32_t>(in.integer(2, 1, kMaxFlowAxis));
    field.ny = static_cast<std::uint32_t>(in.integer(3, 1, kMaxFlowAxis));
    field.nz = static_cast<std::uint32_t>(in.integer(4, 1, kMaxFlowAxis));
    for (int a = 0; a < 3; ++a) {
        field.boundsMin[a] = static_cast<float>(in.number(5 + a));
        field.boundsMax[a] = static_cast<float>(in.number(8 + a));
    }
    for (int a = 0; a < 3; ++a) {
        if (!(field.boundsMax[a] > field.boundsMin[a])) {
            in.fail(in.token(8 + a).column,
                    fmt::format("expected max > min along {}, got min {} max {}", "xyz"[a],
                                field.boundsMin[a], field.boundsMax[a]));
        }
    }
}

}  // namespace

std::optional<std::string> readWholeFile(const std::filesystem::path& path, std::size_t maxBytes,
                                         std::string& error) {
    // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused
    // below like every other file that is not a regular one (/dev/zero,
    // /dev/urandom, a directory), whose size says nothing of what it yields.
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        error = std::strerror(errno);
        return std::nullopt;
    }
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } const closer{fd};
    struct stat info {};
    if (::fstat(fd, &info) != 0) {
        error = std::strerror(errno);
        return std::nullopt;
    }
    if (S_ISDIR(info.st_mode)) {
        error = "is a directory, not a file";
        return std::nullopt;
    }
    if (!S_ISREG(info.st_mode)) {
        error = "is not a regular file (a device, pipe or socket cannot be read as data)";
        return std::nullopt;
    }
    const auto tooLarge = [&](std::string_view size) {
        error = fmt::format("is {} bytes, more than the limit of {} bytes", size, maxBytes);
        return std::nullopt;
    };
    if (static_cast<std::uint64_t>(info.st_size) > maxBytes) {
        return tooLarge(std::to_string(info.st_size));
    }
    // Read at most one byte past the limit: a file that grows while it is
    // read is refused too, and nothing is read without bound.
    std::string text(static_cast<std::size_t>(info.st_size), '\0');
    std::size_t used = 0;
    for (;;) {
        if (used == text.size()) {
            if (used > maxBytes) {
                return tooLarge("more than " + std::to_string(maxBytes));
            }
            text.resize(std::min(maxBytes + 1, std::max<std::size_t>(2 * used, 4096)));
        }
        const ssize_t n = ::read(fd, text.data() + used, text.size() - used);
        if (n < 0) {
            if (errno == EINTR) {
                continue;
            }
            error = std::strerror(errno);
            return std::nullopt;
        }
        if (n == 0) {
            break;
        }
        used += static_cast<std::size_t>(n);
    }
    text.resize(used);
    return text;
}

void readFlowFile(const DataFileRef& ref, const std::string& text, FlowFieldDef& field) {
    LineReader in(ref, text);
    readFlowHeader(in, field);
    const std::size_t count = static_cast<std::size_t>(field.nx) * field.ny * field.nz;
    if (static_cast<std::int64_t>(count) > kMaxFlowSamples) {
        in.fail(in.token(2).column, fmt::format("{} x {} x {} samples is more than the limit {}",
                                                field.nx, field.ny, field.nz, kMaxFlowSamples));
    }
    field.velocities.clear();
    field.velocities.reserve(count);
    while (field.velocities.size() < count) {
        if (!in.next()) {
            in.fail(1, fmt::format("file ends after {} of {} velocity lines \"vx vy vz\"",
                                   field.velocities.size(), count));
        }
        in.expectCount(3, "a velocity \"vx vy vz\"");
        field.velocities.emplace_back(in.number(0), in.number(1), in.number(2));
    }
    if (in.next()) {
        in.fail(1, fmt::format("expected exactly {} velocity lines, found more", count));
    }
}

std::vector<float> readCubeMapFile(const DataFileRef& ref, const std::string& text,
                                   std::uint32_t& res) {
    LineReader in(ref, text);
    expectMagic(in, "spindrift-cubemap", 3, "spindrift-cubemap 1 res");
    res = static_cast<std::uint32_t>(in.integer(2, 2, kMaxCubeResolution));
    const std::size_t rows = 6u * res;
    std::vector<float> depths;
    depths.reserve(rows * res);
    for (std::size_t row = 0; row < rows; ++row) {
        if (!in.next()) {
            in.fail(1, fmt::format("file ends after {} of {} rows (6 faces x {} rows)", row, rows,
                                   res));
        }
        in.expectCount(res, fmt::format("a row of {} depths", res));
        for (std::size_t i = 0; i < res; ++i) {
            const double depth = in.number(i);
            if (!(depth > 0.0)) {
                in.fail(in.token(i).column,
                        fmt::format("expected a depth > 0 (m), got {}", in.token(i).text));
            }
            depths.push_back(static_cast<float>(depth));
        }
    }
    if (in.next()) {
        in.fail(1, fmt::format("expected exactly {} rows of depths, found more", rows));
    }
    return depths;
}

}  // namespace spindrift::scene
