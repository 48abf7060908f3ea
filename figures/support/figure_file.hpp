// figure_file.hpp: how every figure program writes its tables and data files.
//
// Usage:
//   std::ostringstream table;                      // build the whole text in memory
//   table << "| a | b |\n";
//   write_figure_file(folder / "ch01_table.md", table.str());   // throws Error
//
// The text goes through write_file_atomically (base/atomic_file.hpp): all or nothing, so
// a full disk or a missing folder is an Error naming the file, the program exits non-zero
// and the build stops, and the book never includes a silently short table.
#pragma once

#include <filesystem>
#include <string_view>

namespace exactpixels {

/// Writes `text` to `path` all or nothing (kind "figure data" in the error message).
/// Throws Error ("PATH: cannot write figure data file (reason)") on any failure, leaving
/// the file as it was.
void write_figure_file(const std::filesystem::path& path, std::string_view text);

} // namespace exactpixels
