// input_file.hpp: reading an input file whole, never more than a stated number of bytes.
//
// Usage:
//   std::string text = read_input_file("floor.toml", "scene", max_scene_file_bytes,
//                                      InputKind::any);      // a pipe is fine too
//   std::string png = read_input_file("wall.png", "texture", max_png_file_bytes,
//                                     InputKind::regular_file);
//
// The file is read in pieces and given up on as soon as it holds more than `max_bytes`,
// so /dev/zero or a huge file costs at most `max_bytes` of memory. With
// InputKind::regular_file, anything else (a FIFO, a device, a directory) is refused
// before a single byte is read: the file is opened without blocking, so a FIFO nobody
// writes cannot hang the program.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace exactpixels {

/// What an input may be.
enum class InputKind {
    any,         ///< a regular file, a pipe, a device: whatever can be read
    regular_file ///< only a regular file (no FIFO, no device, no directory)
};

/// The whole content of `path`. Throws Error ("PATH: cannot read the KIND file
/// (reason)") when it cannot be opened or read, is not a regular file although `input`
/// asks for one, or holds more than `max_bytes` bytes (the message states the limit).
std::string read_input_file(const std::filesystem::path& path, std::string_view kind,
                            std::size_t max_bytes, InputKind input);

} // namespace exactpixels
