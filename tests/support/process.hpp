// process.hpp: running build/bin/exactpixels (or any command) from a test.
#pragma once

#include <string>

namespace exactpixels::testing {

/// What a finished command printed and returned.
struct CommandResult {
    int exit_code = -1; ///< the process's exit status
    std::string out;    ///< everything written to standard output
    std::string err;    ///< everything written to standard error
};

/// Runs `command` through /bin/sh with `input` on its standard input.
CommandResult run_command(const std::string& command, const std::string& input = "");

/// The command that runs the program at `path`, quoted for the shell: the path itself,
/// or, in a cross build (the arm64 preset), the path after the emulator that runs it.
std::string program_command(const std::string& path);

/// The command that runs build/bin/exactpixels, quoted for the shell (program_command).
std::string cli_path();

} // namespace exactpixels::testing
