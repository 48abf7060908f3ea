// tiny_triangle.hpp: the pixels of a triangle at most 32 px wide and high, found with
// 32-bit edge values four pixels at a time, the same pixels as traverse_pixels.
//
// Usage:
//   check_fixed_triangle(v);                         // within +-max_fixed_coordinate
//   const PixelRect r = pixel_bounds(v, viewport);   // edge_rasterizer.hpp
//   if (is_tiny(v)) {
//       traverse_tiny<Lanes4>(v, r, [&](int x, int y) { ... }); // sign_lanes4.hpp
//   }
//
// Coordinates are chapter 2's fixed point (1/256 px); r must be pixel_bounds of v (or a
// part of it). The edge values are those of setup_edges and FixedEdge::at, bit for bit
// (tested), computed relative to the centre of r's top-left pixel, where they fit in
// int32 (@eq:tiny-bound). Pixels come out row by row, left to right; a triangle of zero
// area gives none.
#pragma once

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/edge_function.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstdint>
#include <utility>

namespace exactpixels {

/// The largest width and height of a tiny triangle's vertex box, in 1/256 px (32 px):
/// within it every edge value traverse_tiny computes is below 2^29 in magnitude.
inline constexpr std::int64_t tiny_extent = 32 * subpixel_scale;

/// True when the vertex box of v is at most tiny_extent wide and high.
inline bool is_tiny(const std::array<FixedPoint2, 3>& v) {
    const auto [x_lo, x_hi] = std::minmax({v[0].x, v[1].x, v[2].x});
    const auto [y_lo, y_hi] = std::minmax({v[0].y, v[1].y, v[2].y});
    return x_hi - x_lo <= tiny_extent && y_hi - y_lo <= tiny_extent;
}

//> traverse-tiny
/// Emits every pixel of r whose centre the tiny triangle v covers (top-left rule), the
/// pixels of traverse_pixels(setup_edges(v), r): the vertices are moved so that the
/// centre of r's top-left pixel is the origin, which changes no edge value, and the
/// three edges are evaluated for four columns at once in int32 lanes.
template <class Lanes, class EmitFn>
void traverse_tiny(const std::array<FixedPoint2, 3>& v, PixelRect r, EmitFn&& emit) {
    assert(is_tiny(v));
    if (r.empty()) {
        return;
    }
    const FixedPoint2 origin = fixed_pixel_centre(r.x_begin, r.y_begin);
    std::array<std::int32_t, 3> x, y; // within +-tiny_extent: origin is in v's box
    for (std::size_t i = 0; i < 3; ++i) {
        x[i] = static_cast<std::int32_t>(v[i].x - origin.x);
        y[i] = static_cast<std::int32_t>(v[i].y - origin.y);
    }
    const std::int32_t area2 =
        (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (area2 == 0) {
        return;
    }
    if (area2 < 0) { // the other winding: setup_edges reverses every edge, and so
        std::swap(x[1], x[2]); // does this swap; which edge is which does not matter
        std::swap(y[1], y[2]);
    }
    std::array<Lanes, 3> row, down; // row: the values of the row's first four columns
    std::array<std::int32_t, 3> step_x;
    for (std::size_t i = 0; i < 3; ++i) {
        const std::size_t a = (i + 1) % 3, b = (i + 2) % 3; // edge v[a] -> v[b]
        const std::int32_t dx = x[b] - x[a], dy = y[b] - y[a];
        step_x[i] = -dy * std::int32_t{subpixel_scale};
        // w at the origin: dx (0 - y_a) - dy (0 - x_a) plus the bias (@eq:edge-bias).
        const std::int32_t w = dy * x[a] - dx * y[a] - (is_top_left(dx, dy) ? 0 : 1);
        row[i] = Lanes::broadcast(w) + Lanes::ramp(step_x[i]);
        down[i] = Lanes::broadcast(dx * std::int32_t{subpixel_scale});
    }
    const int width = r.x_end - r.x_begin;
    const unsigned last = (1u << ((width - 1) % 4 + 1)) - 1; // the last four's columns
    const auto emit_bits = [&](unsigned bits, int px, int py) {
        for (; bits != 0; bits &= bits - 1) {
            emit(px + std::countr_zero(bits), py);
        }
    };
    if (width <= 4) { // one four per row, the common case
        for (int py = r.y_begin; py < r.y_end; ++py) {
            emit_bits((row[0] | row[1] | row[2]).nonnegative_bits() & last, r.x_begin,
                      py);
            for (std::size_t i = 0; i < 3; ++i) {
                row[i] = row[i] + down[i];
            }
        }
        return;
    }
    const std::array<Lanes, 3> across{Lanes::broadcast(4 * step_x[0]),
                                      Lanes::broadcast(4 * step_x[1]),
                                      Lanes::broadcast(4 * step_x[2])};
    for (int py = r.y_begin; py < r.y_end; ++py) {
        std::array<Lanes, 3> w = row;
        for (int px = r.x_begin; px < r.x_end; px += 4) {
            const unsigned bits = (w[0] | w[1] | w[2]).nonnegative_bits();
            emit_bits(bits & (px + 4 >= r.x_end ? last : 0xfu), px, py); // not beyond r
            for (std::size_t i = 0; i < 3; ++i) {
                w[i] = w[i] + across[i];
            }
        }
        for (std::size_t i = 0; i < 3; ++i) {
            row[i] = row[i] + down[i];
        }
    }
}
//< traverse-tiny

} // namespace exactpixels
