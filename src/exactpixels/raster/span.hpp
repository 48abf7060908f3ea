// span.hpp: what a scanline rasterizer hands out, one row of covered pixels at a time.
//
// Usage:
//   Viewport viewport{64, 48};                 // pixels [0, 64) x [0, 48)
//   Span s{3, 10, 14};                         // row 3, pixels x = 10, 11, 12, 13
//   for (int x = s.x_begin; x < s.x_end; ++x) frame.at(x, s.y) = colour;
//
// Rows and columns are pixel indices (origin top-left, y down); pixel (x, y) is covered
// when its centre (x + 0.5, y + 0.5) is inside the triangle under the top-left rule.
// A rasterizer never emits a pixel outside its Viewport, and never an empty span.
#pragma once

namespace exactpixels {

/// The covered pixels of one row: x_begin .. x_end - 1 on row y (half open).
struct Span {
    int y;       ///< the row (0 is the top row)
    int x_begin; ///< the first covered column
    int x_end;   ///< one past the last covered column (x_end > x_begin when emitted)
    /// Spans are equal when row and both ends are.
    friend constexpr bool operator==(Span, Span) = default;
};

/// The pixels a rasterizer may touch: [0, width) x [0, height). Sizes are >= 0.
struct Viewport {
    int width;  ///< columns 0 .. width - 1
    int height; ///< rows 0 .. height - 1
};

} // namespace exactpixels
