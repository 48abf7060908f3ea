// test_pattern.hpp: the asymmetric "F" used throughout the book to catch flips,
// transposes, off-by-ones and channel swaps.
//
// The F is red (255, 0, 0) on blue (0, 0, 255). On a 5 x 7 cell grid, cells are filled
// where the glyph below has '#'; each cell is `cell` pixels square. Row 0 is the top.
//
//   #####
//   #....
//   #....
//   ####.
//   #....
//   #....
//   #....
#pragma once

#include "exactpixels/base/framebuffer.hpp"

namespace exactpixels {

/// Red: the colour of the F's strokes.
inline constexpr Rgba8 pattern_red = rgba(255, 0, 0);
/// Blue: the colour behind the F.
inline constexpr Rgba8 pattern_blue = rgba(0, 0, 255);

/// Width of the F glyph in cells.
inline constexpr int f_glyph_width = 5;
/// Height of the F glyph in cells.
inline constexpr int f_glyph_height = 7;

/// True when cell (column, row) of the 5 x 7 F glyph is part of the letter.
bool f_glyph_cell(int column, int row);

/// A (5 * cell) x (7 * cell) image of the F, red on blue. cell must be >= 1.
Framebuffer draw_f_pattern(int cell);

} // namespace exactpixels
