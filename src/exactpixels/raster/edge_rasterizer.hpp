// edge_rasterizer.hpp: drawing a triangle by testing pixel centres against its three
// edge functions, over its bounding box pixel by pixel or in blocks of 8 x 8 pixels.
//
// Usage:
//   std::array<FixedPoint2, 3> v = {snap_in_range({0.5, 0.5}), ...};   // 1/256 px
//   edge_rasterize_pixels(v, Viewport{64, 48}, [&](int x, int y) { ... });
//   edge_rasterize_blocks(v, Viewport{64, 48}, [&](int x, int y) { ... }); // same pixels
//   std::array<Point2f, 3> f = {...};                                       // float, px
//   edge_rasterize_blocks(f, Viewport{64, 48}, emit);
//
// Coverage: pixel (x, y) is drawn when its centre (x + 1/2, y + 1/2) is inside the
// triangle under the top-left rule (edge_function.hpp). Both windings are drawn (there
// is no back-face culling); a triangle of zero area draws nothing. Nothing outside
// [0, width) x [0, height) is ever emitted. Pixels arrive in no promised order, each at
// most once per triangle.
//
// Fixed point (FixedPoint2, snapped): exact. Both traversals, and chapter 1's
// fixed-point scanline_spans, draw exactly the same pixels. Coordinates beyond
// +-max_fixed_coordinate throw Error. Float (Point2f): every value is rounded, so
// centres on or very near an edge can go either way (chapter 2 counts how often);
// non-finite coordinates throw Error.
#pragma once

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/edge_function.hpp"
#include "exactpixels/raster/span.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace exactpixels {

/// The pixels [x_begin, x_end) x [y_begin, y_end); empty when either range is.
struct PixelRect {
    int x_begin = 0; ///< first column
    int y_begin = 0; ///< first row
    int x_end = 0;   ///< one past the last column
    int y_end = 0;   ///< one past the last row
    /// True when the rectangle holds no pixel.
    bool empty() const { return x_begin >= x_end || y_begin >= y_end; }
};

//> fixed-bounds
/// The pixels whose centres lie in the bounding box of the snapped triangle v, clipped
/// to the viewport. A centre 256 i + 128 is in [lo, hi] for i from
/// ceil((lo - 128) / 256) to floor((hi - 128) / 256); >> 8 is floor division by 256.
inline PixelRect pixel_bounds(const std::array<FixedPoint2, 3>& v, Viewport viewport) {
    constexpr std::int64_t half = subpixel_scale / 2;
    const auto first = [&](std::int64_t lo, int size) {
        return static_cast<int>(
            std::clamp<std::int64_t>((lo - half + 255) >> 8, 0, size));
    };
    const auto last = [&](std::int64_t hi, int size) { // one past
        return static_cast<int>(
            std::clamp<std::int64_t>(((hi - half) >> 8) + 1, 0, size));
    };
    return {first(std::min({v[0].x, v[1].x, v[2].x}), viewport.width),
            first(std::min({v[0].y, v[1].y, v[2].y}), viewport.height),
            last(std::max({v[0].x, v[1].x, v[2].x}), viewport.width),
            last(std::max({v[0].y, v[1].y, v[2].y}), viewport.height)};
}
//< fixed-bounds

/// The pixels of the viewport that may have their centre in the float triangle v: its
/// bounding box, rounded outwards (a column or row too many is harmless: the edge tests
/// reject it). Coordinates must be finite.
inline PixelRect pixel_bounds(const std::array<Point2f, 3>& v, Viewport viewport) {
    const auto floor_index = [](float c, int size) { // floor(c - 1/2) within [-1, size]
        const float clamped = std::clamp(c - 0.5f, -1.0f, static_cast<float>(size));
        return static_cast<int>(clamped + 1.0f) - 1; // truncation is floor when >= 0
    };
    const auto clip = [](int i, int size) { return std::clamp(i, 0, size); };
    const float x_lo = std::min({v[0].x, v[1].x, v[2].x});
    const float y_lo = std::min({v[0].y, v[1].y, v[2].y});
    const float x_hi = std::max({v[0].x, v[1].x, v[2].x});
    const float y_hi = std::max({v[0].y, v[1].y, v[2].y});
    return {clip(floor_index(x_lo, viewport.width), viewport.width),
            clip(floor_index(y_lo, viewport.height), viewport.height),
            clip(floor_index(x_hi, viewport.width) + 1, viewport.width),
            clip(floor_index(y_hi, viewport.height) + 1, viewport.height)};
}

/// Throws Error naming the vertex and the value unless every coordinate of v is finite
/// and within +-max_fixed_coordinate (1/256 px).
void check_fixed_triangle(const std::array<FixedPoint2, 3>& v);

/// The largest vertex coordinate the float rasterizers accept, px: the fixed-point range
/// (2^20). Beyond it the vertices themselves are rounded to coarser than 1/16 px, and far
/// enough out (about 1.8e19 px) the edge products overflow to infinity and NaN, which
/// would silently draw nothing; such a triangle is an Error instead.
inline constexpr float max_float_coordinate = 1048576.0f;

/// Throws Error naming the vertex and the value unless every coordinate of v is finite
/// and within +-max_float_coordinate px.
void check_float_triangle(const std::array<Point2f, 3>& v);

/// The same for a triangle in double, checked before it is converted to float: a value
/// beyond float's range is named as it is (1e+39), not as the infinity it would become.
void check_float_triangle(const std::array<Point2, 3>& v);

//> traverse-pixels
/// Emits every pixel of `r` whose centre passes all three edge tests. Each edge value
/// is evaluated once at the top-left pixel, then stepped: + step_x per pixel right,
/// + step_y per row down (@eq:edge-steps).
template <class Edge, class EmitFn>
void traverse_pixels(const EdgeSetup<Edge>& s, PixelRect r, EmitFn& emit) {
    const Edge &e0 = s.edge[0], &e1 = s.edge[1], &e2 = s.edge[2];
    auto row0 = e0.at(r.x_begin, r.y_begin); // the values at the row's first pixel
    auto row1 = e1.at(r.x_begin, r.y_begin);
    auto row2 = e2.at(r.x_begin, r.y_begin);
    for (int y = r.y_begin; y < r.y_end; ++y) {
        auto w0 = row0, w1 = row1, w2 = row2;
        for (int x = r.x_begin; x < r.x_end; ++x) {
            if (covers(e0, w0) && covers(e1, w1) && covers(e2, w2)) {
                emit(x, y);
            }
            w0 += e0.step_x();
            w1 += e1.step_x();
            w2 += e2.step_x();
        }
        row0 += e0.step_y();
        row1 += e1.step_y();
        row2 += e2.step_y();
    }
}
//< traverse-pixels

/// What the corner test says about a block of pixels.
enum class BlockClass {
    outside, ///< every centre fails one edge: skip the block
    inside,  ///< every centre passes every edge: fill with no per-pixel test
    partial  ///< neither: test pixel by pixel
};

//> classify-block
/// Classifies the block `b` by its corner pixel centres. An edge value is linear, so
/// over the block it is largest at one corner and smallest at another, picked by the
/// signs of step_x and step_y: if it fails even at the largest corner, every centre
/// fails; if it passes even at the smallest, every centre passes (@eq:edge-block).
template <class Edge> BlockClass classify_block(const EdgeSetup<Edge>& s, PixelRect b) {
    bool inside = true;
    for (const Edge& e : s.edge) {
        const auto top_left = e.at(b.x_begin, b.y_begin);
        const auto across = (b.x_end - 1 - b.x_begin) * e.step_x(); // to the right column
        const auto down = (b.y_end - 1 - b.y_begin) * e.step_y();   // to the bottom row
        const auto zero = decltype(top_left){0};
        const auto largest = top_left + std::max(across, zero) + std::max(down, zero);
        const auto smallest = top_left + std::min(across, zero) + std::min(down, zero);
        if (!covers(e, largest)) {
            return BlockClass::outside; // every centre of the block fails this edge
        }
        inside = inside && covers(e, smallest);
    }
    return inside ? BlockClass::inside : BlockClass::partial;
}
//< classify-block

//> classify-block-area
/// Classifies the block `b` by every point of its pixels' squares, not only by
/// their centres (exercise ch02-block-area): outside when one edge fails at every
/// point of the rectangle [x_begin, x_end] x [y_begin, y_end] (in pixels), inside
/// when every edge passes at every point of it, partial otherwise; a point is tested
/// as a centre is (covers). A conservative rasterizer, which draws every pixel the
/// triangle touches, skips the blocks this calls outside.
template <class Edge>
BlockClass classify_block_area(const EdgeSetup<Edge>& s, PixelRect b) {
    //> exercise ch02-block-area: where over the block's squares is each edge largest?
    // The rectangle's corners lie half a pixel beyond the corner centres: from the
    // top-left centre, -1/2 or n - 1/2 pixels across and down.
    bool inside = true;
    for (const Edge& e : s.edge) {
        const auto top_left = e.at(b.x_begin, b.y_begin); // at the top-left centre
        const auto half_x = e.step_x() / 2, half_y = e.step_y() / 2; // exact: even
        const auto left = -half_x, top = -half_y;
        const auto right = (b.x_end - b.x_begin) * e.step_x() - half_x;
        const auto bottom = (b.y_end - b.y_begin) * e.step_y() - half_y;
        const auto most = top_left + std::max(left, right) + std::max(top, bottom);
        const auto least = top_left + std::min(left, right) + std::min(top, bottom);
        if (!covers(e, most)) {
            return BlockClass::outside; // no point of the block passes this edge
        }
        inside = inside && covers(e, least);
    }
    return inside ? BlockClass::inside : BlockClass::partial;
    //| (void)s, (void)b;
    //| return BlockClass::partial; // stub: decide nothing
    //< exercise ch02-block-area
}
//< classify-block-area

/// The side of the square blocks that edge_rasterize_blocks works in, in pixels.
inline constexpr int block_size = 8;

/// Emits every pixel of the block `b`, no test needed. A row of a whole block has a
/// constant length, which lets the compiler write its 8 pixels at once.
template <class EmitFn> void fill_block(PixelRect b, EmitFn& emit) {
    if (b.x_end - b.x_begin == block_size) {
        for (int y = b.y_begin; y < b.y_end; ++y) {
            for (int i = 0; i < block_size; ++i) {
                emit(b.x_begin + i, y);
            }
        }
        return;
    }
    for (int y = b.y_begin; y < b.y_end; ++y) {
        for (int x = b.x_begin; x < b.x_end; ++x) {
            emit(x, y);
        }
    }
}

//> traverse-blocks
/// Emits the pixels of `r` inside the triangle, block by block: blocks are the 8 x 8
/// squares aligned to multiples of 8 px, clipped to `r`, each rejected, filled or
/// walked pixel by pixel as classify_block says. A rectangle within one block is
/// walked directly (the corner tests would cost more than they save).
template <class Edge, class EmitFn>
void traverse_blocks(const EdgeSetup<Edge>& s, PixelRect r, EmitFn& emit) {
    if (r.x_end - r.x_begin <= block_size && r.y_end - r.y_begin <= block_size) {
        traverse_pixels(s, r, emit);
        return;
    }
    const int first_x = r.x_begin - r.x_begin % block_size; // r is never negative
    for (int by = r.y_begin - r.y_begin % block_size; by < r.y_end; by += block_size) {
        for (int bx = first_x; bx < r.x_end; bx += block_size) {
            const PixelRect b{std::max(bx, r.x_begin), std::max(by, r.y_begin),
                              std::min(bx + block_size, r.x_end),
                              std::min(by + block_size, r.y_end)};
            switch (classify_block(s, b)) {
            case BlockClass::outside:
                break;
            case BlockClass::inside:
                fill_block(b, emit);
                break;
            case BlockClass::partial:
                traverse_pixels(s, b, emit);
                break;
            }
        }
    }
}
//< traverse-blocks

//> traverse-blocks-stepped
/// The stepped variant of traverse_blocks (same pixels in fixed point; tested): for a
/// whole 8 x 8 block the offsets from its top-left centre to its largest and smallest
/// corner are the same for every block, so they are computed once per edge, and the
/// top-left values are stepped from block to block (+8 step_x) instead of evaluated.
/// Blocks clipped by `r` go through classify_block.
template <class Edge, class EmitFn>
void traverse_blocks_stepped(const EdgeSetup<Edge>& s, PixelRect r, EmitFn& emit) {
    if (r.x_end - r.x_begin <= block_size && r.y_end - r.y_begin <= block_size) {
        traverse_pixels(s, r, emit);
        return;
    }
    using Value = decltype(s.edge[0].at(0, 0));
    constexpr int last = block_size - 1;
    std::array<Value, 3> largest, smallest, block_step;
    for (int i = 0; i < 3; ++i) {
        const Value across = last * s.edge[i].step_x(), down = last * s.edge[i].step_y();
        largest[i] = std::max(across, Value{0}) + std::max(down, Value{0});
        smallest[i] = std::min(across, Value{0}) + std::min(down, Value{0});
        block_step[i] = block_size * s.edge[i].step_x();
    }
    const int first_x = r.x_begin - r.x_begin % block_size;
    for (int by = r.y_begin - r.y_begin % block_size; by < r.y_end; by += block_size) {
        std::array<Value, 3> w{s.edge[0].at(first_x, by), s.edge[1].at(first_x, by),
                               s.edge[2].at(first_x, by)}; // at each block's top left
        const bool whole_rows = by >= r.y_begin && by + block_size <= r.y_end;
        for (int bx = first_x; bx < r.x_end; bx += block_size) {
            const PixelRect b{std::max(bx, r.x_begin), std::max(by, r.y_begin),
                              std::min(bx + block_size, r.x_end),
                              std::min(by + block_size, r.y_end)};
            BlockClass c = BlockClass::partial;
            if (whole_rows && bx >= r.x_begin && bx + block_size <= r.x_end) {
                bool inside = true, outside = false;
                for (int i = 0; i < 3; ++i) {
                    outside = outside || !covers(s.edge[i], w[i] + largest[i]);
                    inside = inside && covers(s.edge[i], w[i] + smallest[i]);
                }
                c = outside  ? BlockClass::outside
                    : inside ? BlockClass::inside
                             : BlockClass::partial;
            } else {
                c = classify_block(s, b);
            }
            if (c == BlockClass::inside) {
                fill_block(b, emit);
            } else if (c == BlockClass::partial) {
                traverse_pixels(s, b, emit);
            }
            for (int i = 0; i < 3; ++i) {
                w[i] += block_step[i];
            }
        }
    }
}
//< traverse-blocks-stepped

//> edge-rasterize
/// Emits emit(x, y) for every pixel of the viewport whose centre the snapped triangle v
/// covers (top-left rule), walking its bounding box pixel by pixel. Throws Error for a
/// coordinate beyond +-max_fixed_coordinate.
template <class EmitFn>
void edge_rasterize_pixels(const std::array<FixedPoint2, 3>& v, Viewport viewport,
                           EmitFn&& emit) {
    check_fixed_triangle(v);
    const EdgeSetup<FixedEdge> s = setup_edges(v);
    if (!s.empty) {
        traverse_pixels(s, pixel_bounds(v, viewport), emit);
    }
}
//< edge-rasterize

/// Emits the same pixels as edge_rasterize_pixels (fixed point), walking 8 x 8 blocks.
template <class EmitFn>
void edge_rasterize_blocks(const std::array<FixedPoint2, 3>& v, Viewport viewport,
                           EmitFn&& emit) {
    check_fixed_triangle(v);
    const EdgeSetup<FixedEdge> s = setup_edges(v);
    if (!s.empty) {
        traverse_blocks_stepped(s, pixel_bounds(v, viewport), emit);
    }
}

/// The float version of edge_rasterize_pixels: vertices in px, single precision, every
/// edge value rounded. Throws Error for a coordinate that is not finite.
template <class EmitFn>
void edge_rasterize_pixels(const std::array<Point2f, 3>& v, Viewport viewport,
                           EmitFn&& emit) {
    check_float_triangle(v);
    const EdgeSetup<FloatEdge> s = setup_edges(v);
    if (!s.empty) {
        traverse_pixels(s, pixel_bounds(v, viewport), emit);
    }
}

/// The float version of edge_rasterize_blocks (8 x 8 blocks, single precision).
template <class EmitFn>
void edge_rasterize_blocks(const std::array<Point2f, 3>& v, Viewport viewport,
                           EmitFn&& emit) {
    check_float_triangle(v);
    const EdgeSetup<FloatEdge> s = setup_edges(v);
    if (!s.empty) {
        traverse_blocks_stepped(s, pixel_bounds(v, viewport), emit);
    }
}

/// The rasterizers of chapters 1 and 2, by name (the `coverage` command's choice).
enum class RasterizerKind {
    scanline, ///< chapter 1: edge walking, one span per row
    edge,     ///< chapter 2: edge functions over the bounding box, pixel by pixel
    edge8x8   ///< chapter 2: edge functions in 8 x 8 blocks
};

/// The arithmetic a rasterizer works in.
enum class CoveragePrecision {
    fixed,   ///< vertices snapped to 1/256 px, exact integer tests
    floating ///< floating point: float for the edge rasterizers, double for scanline
};

/// Adds 1 to counts[y * viewport.width + x] for every pixel the triangle v (pixels)
/// covers, drawn by `kind` in `precision`. counts must hold width * height values.
/// Throws Error naming the value for a coordinate that is not finite or (fixed point)
/// outside +-max_fixed_coordinate_px.
void add_coverage(std::vector<int>& counts, Viewport viewport,
                  const std::array<Point2, 3>& v, RasterizerKind kind,
                  CoveragePrecision precision);

} // namespace exactpixels
