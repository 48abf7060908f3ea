#include "exactpixels/base/atomic_file.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <pthread.h>
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

// The temporary files being written, kept for the signal handler. A handler may not
// allocate or take a lock, so each name is copied into a fixed slot while the file is
// created, and the slot's state (lock-free, so a handler may read it) says whether the
// name is whole.

/// The signals that end a process by default and that a user or a closed pipe sends.
constexpr std::array caught_signals{SIGINT, SIGTERM, SIGHUP, SIGPIPE};

/// How many temporary files at once are guarded (more are written, unguarded).
constexpr int max_guarded_temporaries = 8;

enum SlotState : int { slot_free, slot_filling, slot_guarded };

struct GuardSlot {
    std::atomic<int> state{slot_free};
    char path[PATH_MAX] = {};
};
static_assert(std::atomic<int>::is_always_lock_free);

std::array<GuardSlot, max_guarded_temporaries> guard_slots;

/// Stores `temporary` for the handler; the slot's index, or -1 when every slot is taken.
int guard(const std::filesystem::path& temporary) {
    const std::string& name = temporary.native();
    if (name.size() >= PATH_MAX) {
        return -1; // cannot happen: open() refused the name already
    }
    for (int i = 0; i < max_guarded_temporaries; ++i) {
        GuardSlot& slot = guard_slots[static_cast<std::size_t>(i)];
        int expected = slot_free;
        if (slot.state.compare_exchange_strong(expected, slot_filling)) {
            std::memcpy(slot.path, name.c_str(), name.size() + 1);
            slot.state.store(slot_guarded);
            return i;
        }
    }
    return -1;
}

/// Frees the slot `guard` returned (after the file was renamed or removed).
void unguard(int index) {
    if (index >= 0) {
        guard_slots[static_cast<std::size_t>(index)].state.store(slot_free);
    }
}

/// The handler: removes every guarded temporary, then ends the process by `signal`.
void remove_temporaries_and_die(int signal) {
    for (GuardSlot& slot : guard_slots) {
        if (slot.state.load() == slot_guarded) {
            ::unlink(slot.path);
        }
    }
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    ::sigaction(signal, &default_action, nullptr);
    ::raise(signal); // blocked while the handler runs, delivered as it returns
}

/// Holds the caught signals back on this thread while it exists, so that a signal finds
/// a temporary file either not yet created or already guarded.
class SignalsHeld {
  public:
    SignalsHeld() {
        sigset_t held;
        sigemptyset(&held);
        for (const int signal : caught_signals) {
            sigaddset(&held, signal);
        }
        ::pthread_sigmask(SIG_BLOCK, &held, &before_);
    }
    ~SignalsHeld() { ::pthread_sigmask(SIG_SETMASK, &before_, nullptr); }
    SignalsHeld(const SignalsHeld&) = delete;
    SignalsHeld& operator=(const SignalsHeld&) = delete;

  private:
    sigset_t before_{};
};

/// A new, empty file beside `path`, opened for writing; `temporary` receives its name
/// and `guard_index` its slot for the signal handler.
int create_temporary(const std::filesystem::path& path, std::string_view kind,
                     std::filesystem::path& temporary, int& guard_index) {
    std::random_device device;
    std::uniform_int_distribution<unsigned long long> digits(0, (1ULL << 48) - 1);
    for (int attempt = 0; attempt < max_temporary_attempts; ++attempt) {
        temporary = folder_of(path) / fmt::format(".ep-{:012x}", digits(device));
        const SignalsHeld held;
        const int fd = ::open(temporary.c_str(),
                              O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0) {
            guard_index = guard(temporary);
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
    const int fd = create_temporary(path, kind, temporary_, guard_);
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
    unguard(guard_);
    guard_ = -1;
}

void PendingFile::discard() noexcept {
    if (!temporary_.empty()) {
        ::unlink(temporary_.c_str());
        temporary_.clear();
    }
    unguard(guard_);
    guard_ = -1;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view kind,
                           std::string_view bytes,
                           std::span<const std::filesystem::path> inputs) {
    PendingFile(path, kind, bytes, inputs).commit();
}

void remove_temporaries_on_signals() {
    for (const int signal : caught_signals) {
        struct sigaction before {};
        ::sigaction(signal, nullptr, &before);
        if (before.sa_handler == SIG_IGN) {
            continue; // ignored by whoever started us (nohup): stays ignored
        }
        struct sigaction action {};
        action.sa_handler = remove_temporaries_and_die;
        sigemptyset(&action.sa_mask);
        ::sigaction(signal, &action, nullptr);
    }
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
