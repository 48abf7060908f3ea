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

#include <algorithm>
#include <array>

namespace exactpixels {

/// The most fill work one drawing may ask for, pixels: 16 frames of the largest size
/// (2^24 pixels, max_image_pixels and max_frame_pixels), 2^28 pixels, about a second
/// of the plainest drawing.
inline constexpr long long max_fill_work = 16LL << 24;

/// The pixels of the bounding box of `corners` (pixels, finite) inside `viewport`.
/// (Inline: the scene renderer sums it over every triangle before drawing, and called,
/// it cost the big torus's frame 3.1M instructions.)
inline long long fill_work(const std::array<Point2, 3>& corners, Viewport viewport) {
    // The whole pixels the box [x0, x1] x [y0, y1] touches, clamped to the viewport
    // first so that a corner far outside (up to the guard band) cannot overflow.
    // On [0, size] floor is the conversion to int (it truncates towards zero) and ceil
    // one more where that dropped a fraction: no call to floor or ceil per triangle.
    const auto pixels = [](double lo, double hi, int size) -> long long {
        const double low = std::clamp(lo, 0.0, double(size));
        const double high = std::clamp(hi, 0.0, double(size));
        const long long first = static_cast<long long>(low);
        const long long whole = static_cast<long long>(high);
        const long long end = whole + (double(whole) < high ? 1 : 0);
        return std::max(0LL, end - first);
    };
    const auto [x0, x1] = std::minmax({corners[0].x, corners[1].x, corners[2].x});
    const auto [y0, y1] = std::minmax({corners[0].y, corners[1].y, corners[2].y});
    return pixels(x0, x1, viewport.width) * pixels(y0, y1, viewport.height);
}

} // namespace exactpixels
