// commands.hpp: the subcommands of build/bin/exactpixels. Each chapter that adds a
// command writes one src/cli/<name>_command.cpp defining its add_*_command function and
// adds one line to main.cpp.
#pragma once

#include <CLI/CLI.hpp>

namespace exactpixels::cli {

/// The exit code for malformed input (a message naming the line and value goes to
/// stderr).
inline constexpr int exit_bad_input = 2;

/// Registers `exactpixels pattern`: writes the chapter 0 "F" test pattern as a PNG.
void add_pattern_command(CLI::App& app, int& exit_code);

/// Registers `exactpixels coverage`: reads a frame size and triangles from standard
/// input and prints how many triangles cover each pixel centre (chapter 2).
void add_coverage_command(CLI::App& app, int& exit_code);

/// Registers `exactpixels render`: renders a chapter 7 scene file to a PNG.
void add_render_command(CLI::App& app, int& exit_code);

} // namespace exactpixels::cli
