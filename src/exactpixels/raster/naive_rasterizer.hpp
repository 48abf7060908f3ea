// naive_rasterizer.hpp: the rasterizer most tutorials teach, kept as the baseline that
// chapter 2's benchmark measures the edge-function rasterizers against.
//
// Usage:
//   std::array<Point2f, 3> v{{{0.5f, 0.5f}, {9.5f, 2.5f}, {3.5f, 7.5f}}};   // pixels
//   naive_rasterize(v, Viewport{64, 48}, [&](int x, int y) { ... });
//
// For every pixel of the bounding box it computes the barycentric coordinates of the
// pixel centre from scratch, in float, with a division each, and draws the pixel when
// all three are >= 0. There is no fill rule: a centre exactly on an edge shared by two
// triangles is drawn by both, and rounding can leave gaps, so it is not watertight.
// Nothing outside [0, width) x [0, height) is emitted; zero area draws nothing;
// either winding is drawn. It is not used for anything but comparison.
#pragma once

#include "exactpixels/base/types.hpp"
#include "exactpixels/raster/span.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace exactpixels {

//> naive
/// Emits emit(x, y) for every pixel whose centre has three non-negative barycentric
/// coordinates, each recomputed per pixel as a ratio of float cross products.
template <class EmitFn>
void naive_rasterize(const std::array<Point2f, 3>& v, Viewport viewport, EmitFn&& emit) {
    const auto cross = [](Point2f a, Point2f b, Point2f p) {
        return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    };
    const float area2 = cross(v[0], v[1], v[2]);
    if (!(area2 != 0.0f)) {
        return; // no area (or not a number): nothing to draw
    }
    const auto clamp_to = [](float c, int size) {
        return static_cast<int>(
            std::clamp(std::floor(c), 0.0f, static_cast<float>(size)));
    };
    const int x0 = clamp_to(std::min({v[0].x, v[1].x, v[2].x}), viewport.width);
    const int y0 = clamp_to(std::min({v[0].y, v[1].y, v[2].y}), viewport.height);
    const int x1 = clamp_to(std::max({v[0].x, v[1].x, v[2].x}) + 1.0f, viewport.width);
    const int y1 = clamp_to(std::max({v[0].y, v[1].y, v[2].y}) + 1.0f, viewport.height);
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            const Point2f p{x + 0.5f, y + 0.5f};
            const float l0 = cross(v[1], v[2], p) / area2; // barycentric of vertex 0
            const float l1 = cross(v[2], v[0], p) / area2;
            const float l2 = cross(v[0], v[1], p) / area2;
            if (l0 >= 0.0f && l1 >= 0.0f && l2 >= 0.0f) {
                emit(x, y);
            }
        }
    }
}
//< naive

} // namespace exactpixels
