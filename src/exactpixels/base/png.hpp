// png.hpp: reading PNG files through libpng and writing them through stb.
//
// Usage:
//   write_png("f.png", fb);             // throws Error naming the path on failure
//   write_png("f.png", fb, {scene});    // ... also when "f.png" is the file `scene`
//   Framebuffer image = read_png("f.png");
//   Framebuffer small = read_png("t.png", [](int w, int h) { /* throw if too big */ });
//
// Writing is all or nothing (atomic_file.hpp): the image is encoded in memory, goes to a
// new temporary file beside the target, and is renamed over the target only when every
// byte is on the disk. On failure no file is left and the target is unchanged.
//
// Reading is strict: the file must be a regular file of at most max_png_file_bytes that
// starts with the PNG signature; libpng checks every chunk's CRC and the zlib stream's
// Adler-32 checksum, so a corrupt file is an Error, never an image with wrong pixels. The
// size in the header is checked (against max_png_pixels, and by the caller's check)
// before any pixel memory is allocated, and so is the zlib stream: it may inflate to at
// most max_png_extra_inflated_bytes more than the image's rows, else the file is refused
// before libpng inflates it. Pixels come out as 8-bit RGBA, rows top to bottom, as sRGB
// codes: a file without a gAMA or sRGB chunk is sRGB whatever its depth (a 16-bit sample
// v becomes the nearest code, round(v / 257)); libpng converts a file whose gAMA says
// another gamma.
#pragma once

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/framebuffer.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace exactpixels {

/// The bytes of `frame` as an 8-bit RGBA PNG file (stb's encoder: filter and deflate),
/// in memory: write_png's first half. Throws Error for an empty frame.
std::string encode_png(const Framebuffer& frame);

/// write_png's work but the rename: `frame` encoded and written beside `path`, which it
/// replaces only at commit() (for a command that prints before its output is done).
PendingFile prepare_png(const std::filesystem::path& path, const Framebuffer& frame,
                        std::span<const std::filesystem::path> inputs = {});

/// Writes `frame` as an 8-bit RGBA PNG. Throws Error (naming the path) on failure, in
/// which case the target is left as it was and no temporary file is left behind. The
/// target may not be one of `inputs`, nor anything but a regular file (see
/// write_file_atomically).
void write_png(const std::filesystem::path& path, const Framebuffer& frame,
               std::span<const std::filesystem::path> inputs = {});

/// The largest PNG file read_png reads, bytes (the largest image it decodes, stored
/// uncompressed, fits with room to spare).
inline constexpr std::size_t max_png_file_bytes = std::size_t{80} << 20;
/// The most pixels read_png decodes (2^24: 64 MiB of RGBA8).
inline constexpr long long max_png_pixels = 1LL << 24;
/// How many bytes a PNG's zlib stream may inflate to beyond its image's own rows (a
/// filter byte and the packed samples of each): an honest stream has none, and a
/// "decompression bomb" is refused after at most this much work.
inline constexpr long long max_png_extra_inflated_bytes = 1LL << 20;

/// Decodes the PNG `bytes` as RGBA8, as read_png does after reading the file; `name`
/// names it in messages.
Framebuffer decode_png(std::string_view bytes, const std::string& name,
                       const std::function<void(int width, int height)>& check_size = {});

/// Reads a PNG as RGBA8. After the header is read and before the pixels are decoded,
/// calls `check_size(width, height)` when given, which may throw to refuse the size.
/// Throws Error naming the path and the reason when the file is missing, not a regular
/// file, too large, not a PNG (by its signature), corrupt (a bad CRC, a bad zlib
/// checksum, truncated) or has more than max_png_pixels pixels.
Framebuffer read_png(const std::filesystem::path& path,
                     const std::function<void(int width, int height)>& check_size = {});

} // namespace exactpixels
