#include "exactpixels/base/input_file.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace exactpixels {

namespace {

[[noreturn]] void fail(const std::filesystem::path& path, std::string_view kind,
                       const std::string& reason) {
    throw Error(
        fmt::format("{}: cannot read the {} file ({})", path.string(), kind, reason));
}

/// Closes a file descriptor when the reading ends, however it ends.
struct Descriptor {
    int fd;
    ~Descriptor() { ::close(fd); }
};

} // namespace

std::string read_input_file(const std::filesystem::path& path, std::string_view kind,
                            std::size_t max_bytes, InputKind input) {
    // O_NONBLOCK: opening a FIFO must not wait for a writer before we can refuse it.
    const int flags =
        O_RDONLY | O_CLOEXEC | (input == InputKind::regular_file ? O_NONBLOCK : 0);
    const Descriptor file{::open(path.c_str(), flags)};
    if (file.fd < 0) {
        fail(path, kind, std::strerror(errno));
    }
    struct stat info {};
    if (::fstat(file.fd, &info) != 0) {
        fail(path, kind, std::strerror(errno));
    }
    if (S_ISDIR(info.st_mode)) {
        fail(path, kind, "it is a directory");
    }
    if (input == InputKind::regular_file && !S_ISREG(info.st_mode)) {
        fail(path, kind, "it is not a regular file (a FIFO or a device?)");
    }
    if (S_ISREG(info.st_mode) && static_cast<std::uintmax_t>(info.st_size) > max_bytes) {
        fail(
            path, kind,
            fmt::format("{} bytes is more than the {} allowed", info.st_size, max_bytes));
    }
    std::string bytes;
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n < 0) {
            fail(path, kind, std::strerror(errno));
        }
        if (n == 0) {
            return bytes;
        }
        if (static_cast<std::size_t>(n) > max_bytes - bytes.size()) {
            fail(path, kind, fmt::format("more than the {} bytes allowed", max_bytes));
        }
        bytes.append(buffer, static_cast<std::size_t>(n));
    }
}

} // namespace exactpixels
