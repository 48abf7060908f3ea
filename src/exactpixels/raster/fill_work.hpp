// fill_work.hpp: how much drawing some triangles ask for, measured before any is drawn.
//
// Usage:
//   long long work = 0;
//   for (const auto& corners : triangles) {      // corners in pixels
//       work += fill_work(corners, viewport);
//   }
//   if (work > max_fill_work) { /* refuse the input: nothing drawn yet */ }
//
// A triangle's fill work is the number of pixels of its bounding box inside the
// viewport (pixel (x, y) covers [x, x+1) x [y, y+1)): whatever its shape, a rasterizer
// of chapters 1, 2 and 10 visits no more than those (the 8 x 8 traversals round the box
// out to whole blocks). The sum over an input's triangles bounds the time drawing it
// takes, so a small input that asks for hours of drawing is refused in advance.
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/span.hpp"

#include <array>

namespace exactpixels {

/// The most fill work one drawing may ask for, pixels: 16 frames of the largest size
/// (2^24 pixels, max_image_pixels and max_frame_pixels), 2^28 pixels, about a second
/// of the plainest drawing.
inline constexpr long long max_fill_work = 16LL << 24;

/// The pixels of the bounding box of `corners` (pixels, finite) inside `viewport`.
long long fill_work(const std::array<Point2, 3>& corners, Viewport viewport);

} // namespace exactpixels
