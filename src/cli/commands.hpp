// commands.hpp: the subcommands of build/bin/exactpixels. Each chapter that adds a
// command writes one src/cli/<name>_command.cpp defining its add_*_command function and
// adds one line to main.cpp.
#pragma once

#include <CLI/CLI.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace exactpixels::cli {

/// The exit code for malformed input (a message naming the line and value goes to
/// stderr).
inline constexpr int exit_bad_input = 2;

/// The most characters of one word a message shows; a longer word (a 50 MB token on
/// the command line or in the input) is cut to this many and an ellipsis. A file's path
/// is one word, and a message must name its file whole: 4096 is Linux's PATH_MAX, the
/// longest path a system call accepts (macOS's is 1024), so no real path is cut.
inline constexpr std::size_t max_word_chars = 4096;

/// `message` as one line: line breaks become spaces, and every word longer than
/// max_word_chars is cut to that many characters followed by "...".
std::string one_line(std::string_view message);

/// Prints "exactpixels[ COMMAND]: MESSAGE" as one_line(message), control characters
/// escaped (printable.hpp), on standard error.
/// Never throws: when even standard error cannot be written there is nobody to tell,
/// and the exit code still says what happened.
void print_error(std::string_view command, std::string_view message);

/// Runs a command's `body` and reports what it throws as bad input (exit_bad_input and
/// one line on standard error): an Error, and std::bad_alloc, an input whose work needs
/// more memory than the process may have (`ulimit -v`). Whatever the body had written is
/// removed as it unwinds (a PendingFile), so nothing is left.
void report_errors(std::string_view command, int& exit_code,
                   const std::function<void()>& body);

/// Registers `exactpixels pattern`: writes the chapter 0 "F" test pattern as a PNG.
void add_pattern_command(CLI::App& app, int& exit_code);

/// Registers `exactpixels coverage`: reads a frame size and triangles from standard
/// input and prints how many triangles cover each pixel centre (chapter 2).
void add_coverage_command(CLI::App& app, int& exit_code);

/// Registers `exactpixels render`: renders a chapter 7 scene file to a PNG.
void add_render_command(CLI::App& app, int& exit_code);

} // namespace exactpixels::cli
