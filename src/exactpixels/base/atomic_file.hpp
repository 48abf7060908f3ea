// atomic_file.hpp: writing a file all or nothing, and never over something precious.
//
// Usage:
//   write_file_atomically("out.png", "PNG", bytes, {scene_file, texture_file});
//   check_output("out.png", "PNG", inputs);  // the same checks, before any work is done
//
// The bytes go to a new temporary file in the target's folder, created exclusively
// (O_CREAT | O_EXCL | O_NOFOLLOW: it never reuses or follows anything already there)
// under a short unique name (".ep-" and 12 hex digits, so any legal target name still
// works). Every write is checked, the file is flushed to the disk (fsync) and closed, and
// only then renamed over the target. On any failure the temporary file is removed, the
// target is left as it was, and an Error names the path and the reason. A file that is
// replaced keeps its permission bits (a 0600 file stays 0600); a new file gets 0666 less
// the umask, like any file a program creates.
//
// A command that must also print before its output counts as done holds the file as a
// PendingFile: written and on the disk, renamed only by commit(), removed if commit() is
// never reached. After remove_temporaries_on_signals(), a process killed by SIGINT,
// SIGTERM, SIGHUP or SIGPIPE removes its temporary files too before it dies.
//
// Refused before anything is written: an empty path; a target that exists and is not a
// regular file (a directory, a device such as /dev/null, a FIFO, a symbolic link); and a
// target that is the same file as one of `inputs` (same device and inode, so a hard link
// or another spelling of the same path is caught too). A command that reads standard
// input names it among its inputs as `standard_input`, compared through its descriptor,
// so that `cmd -o f < f` is refused too.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace exactpixels {

/// The name an input list gives standard input: check_output compares the file open as
/// descriptor 0 (whatever redirected it) with the target.
inline const std::filesystem::path standard_input = "-";

/// Throws Error ("PATH: cannot write KIND file (reason)") when `path` may not be written:
/// it is empty, exists and is not a regular file, or is the same file as one of
/// `inputs` (inputs that do not exist are ignored). Writes nothing.
void check_output(const std::filesystem::path& path, std::string_view kind,
                  std::span<const std::filesystem::path> inputs = {});

/// A file written whole to a temporary beside its target and not yet in place.
///   PendingFile png(path, "PNG", bytes, inputs); // checked, written, flushed
///   write_standard_output("wrote it\n");         // throws: the temporary is removed
///   png.commit();                                // renamed over the target
class PendingFile {
  public:
    /// check_output(path, kind, inputs), then the bytes to a new temporary file, flushed
    /// to the disk and closed. Throws Error as write_file_atomically does.
    PendingFile(const std::filesystem::path& path, std::string_view kind,
                std::string_view bytes,
                std::span<const std::filesystem::path> inputs = {});
    /// Removes the temporary file unless commit() succeeded.
    ~PendingFile();
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;

    /// Renames the temporary file over the target (once). Throws Error on failure,
    /// having removed the temporary file.
    void commit();

  private:
    /// Removes the temporary file, if it is still there.
    void discard() noexcept;

    std::filesystem::path path_;      ///< the target
    std::string kind_;                ///< "PNG", "coverage": for messages
    std::filesystem::path temporary_; ///< the written file (empty: renamed or removed)
    int guard_ = -1;                  ///< its slot for the signal handler (-1: none)
};

/// Writes `bytes` to `path` all or nothing, after check_output(path, kind, inputs).
/// Throws Error ("PATH: cannot write KIND file (reason)") on any failure, leaving the
/// target as it was and no temporary file behind.
void write_file_atomically(const std::filesystem::path& path, std::string_view kind,
                           std::string_view bytes,
                           std::span<const std::filesystem::path> inputs = {});

/// Makes SIGINT, SIGTERM, SIGHUP and SIGPIPE remove every temporary file this process
/// is writing, then end it by that signal as before (its exit status still says which).
/// A signal the process was started with set to be ignored stays ignored. For a
/// program's main(), once.
void remove_temporaries_on_signals();

/// Writes `bytes` to standard output and flushes it. Throws Error ("standard output:
/// reason") when any of it could not be written (a full disk, /dev/full, or a closed
/// pipe when SIGPIPE is ignored; otherwise SIGPIPE ends the process).
void write_standard_output(std::string_view bytes);

} // namespace exactpixels
