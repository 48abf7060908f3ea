#include "exactpixels/raster/edge_rasterizer.hpp"

#include "exactpixels/raster/scanline.hpp"

#include <fmt/format.h>

#include <cassert>
#include <cstddef>

namespace exactpixels {

void check_fixed_triangle(const std::array<FixedPoint2, 3>& v) {
    for (int i = 0; i < 3; ++i) {
        try {
            check_fixed_range(v[i]);
        } catch (const Error& error) {
            throw Error(fmt::format("vertex {}: {}", i, error.what()));
        }
    }
}

namespace {

/// check_float_triangle for a triangle of either precision: the value named is the one
/// given, so a double beyond float's range is named as it is, not as infinity.
template <class Point> void check_float_range(const std::array<Point, 3>& v) {
    static_assert(max_float_coordinate == max_fixed_coordinate_px);
    for (int i = 0; i < 3; ++i) {
        try {
            check_pixel_range(static_cast<double>(v[i].x));
            check_pixel_range(static_cast<double>(v[i].y));
        } catch (const Error& error) {
            throw Error(fmt::format("vertex {}: {}", i, error.what()));
        }
    }
}

} // namespace

void check_float_triangle(const std::array<Point2f, 3>& v) {
    check_float_range(v);
}

void check_float_triangle(const std::array<Point2, 3>& v) {
    check_float_range(v);
}

void add_coverage(std::vector<int>& counts, Viewport viewport,
                  const std::array<Point2, 3>& v, RasterizerKind kind,
                  CoveragePrecision precision) {
    assert(counts.size() == static_cast<std::size_t>(viewport.width) *
                                static_cast<std::size_t>(viewport.height));
    const auto count = [&](int x, int y) {
        ++counts[static_cast<std::size_t>(y) * static_cast<std::size_t>(viewport.width) +
                 static_cast<std::size_t>(x)];
    };
    const auto count_span = [&](Span s) {
        for (int x = s.x_begin; x < s.x_end; ++x) {
            count(x, s.y);
        }
    };
    if (precision == CoveragePrecision::fixed) {
        std::array<FixedPoint2, 3> f;
        for (int i = 0; i < 3; ++i) {
            try {
                f[i] = snap_in_range(v[i]);
            } catch (const Error& error) {
                throw Error(fmt::format("vertex {}: {}", i, error.what()));
            }
        }
        switch (kind) {
        case RasterizerKind::scanline:
            scanline_spans(f, viewport, count_span);
            break;
        case RasterizerKind::edge:
            edge_rasterize_pixels(f, viewport, count);
            break;
        case RasterizerKind::edge8x8:
            edge_rasterize_blocks(f, viewport, count);
            break;
        }
        return;
    }
    if (kind != RasterizerKind::scanline) { // the scanline walk reads v in double
        check_float_triangle(v);            // before float would turn 1e39 into infinity
    }
    const std::array<Point2f, 3> f{Point2f(v[0]), Point2f(v[1]), Point2f(v[2])};
    switch (kind) {
    case RasterizerKind::scanline:
        scanline_spans(v, viewport, count_span);
        break;
    case RasterizerKind::edge:
        edge_rasterize_pixels(f, viewport, count);
        break;
    case RasterizerKind::edge8x8:
        edge_rasterize_blocks(f, viewport, count);
        break;
    }
}

} // namespace exactpixels
