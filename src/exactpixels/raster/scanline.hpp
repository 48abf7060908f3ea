// scanline.hpp: the edge-walking scanline rasterizer of chapter 1.
//
// Usage:
//   std::array<Point2, 3> v{{{0.5, 0.5}, {5.5, 0.5}, {5.5, 5.5}}};   // pixels, any order
//   scanline_spans(v, Viewport{64, 48}, [&](Span s) { ... });        // row by row
//   std::array<Attributes<3>, 3> rgb{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
//   scanline_interpolate(v, rgb, Viewport{64, 48},
//                        [&](int x, int y, const Attributes<3>& c) { ... });
//
// Coverage: pixel (x, y) is drawn when its centre (x + 0.5, y + 0.5) lies inside the
// triangle; a centre exactly on an edge is drawn only for a top edge (horizontal, the
// third vertex below it) or a left edge (the triangle's interior to its right). So a
// mesh of triangles sharing edges covers every pixel centre inside it exactly once.
// Either winding is drawn; a triangle of zero area draws nothing.
//
// Two coverage forms:
//   - Point2 vertices (double): edges are walked in floating point, so a centre lying
//     exactly on an edge can be decided either way by rounding (not when the edge's
//     dx/dy and the vertices are short binary fractions). Shared edges are walked
//     identically by both triangles, so meshes stay watertight all the same.
//   - FixedPoint2 vertices (1/256 px, already snapped): the span ends are found with
//     exact integer arithmetic, so the result is the exact top-left coverage of the
//     snapped triangle, pixel for pixel the same as chapter 2's edge functions.
//     Coordinates must lie in [-max_fixed_coordinate, max_fixed_coordinate].
// Spans arrive top to bottom, one per non-empty row, clipped to the Viewport.
//
// Attributes: scanline_interpolate steps N values (colour channels, u, v, ...) across the
// triangle. The value handed out for pixel (x, y) is the triangle's plane evaluated at
// that pixel's centre (@eq:plane; prestepped from the vertices, @eq:prestep), up to the
// rounding of the additions that step it.
#pragma once

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/integer_division.hpp"
#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/span.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

namespace exactpixels {

/// The largest |x| or |y| in pixels that the floating-point scanline forms accept.
inline constexpr double scanline_coordinate_limit = 1 << 24;

/// N attribute values carried by a vertex, or stepped to a pixel.
template <std::size_t N> using Attributes = std::array<double, N>;

/// The first pixel index i whose centre i + 0.5 is at or after the coordinate v
/// (ceil(v - 1/2), @eq:first-centre), clamped to [lo, hi].
inline int first_centre_at_or_after(double v, int lo, int hi) {
    const double i = std::ceil(v - 0.5);
    return i < lo ? lo : i > hi ? hi : static_cast<int>(i);
}

/// Throws Error naming the function, the vertex and the value unless every coordinate
/// of v is finite and within +-scanline_coordinate_limit pixels.
inline void check_scanline_input(const std::array<Point2, 3>& v, const char* function) {
    for (int i = 0; i < 3; ++i) {
        for (const double value : {v[i].x, v[i].y}) {
            if (!(std::abs(value) <= scanline_coordinate_limit)) {
                throw Error(std::string(function) + ": vertex " + std::to_string(i) +
                            " has coordinate " + std::to_string(value) +
                            " px, outside [-2^24, 2^24]");
            }
        }
    }
}

//> edge-walker
/// One edge being walked down the rows whose centres lie in [top.y, bottom.y).
struct EdgeWalker {
    double x;    ///< where the edge crosses the current row's centre line
    double dxdy; ///< x per row (@eq:edge-dxdy)
    int y_begin; ///< the first row walked (clipped to the viewport)
    int y_end;   ///< one past the last row walked (clipped to the viewport)

    /// Starts walking from `top` to `bottom` (top.y <= bottom.y) at the first row of
    /// the viewport whose centre is at or below top.y: the edge is prestepped there.
    EdgeWalker(Point2 top, Point2 bottom, Viewport viewport)
        : x(top.x), dxdy(0.0),
          y_begin(first_centre_at_or_after(top.y, 0, viewport.height)),
          y_end(first_centre_at_or_after(bottom.y, 0, viewport.height)) {
        if (y_begin < y_end) { // y_begin < y_end implies bottom.y > top.y
            dxdy = (bottom.x - top.x) / (bottom.y - top.y);
            x = top.x + ((y_begin + 0.5) - top.y) * dxdy; // prestep to the row centre
        }
    }
    /// Moves to the next row.
    void step() { x += dxdy; }
};
//< edge-walker

/// The triangle's vertices sorted by y (ties keep their order) and which side the
/// middle vertex is on. `area2` is twice the signed area 2A in sorted order (positive
/// when top, middle, bottom run clockwise on screen): negative when the middle vertex
/// lies left of the long edge, zero for a degenerate triangle.
template <class Vertex> struct SortedTriangle {
    std::array<int, 3> order; ///< indices of top, middle and bottom in the input
    Vertex top;               ///< smallest y
    Vertex middle;            ///< middle y
    Vertex bottom;            ///< largest y
    bool middle_on_left;      ///< the short edges are the left side
    bool degenerate;          ///< zero area: nothing to draw
};

/// Sorts v by y and classifies it (@eq:split-denominator gives the sign test).
/// (Always inlined: called, it cost the big torus's frame 2.8M instructions.)
template <class Vertex>
[[gnu::always_inline]] inline SortedTriangle<Vertex>
sort_triangle(const std::array<Vertex, 3>& v) {
    const auto order = sorted_by_y(std::array{v[0].y, v[1].y, v[2].y});
    const Vertex a = v[order[0]], b = v[order[1]], c = v[order[2]];
    // 2A = (x2 - x1)(y3 - y1) - (x3 - x1)(y2 - y1) = -(x4 - x2)(y3 - y1): negative
    // exactly when the middle vertex is left of the long edge (x2 < x4).
    const auto area2 = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    return {order, a, b, c, area2 < 0, area2 == 0};
}

//> scanline-spans
/// Emits the covered pixels of the triangle v (pixels, any order, either winding), one
/// Span per non-empty row, top to bottom, never outside the viewport. Throws Error for
/// a coordinate that is not finite or beyond +-scanline_coordinate_limit.
template <class SpanFn>
void scanline_spans(const std::array<Point2, 3>& v, Viewport viewport, SpanFn&& emit) {
    check_scanline_input(v, "scanline_spans");
    const SortedTriangle<Point2> t = sort_triangle(v);
    if (t.degenerate) {
        return;
    }
    EdgeWalker long_edge(t.top, t.bottom, viewport);
    const EdgeWalker short_edges[2] = {EdgeWalker(t.top, t.middle, viewport),
                                       EdgeWalker(t.middle, t.bottom, viewport)};
    for (EdgeWalker short_edge : short_edges) { // upper half, then lower half
        EdgeWalker& left = t.middle_on_left ? short_edge : long_edge;
        EdgeWalker& right = t.middle_on_left ? long_edge : short_edge;
        for (int y = short_edge.y_begin; y < short_edge.y_end; ++y) {
            // Centres on the left edge are inside, centres on the right edge are not.
            const int x_begin = first_centre_at_or_after(left.x, 0, viewport.width);
            const int x_end = first_centre_at_or_after(right.x, 0, viewport.width);
            if (x_begin < x_end) {
                emit(Span{y, x_begin, x_end});
            }
            left.step();
            right.step();
        }
    }
}
//< scanline-spans

/// Throws Error naming the function and the vertex (and, by check_pixel_range, the
/// value) unless every coordinate of v is within +-max_fixed_coordinate (1/256 px).
inline void check_scanline_input(const std::array<FixedPoint2, 3>& v,
                                 const char* function) {
    for (int i = 0; i < 3; ++i) {
        try {
            check_fixed_range(v[i]);
        } catch (const Error& error) {
            throw Error(std::string(function) + ": vertex " + std::to_string(i) + ": " +
                        error.what());
        }
    }
}

//> fixed-edge-walker
/// One edge of a snapped triangle walked down the rows, in integers only. On every row
/// it holds x_first = ceil((x_edge - 1/2) / 1 px) exactly, the first column whose centre
/// is at or right of the edge, as x_first - remainder / denominator = that quotient
/// before rounding (0 <= remainder < denominator): a Bresenham-style walk
/// (@eq:fixed-first-column).
struct FixedEdgeWalker {
    std::int64_t x_first = 0;     ///< first column with centre at or after the edge
    std::int64_t remainder = 0;   ///< x_first * denominator - numerator, in [0, den)
    std::int64_t denominator = 1; ///< 256 * (bottom.y - top.y)
    std::int64_t step_whole = 0;  ///< whole columns the edge moves per row
    std::int64_t step_part = 0;   ///< the rest of the move, in units of 1/denominator
    int y_begin = 0;              ///< the first row walked (clipped to the viewport)
    int y_end = 0;                ///< one past the last row walked (clipped)

    /// Starts walking from `top` to `bottom` (top.y <= bottom.y), prestepped to the
    /// first row of the viewport whose centre is at or below top.y.
    FixedEdgeWalker(FixedPoint2 top, FixedPoint2 bottom, Viewport viewport) {
        constexpr std::int64_t half = subpixel_scale / 2; // a pixel centre's offset
        const auto first_row = [&](std::int64_t y) {
            const std::int64_t row = ceil_div(y - half, subpixel_scale);
            return static_cast<int>(std::clamp<std::int64_t>(row, 0, viewport.height));
        };
        y_begin = first_row(top.y);
        y_end = first_row(bottom.y);
        if (y_begin >= y_end) {
            return;
        }
        const std::int64_t dx = bottom.x - top.x, dy = bottom.y - top.y; // dy > 0
        denominator = subpixel_scale * dy;
        // The edge meets the centre line of row y_begin at x = top.x + dx (yc - top.y)
        // / dy; in units of 1/denominator px, minus the centre's half pixel:
        const std::int64_t yc = y_begin * std::int64_t{subpixel_scale} + half;
        const std::int64_t numerator = (top.x - half) * dy + dx * (yc - top.y);
        x_first = ceil_div(numerator, denominator);
        remainder = x_first * denominator - numerator;
        // One row down the edge moves 256 dx / denominator columns.
        step_whole = floor_div(subpixel_scale * dx, denominator);
        step_part = subpixel_scale * dx - step_whole * denominator;
    }
    /// Moves to the next row, keeping x_first exact.
    void step() {
        x_first += step_whole;
        remainder -= step_part;
        if (remainder < 0) { // the quotient passed another whole column
            x_first += 1;
            remainder += denominator;
        }
    }
};
//< fixed-edge-walker

/// scanline_spans for a snapped triangle v whose coordinates are known to be within
/// +-max_fixed_coordinate (snapped by snap_in_range, say): the same spans, without
/// checking v again.
template <class SpanFn>
void scanline_spans_in_range(const std::array<FixedPoint2, 3>& v, Viewport viewport,
                             SpanFn&& emit) {
    const SortedTriangle<FixedPoint2> t = sort_triangle(v);
    if (t.degenerate) {
        return;
    }
    const auto clamp_x = [&](std::int64_t x) {
        return static_cast<int>(std::clamp<std::int64_t>(x, 0, viewport.width));
    };
    FixedEdgeWalker long_edge(t.top, t.bottom, viewport);
    const FixedEdgeWalker short_edges[2] = {
        FixedEdgeWalker(t.top, t.middle, viewport),
        FixedEdgeWalker(t.middle, t.bottom, viewport)};
    for (FixedEdgeWalker short_edge : short_edges) {
        FixedEdgeWalker& left = t.middle_on_left ? short_edge : long_edge;
        FixedEdgeWalker& right = t.middle_on_left ? long_edge : short_edge;
        for (int y = short_edge.y_begin; y < short_edge.y_end; ++y) {
            const int x_begin = clamp_x(left.x_first);
            const int x_end = clamp_x(right.x_first);
            if (x_begin < x_end) {
                emit(Span{y, x_begin, x_end});
            }
            left.step();
            right.step();
        }
    }
}

/// Emits the exact top-left coverage of the snapped triangle v (1/256 px, any order,
/// either winding), one Span per non-empty row, top to bottom, never outside the
/// viewport. Throws Error for a coordinate beyond +-max_fixed_coordinate.
template <class SpanFn>
void scanline_spans(const std::array<FixedPoint2, 3>& v, Viewport viewport,
                    SpanFn&& emit) {
    check_scanline_input(v, "scanline_spans");
    scanline_spans_in_range(v, viewport, std::forward<SpanFn>(emit));
}

//> prestep
/// A linear value known at coordinate `from`, moved to coordinate `to` along a line on
/// which it changes by `slope` per pixel (@eq:prestep): how every walk reaches its first
/// sample point.
inline double prestep(double value, double slope, double from, double to) {
    return value + (to - from) * slope;
}
//< prestep

/// A value at the centre of one row: where a walk up an edge starts.
struct RowValue {
    int row;      ///< the row, whose centre is at y = row + 1/2
    double value; ///< the value at the edge's crossing of that row's centre line
};

//> prestep-up
/// For a renderer that walks each edge up the screen, from its lower end, with a
/// bottom-left fill rule (a centre exactly level with the lower end is drawn;
/// exercise ch01-prestep-up): the first row of the walk, the lowest whose centre is
/// at or above `y_from` (y down), and the value there, from `value` at `y_from` and
/// its change `slope` per pixel down the edge.
inline RowValue prestep_up(double value, double slope, double y_from) {
    //> exercise ch01-prestep-up: which row comes first going up, and how far away is it?
    // The centre row + 1/2 <= y_from, the largest such row; the step there is
    // upwards, so the distance (row + 1/2 - y_from) is in (-1, 0].
    const int row = static_cast<int>(std::floor(y_from - 0.5));
    return {row, value + ((row + 0.5) - y_from) * slope};
    //| (void)slope, (void)y_from;
    //| return {0, value}; // stub: row 0, the value where it is known
    //< exercise ch01-prestep-up
}
//< prestep-up

//> scanline-interpolate
/// Draws the triangle v like scanline_spans and calls shade(x, y, values) for every
/// covered pixel, left to right, top to bottom, with the N attributes (given per vertex
/// in `c`) stepped to that pixel's centre: the plane of each attribute evaluated there.
template <std::size_t N, class PixelFn>
void scanline_interpolate(const std::array<Point2, 3>& v,
                          const std::array<Attributes<N>, 3>& c, Viewport viewport,
                          PixelFn&& shade) {
    check_scanline_input(v, "scanline_interpolate");
    const SortedTriangle<Point2> t = sort_triangle(v);
    if (t.degenerate) {
        return;
    }
    // Setup: one gradient per attribute (@eq:closed-form), the same over the whole
    // triangle.
    std::array<Gradient<double>, N> g{};
    for (std::size_t k = 0; k < N; ++k) {
        g[k] = closed_form_gradient<double>(v, {c[0][k], c[1][k], c[2][k]});
    }
    // A left edge carries the attributes' values where it crosses the current row.
    struct LeftEdge {
        EdgeWalker edge;
        Attributes<N> value; // at (edge.x, row centre)
        Attributes<N> slope; // per row down the edge (@eq:edge-slope-gradient)
        void step() {
            edge.step();
            for (std::size_t k = 0; k < N; ++k) {
                value[k] += slope[k];
            }
        }
    };
    const auto left_edge = [&](int top, int bottom) { // vertex indices
        LeftEdge e{EdgeWalker(v[top], v[bottom], viewport), c[top], {}};
        for (std::size_t k = 0; k < N; ++k) {
            e.slope[k] = edge_slope_from_gradient(g[k], v[top], v[bottom]);
            e.value[k] = prestep(c[top][k], e.slope[k], v[top].y, e.edge.y_begin + 0.5);
        }
        return e;
    };
    const auto [i1, i2, i3] = t.order;
    const std::pair<int, int> short_edges[2] = {{i1, i2}, {i2, i3}};
    LeftEdge long_left = left_edge(i1, i3);
    EdgeWalker long_right(v[i1], v[i3], viewport);
    for (const auto& [upper, lower] : short_edges) {
        LeftEdge short_left = left_edge(upper, lower);
        EdgeWalker short_right(v[upper], v[lower], viewport);
        LeftEdge& left = t.middle_on_left ? short_left : long_left;
        EdgeWalker& right = t.middle_on_left ? long_right : short_right;
        for (int y = short_right.y_begin; y < short_right.y_end; ++y) {
            const int x_begin = first_centre_at_or_after(left.edge.x, 0, viewport.width);
            const int x_end = first_centre_at_or_after(right.x, 0, viewport.width);
            Attributes<N> value; // prestepped from the edge to the first centre
            for (std::size_t k = 0; k < N; ++k) {
                value[k] = prestep(left.value[k], g[k].dx, left.edge.x, x_begin + 0.5);
            }
            for (int x = x_begin; x < x_end; ++x) {
                shade(x, y, std::as_const(value));
                for (std::size_t k = 0; k < N; ++k) {
                    value[k] += g[k].dx;
                }
            }
            left.step();
            right.step();
        }
    }
}
//< scanline-interpolate

} // namespace exactpixels
