// coverage_reader.hpp: the input of `exactpixels coverage` (chapter 2), read and drawn.
//
// Usage:
//   Viewport viewport{0, 0};
//   std::vector<int> counts = count_coverage(std::cin, RasterizerKind::edge8x8,
//                                            CoveragePrecision::fixed, viewport);
//   std::string text = format_counts(counts, viewport);
//
// The input: a first line "W H" (the frame's size in pixels, whole numbers from 1 to
// max_frame_side, at most max_frame_pixels in all), then one triangle per line,
// "x0 y0 x1 y1 x2 y2" (pixels, origin top-left, y down). A number is decimal: one
// optional sign, digits with an optional point, an optional exponent (3, -0.5, +.25,
// 1e-3); "+-0.5", "0x10" and "inf" are not numbers. Words are separated by spaces and
// tabs; blank lines are skipped. Counts are row by row, top to bottom. Malformed input is
// an Error whose message starts "line N:" and quotes the value as written. The whole input
// is read before anything is drawn: at most max_coverage_triangles triangles, whose fill
// work together (fill_work.hpp: the pixels of their bounding boxes in the frame) is at
// most max_fill_work, so an input that asks for more is refused at the line that passes
// the limit, before the count grid is allocated.
#pragma once

#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/span.hpp"

#include <array>
#include <cstddef>
#include <functional>
#include <istream>
#include <string>
#include <vector>

namespace exactpixels {

/// The largest frame side the coverage input may ask for, pixels.
inline constexpr int max_frame_side = 16384;
/// The most pixels of a coverage frame (2^24, 64 MiB of counts): checked before the
/// count grid and the output text (2 bytes or more per pixel) are allocated.
inline constexpr long long max_frame_pixels = 1LL << 24;

/// The most triangles of a coverage input (2^20, as many as a scene's): all of them are
/// held, 56 bytes each, until the input is read to its end.
inline constexpr long long max_coverage_triangles = 1 << 20;

/// The longest line of the coverage input, bytes (a triangle needs about a hundred).
inline constexpr std::size_t max_line_bytes = 1024;

/// Reads the whole of `in`, draws every triangle with `kind` in `precision`, sets
/// `viewport` to the frame's size and returns the counts row by row. Throws Error
/// ("line N: ...") on malformed input, an input over the limits above or
/// max_fill_work (before drawing anything), or a triangle the rasterizer refuses.
/// `max_pixels` (at most max_frame_pixels) lowers the frame limit, as the fuzz target
/// does to stay fast.
std::vector<int> count_coverage(std::istream& in, RasterizerKind kind,
                                CoveragePrecision precision, Viewport& viewport,
                                long long max_pixels = max_frame_pixels);

/// Adds 1 to counts[y * width + x] for every pixel the triangle (pixels) covers.
using CoverageDraw = std::function<void(std::vector<int>& counts, Viewport viewport,
                                        const std::array<Point2, 3>& triangle)>;

/// The same with any rasterizer: `draw` adds one triangle's coverage (chapter 10's fast
/// traversals use this).
std::vector<int> count_coverage(std::istream& in, const CoverageDraw& draw,
                                Viewport& viewport,
                                long long max_pixels = max_frame_pixels);

/// The counts as text: one line per row, counts separated by one space.
std::string format_counts(const std::vector<int>& counts, Viewport viewport);

} // namespace exactpixels
