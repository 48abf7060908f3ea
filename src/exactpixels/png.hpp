// png.hpp: reading and writing frames as PNG files, through stb.
//
// Usage:
//   write_png("f.png", fb);             // throws Error naming the path on failure
//   write_png("f.png", fb, {scene});    // ... also when "f.png" is the file `scene`
//   Framebuffer image = read_png("f.png");
//
// Writing is all or nothing (atomic_file.hpp): the image is encoded in memory, goes to a
// new temporary file beside the target, and is renamed over the target only when every
// byte is on the disk. On failure no file is left and the target is unchanged.
#pragma once

#include "exactpixels/framebuffer.hpp"

#include <filesystem>
#include <span>

namespace exactpixels {

/// Writes `frame` as an 8-bit RGBA PNG. Throws Error (naming the path) on failure, in
/// which case the target is left as it was and no temporary file is left behind. The
/// target may not be one of `inputs`, nor anything but a regular file (see
/// write_file_atomically).
void write_png(const std::filesystem::path& path, const Framebuffer& frame,
               std::span<const std::filesystem::path> inputs = {});

/// Reads a PNG (or any image stb reads) as RGBA8. Throws Error naming the path and
/// stb's reason when the file is missing, unreadable, corrupt or has zero size.
Framebuffer read_png(const std::filesystem::path& path);

} // namespace exactpixels
