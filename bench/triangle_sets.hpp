// triangle_sets.hpp: the benchmarks' triangles (chapters 2 and 10): for a given area,
// `count` well-shaped random triangles (no angle below about 25 degrees), random
// orientation and position inside a side x side frame, scaled to the exact area before
// snapping; the same seed, so the same triangles, in every benchmark program.
#pragma once

#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/base/types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

namespace exactpixels::bench {

/// One area's triangles, in float pixels and snapped (1/256 px).
struct TriangleSet {
    std::vector<std::array<Point2f, 3>> floats;    ///< vertices in px, rounded to float
    std::vector<std::array<FixedPoint2, 3>> fixed; ///< the same vertices snapped
};

/// `count` triangles of area `area` px^2 inside a side x side frame (seeded by area).
inline TriangleSet make_triangles(int area, int count, int side) {
    TriangleSet set;
    std::mt19937_64 rng(static_cast<std::uint64_t>(area));
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 0; n < count; ++n) {
        // Vertices near a circle, about 120 degrees apart: a well-shaped triangle.
        const double turn = 2 * std::numbers::pi * unit(rng);
        std::array<Point2, 3> p;
        for (int k = 0; k < 3; ++k) {
            const double angle =
                turn + 2 * std::numbers::pi * (k + 0.3 * (unit(rng) - 0.5)) / 3;
            const double radius = 0.8 + 0.4 * unit(rng);
            p[k] = radius * Point2{std::cos(angle), std::sin(angle)};
        }
        const double area2 =
            (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
        const double scale = std::sqrt(2.0 * area / std::abs(area2));
        double lo = 1e9, hi = -1e9;
        for (Point2& q : p) {
            q *= scale;
            lo = std::min({lo, q.x, q.y});
            hi = std::max({hi, q.x, q.y});
        }
        // A random position that keeps the whole triangle in the frame.
        const double room = side - (hi - lo) - 2.0;
        const Point2 shift{1.0 - lo + room * unit(rng), 1.0 - lo + room * unit(rng)};
        std::array<Point2f, 3> f;
        std::array<FixedPoint2, 3> x;
        for (int k = 0; k < 3; ++k) {
            f[k] = Point2f(p[k] + shift);
            x[k] = snap_to_subpixel(p[k] + shift);
        }
        set.floats.push_back(f);
        set.fixed.push_back(x);
    }
    return set;
}

} // namespace exactpixels::bench
