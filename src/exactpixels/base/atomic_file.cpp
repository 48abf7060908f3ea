#include "exactpixels/base/atomic_file.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <random>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace exactpixels {

namespace {

/// How many fresh names are tried before giving up (each is 48 random bits).
constexpr int max_temporary_attempts = 16;

[[noreturn]] void fail(const std::filesystem::path& path, std::string_view kind,
                       const std::string& reason) {
    throw Error(
        fmt::format("{}: cannot write {} file ({})", path.string(), kind, reason));
}

/// The folder a relative or absolute target lives in ("." for a bare name).
std::filesystem::path folder_of(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.parent_path();
    return folder.empty() ? std::filesystem::path(".") : folder;
}

/// A new, empty file beside `path`, opened for writing; `temporary` receives its name.
int create_temporary(const std::filesystem::path& path, std::string_view kind,
                     std::filesystem::path& temporary) {
    std::random_device device;
    std::uniform_int_distribution<unsigned long long> digits(0, (1ULL << 48) - 1);
    for (int attempt = 0; attempt < max_temporary_attempts; ++attempt) {
        temporary = folder_of(path) / fmt::format(".ep-{:012x}", digits(device));
        const int fd = ::open(temporary.c_str(),
                              O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0) {
            return fd;
        }
        if (errno != EEXIST) {
            fail(path, kind,
                 fmt::format("cannot create a temporary file in {}: {}",
                             folder_of(path).string(), std::strerror(errno)));
        }
    }
    fail(path, kind, "no unused temporary file name was found");
}

/// Writes all of `bytes` to `fd`; the errno of the first failure, or 0.
int write_all(int fd, std::string_view bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            return n < 0 ? errno : EIO;
        }
        done += static_cast<std::size_t>(n);
    }
    return 0;
}

/// Gives the temporary file `fd` the permission bits of the regular file `target` it
/// will replace, if there is one; a new file keeps 0666 less the umask from open().
/// Returns the errno of a failure, or 0.
int keep_mode_of(const std::filesystem::path& target, int fd) {
    struct stat old {};
    if (::lstat(target.c_str(), &old) != 0 || !S_ISREG(old.st_mode)) {
        return 0;
    }
    return ::fchmod(fd, old.st_mode & 0777) == 0 ? 0 : errno;
}

} // namespace

void check_output(const std::filesystem::path& path, std::string_view kind,
                  std::span<const std::filesystem::path> inputs) {
    if (path.empty()) {
        throw Error(fmt::format("the {} output path is empty", kind));
    }
    struct stat target {};
    if (::lstat(path.c_str(), &target) != 0) {
        if (errno == ENOENT) {
            return; // a new file: nothing to protect
        }
        fail(path, kind, std::strerror(errno));
    }
    if (!S_ISREG(target.st_mode)) {
        fail(path, kind,
             S_ISDIR(target.st_mode)   ? "it is a directory"
             : S_ISLNK(target.st_mode) ? "it is a symbolic link, not a regular file"
                                       : "it exists and is not a regular file");
    }
    for (const std::filesystem::path& input : inputs) {
        struct stat source {};
        const bool is_stdin = input == standard_input;
        const bool found = is_stdin
                               ? ::fstat(STDIN_FILENO, &source) == 0
                               : !input.empty() && ::stat(input.c_str(), &source) == 0;
        if (found && source.st_dev == target.st_dev && source.st_ino == target.st_ino) {
            fail(path, kind,
                 is_stdin ? std::string("it is the file read as standard input")
                          : fmt::format("it is the input file {}", input.string()));
        }
    }
}

PendingFile::PendingFile(const std::filesystem::path& path, std::string_view kind,
                         std::string_view bytes,
                         std::span<const std::filesystem::path> inputs)
    : path_(path), kind_(kind) {
    check_output(path, kind, inputs);
    const int fd = create_temporary(path, kind, temporary_);
    int error = write_all(fd, bytes);
    if (error == 0) {
        error = keep_mode_of(path, fd);
    }
    if (error == 0 && ::fsync(fd) != 0) {
        error = errno;
    }
    if (::close(fd) != 0 && error == 0) {
        error = errno;
    }
    if (error != 0) {
        discard(); // the destructor does not run when a constructor throws
        fail(path, kind, std::strerror(error));
    }
}

PendingFile::~PendingFile() {
    discard();
}

void PendingFile::commit() {
    if (temporary_.empty()) {
        return; // renamed or removed already
    }
    if (::rename(temporary_.c_str(), path_.c_str()) != 0) {
        const int error = errno;
        discard();
        fail(path_, kind_, std::strerror(error));
    }
    temporary_.clear();
}

void PendingFile::discard() noexcept {
    if (!temporary_.empty()) {
        ::unlink(temporary_.c_str());
        temporary_.clear();
    }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view kind,
                           std::string_view bytes,
                           std::span<const std::filesystem::path> inputs) {
    PendingFile(path, kind, bytes, inputs).commit();
}

void write_standard_output(std::string_view bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() ||
        std::fflush(stdout) != 0) {
        const int error = errno;
        throw Error(fmt::format("standard output: cannot write ({})",
                                error != 0 ? std::strerror(error) : "write failed"));
    }
}

} // namespace exactpixels
