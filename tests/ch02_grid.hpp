// ch02_grid.hpp: helpers shared by chapter 2's tests: a count per pixel, ASCII masks,
// and every rasterizer of chapters 1 and 2 behind one name.
#pragma once

#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/scanline.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <ostream>
#include <random>
#include <string>
#include <vector>

namespace ch02 {

using namespace exactpixels;

/// How many times each pixel of a width x height frame was emitted.
struct Grid {
    int width = 0;  ///< columns
    int height = 0; ///< rows
    std::vector<int> count = std::vector<int>(static_cast<std::size_t>(width * height));

    /// Counts pixel (x, y); a pixel outside the frame is counted in `outside`.
    void hit(int x, int y) {
        if (x < 0 || y < 0 || x >= width || y >= height) {
            ++outside;
            return;
        }
        ++count[static_cast<std::size_t>(y * width + x)];
    }
    /// The count of pixel (x, y).
    int at(int x, int y) const { return count[static_cast<std::size_t>(y * width + x)]; }
    /// Emitted pixels that lay outside the frame (must stay 0).
    int outside = 0;
    /// The viewport of the whole frame.
    Viewport viewport() const { return {width, height}; }
    /// One character per pixel, rows separated by '\n': '.' for 0, '#' for 1, the digit
    /// for 2..9.
    std::string mask() const {
        std::string s;
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const int c = at(x, y);
                s += c == 0   ? '.'
                     : c == 1 ? '#'
                              : static_cast<char>('0' + std::min(c, 9));
            }
            s += '\n';
        }
        return s;
    }
    /// Grids are equal when sizes and counts are.
    friend bool operator==(const Grid&, const Grid&) = default;
    /// How a failed check prints a grid: its size, pixels outside, and its mask on one
    /// line (rows separated by '/').
    friend std::ostream& operator<<(std::ostream& out, const Grid& grid) {
        std::string rows = grid.mask();
        std::replace(rows.begin(), rows.end(), '\n', '/');
        return out << grid.width << "x" << grid.height << " grid, " << grid.outside
                   << " outside: " << rows;
    }
};

/// The rasterizers and precisions a test can run.
enum class Raster {
    scanline_fixed,
    pixels_fixed,
    blocks_fixed,
    pixels_float,
    blocks_float,
    scanline_double
};

/// A name for messages.
inline const char* name_of(Raster r) {
    switch (r) {
    case Raster::scanline_fixed:
        return "scanline (fixed)";
    case Raster::pixels_fixed:
        return "edge pixels (fixed)";
    case Raster::blocks_fixed:
        return "edge 8x8 (fixed)";
    case Raster::pixels_float:
        return "edge pixels (float)";
    case Raster::blocks_float:
        return "edge 8x8 (float)";
    case Raster::scanline_double:
        return "scanline (double)";
    }
    return "?";
}

/// The three fixed-point rasterizers (exact: must agree pixel for pixel).
inline constexpr std::array<Raster, 3> fixed_rasters{
    Raster::scanline_fixed, Raster::pixels_fixed, Raster::blocks_fixed};

/// Draws the snapped triangle v into g with rasterizer r (float ones get the snapped
/// vertices converted to pixels, which float represents exactly below 2^15 px).
inline void draw(Grid& g, const std::array<FixedPoint2, 3>& v, Raster r) {
    auto hit = [&](int x, int y) { g.hit(x, y); };
    auto span = [&](Span s) {
        for (int x = s.x_begin; x < s.x_end; ++x) {
            g.hit(x, s.y);
        }
    };
    const std::array<Point2, 3> d{to_pixels(v[0]), to_pixels(v[1]), to_pixels(v[2])};
    const std::array<Point2f, 3> f{Point2f(d[0]), Point2f(d[1]), Point2f(d[2])};
    switch (r) {
    case Raster::scanline_fixed:
        scanline_spans(v, g.viewport(), span);
        break;
    case Raster::pixels_fixed:
        edge_rasterize_pixels(v, g.viewport(), hit);
        break;
    case Raster::blocks_fixed:
        edge_rasterize_blocks(v, g.viewport(), hit);
        break;
    case Raster::pixels_float:
        edge_rasterize_pixels(f, g.viewport(), hit);
        break;
    case Raster::blocks_float:
        edge_rasterize_blocks(f, g.viewport(), hit);
        break;
    case Raster::scanline_double:
        scanline_spans(d, g.viewport(), span);
        break;
    }
}

/// Snaps three points given in pixels.
inline std::array<FixedPoint2, 3> snap3(Point2 a, Point2 b, Point2 c) {
    return {snap_to_subpixel(a), snap_to_subpixel(b), snap_to_subpixel(c)};
}

/// A random snapped triangle with vertices in [lo, hi)^2 pixels.
inline std::array<FixedPoint2, 3> random_triangle(std::mt19937_64& rng, double lo,
                                                  double hi) {
    std::uniform_real_distribution<double> u(lo, hi);
    return snap3({u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)});
}

/// A random triangle whose vertices lie on the half-pixel grid (multiples of 1/2 px):
/// its edges pass through pixel centres often, so every tie rule is exercised.
inline std::array<FixedPoint2, 3> random_tie_triangle(std::mt19937_64& rng, int lo,
                                                      int hi) {
    std::uniform_int_distribution<int> u(2 * lo, 2 * hi);
    const auto p = [&] { return Point2{u(rng) / 2.0, u(rng) / 2.0}; };
    return snap3(p(), p(), p());
}

/// Random trials per test: fewer in a Debug (sanitizer) build, which runs 20x slower.
#ifdef NDEBUG
inline constexpr int trials = 4000;
#else
inline constexpr int trials = 400;
#endif

} // namespace ch02
