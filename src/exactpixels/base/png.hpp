// png.hpp: reading and writing frames as PNG files, through stb.
//
// Usage:
//   write_png("f.png", fb);             // throws Error naming the path on failure
//   Framebuffer image = read_png("f.png");
//
// Writing is all or nothing: the image goes to a temporary file beside the target,
// which is renamed over the target only when complete. On failure no file is left.
#pragma once

#include "exactpixels/base/framebuffer.hpp"

#include <filesystem>

namespace exactpixels {

/// Writes `frame` as an 8-bit RGBA PNG. Throws Error (naming the path) on failure, in
/// which case neither `path` nor any temporary file is left behind.
void write_png(const std::filesystem::path& path, const Framebuffer& frame);

/// Reads a PNG (or any image stb reads) as RGBA8. Throws Error naming the path and
/// stb's reason when the file is missing, unreadable, corrupt or has zero size.
Framebuffer read_png(const std::filesystem::path& path);

} // namespace exactpixels
