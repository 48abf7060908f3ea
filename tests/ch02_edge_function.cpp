// Chapter 2 tests: the edge function's identities (sum, stepping, barycentrics, the
// gradient), the top-left rule as a bias, and the exact fixed-point range.
#include "ch02_grid.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/raster/edge_function.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace exactpixels;

namespace {

/// The edge function in exact integers: the reference that cannot overflow.
Integer wide_edge(FixedPoint2 a, FixedPoint2 b, FixedPoint2 p) {
    return Integer{b.x - a.x} * Integer{p.y - a.y} -
           Integer{b.y - a.y} * Integer{p.x - a.x};
}

/// A random fixed-point point anywhere in the exact range.
FixedPoint2 random_point(std::mt19937_64& rng,
                         std::int64_t limit = max_fixed_coordinate) {
    std::uniform_int_distribution<std::int64_t> u(-limit, limit);
    return {u(rng), u(rng)};
}

} // namespace

TEST_CASE("the three edge functions sum to twice the area at every point, exactly") {
    std::mt19937_64 rng(2);
    for (int trial = 0; trial < ch02::trials; ++trial) {
        // Half the trials near the origin, half spread over the whole exact range.
        const std::int64_t limit = trial % 2 ? max_fixed_coordinate : 64 * subpixel_scale;
        const std::array<FixedPoint2, 3> v{
            random_point(rng, limit), random_point(rng, limit), random_point(rng, limit)};
        const FixedPoint2 p = random_point(rng, limit);
        const std::int64_t e0 = edge_function(v[1], v[2], p);
        const std::int64_t e1 = edge_function(v[2], v[0], p);
        const std::int64_t e2 = edge_function(v[0], v[1], p);
        const std::int64_t area2 = edge_function(v[0], v[1], v[2]);
        // Each value equals the 128-bit reference (no overflow anywhere in the range) ...
        REQUIRE(Integer{e0} == wide_edge(v[1], v[2], p));
        REQUIRE(Integer{area2} == wide_edge(v[0], v[1], v[2]));
        // ... and the identity (@eq:edge-sum) holds exactly.
        REQUIRE(e0 + e1 + e2 == area2);
    }
}

TEST_CASE("incremental edge values equal direct evaluation bit for bit") {
    std::mt19937_64 rng(3);
    const Viewport viewport{96, 80};
    std::int64_t pixels_checked = 0;
    for (int trial = 0; trial < ch02::trials / 10; ++trial) {
        const auto v = ch02::random_triangle(rng, -20.0, 110.0);
        const EdgeSetup<FixedEdge> s = setup_edges(v);
        const PixelRect r = pixel_bounds(v, viewport);
        for (int i = 0; i < 3; ++i) {
            const FixedEdge& e = s.edge[i];
            std::int64_t row = e.at(r.x_begin, r.y_begin);
            for (int y = r.y_begin; y < r.y_end; ++y, row += e.step_y()) {
                std::int64_t w = row;
                for (int x = r.x_begin; x < r.x_end; ++x, w += e.step_x()) {
                    // Stepped (@eq:edge-steps) == direct (@eq:edge-function plus the
                    // bias).
                    const FixedPoint2 b{e.a.x + e.dx, e.a.y + e.dy};
                    REQUIRE(w == e.at(x, y));
                    REQUIRE(w ==
                            edge_function(e.a, b, fixed_pixel_centre(x, y)) + e.bias);
                    ++pixels_checked;
                }
            }
        }
    }
    CHECK(pixels_checked > 100000); // the boxes were not all empty
}

TEST_CASE("barycentric weights sum to one and reproduce the vertex values" *
          doctest::description("points: 10; exercise: ch02-barycentric")) {
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> value(-10.0, 10.0);
    constexpr double u = std::numeric_limits<double>::epsilon() / 2; // unit roundoff
    for (int trial = 0; trial < ch02::trials; ++trial) {
        const auto v = ch02::random_triangle(rng, -1000.0, 1000.0);
        if (edge_function(v[0], v[1], v[2]) == 0) {
            continue;
        }
        // At the vertices the weights are exactly (1, 0, 0), (0, 1, 0), (0, 0, 1): the
        // edge functions there are exactly 0 or exactly twice the area.
        for (int i = 0; i < 3; ++i) {
            const auto l = barycentric(v, v[i]);
            for (int j = 0; j < 3; ++j) {
                REQUIRE(l[j] == (i == j ? 1.0 : 0.0));
            }
        }
        // Anywhere: each weight is two roundings (to double, then the division) from the
        // exact ratio, relative error <= 2u each; the sum adds two more roundings. So
        // |sum - 1| <= 4u (|l0| + |l1| + |l2|) + 2u.
        const FixedPoint2 p = ch02::random_triangle(rng, -2000.0, 2000.0)[0];
        const auto l = barycentric(v, p);
        const double magnitude = std::abs(l[0]) + std::abs(l[1]) + std::abs(l[2]);
        REQUIRE(magnitude > 0.0);
        REQUIRE(std::abs(l[0] + l[1] + l[2] - 1.0) <= 4 * u * magnitude + 2 * u);
        // An attribute interpolated with the weights reproduces the vertex values.
        const std::array<double, 3> c{value(rng), value(rng), value(rng)};
        for (int i = 0; i < 3; ++i) {
            const auto w = barycentric(v, v[i]);
            REQUIRE(w[0] * c[0] + w[1] * c[1] + w[2] * c[2] == c[i]);
        }
    }
}

TEST_CASE("the edge-function gradient is chapter 1's closed form, exactly") {
    std::mt19937_64 rng(5);
    std::uniform_int_distribution<int> coordinate(-4000, 4000); // in 1/256 px
    std::uniform_int_distribution<int> value(-1000, 1000);
    int compared = 0;
    for (int trial = 0; trial < ch02::trials / 4; ++trial) {
        PlaneSamples<Rational> s;
        for (int i = 0; i < 3; ++i) {
            s.x[i] = Rational(coordinate(rng), 256);
            s.y[i] = Rational(coordinate(rng), 256);
            s.c[i] = Rational(value(rng), 16);
        }
        const Gradient<Rational> a = edge_function_gradient(s);
        const Gradient<Rational> b = closed_form_gradient(s);
        REQUIRE(a.dx == b.dx);
        REQUIRE(a.dy == b.dy);
        compared += a.dx != Rational(0);
    }
    CHECK(compared > ch02::trials / 8);
}

TEST_CASE("top and left edges are told apart by the signs of dx and dy" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    // Triangles oriented with the inside on the right of every edge (y down).
    CHECK(is_top_left(1, 0));        // horizontal, going right: a top edge
    CHECK_FALSE(is_top_left(-1, 0)); // horizontal, going left: a bottom edge
    CHECK(is_top_left(0, -1));       // going up: a left edge
    CHECK(is_top_left(5, -3));       // going up and right: a left edge
    CHECK(is_top_left(-5, -3));      // going up and left: a left edge
    CHECK_FALSE(is_top_left(0, 1));  // going down: a right edge
    CHECK_FALSE(is_top_left(-2, 7));
    CHECK_FALSE(is_top_left(2, 7));
    // The bias: on the triangle (0,0), (4,0), (0,4) px, the top edge (0,0)-(4,0) and the
    // left edge (0,4)-(0,0) get 0, the hypotenuse (a right/bottom edge) gets -1.
    const auto s = setup_edges(ch02::snap3({0, 0}, {4, 0}, {0, 4}));
    CHECK(s.edge[2].bias == 0);  // v0 -> v1: top
    CHECK(s.edge[1].bias == 0);  // v2 -> v0: left
    CHECK(s.edge[0].bias == -1); // v1 -> v2: the hypotenuse
}

TEST_CASE("the fixed-point range: exact at its edge, an error beyond it") {
    // At the very edge every edge function is exact: the largest possible triangle.
    const std::int64_t m = max_fixed_coordinate;
    const std::array<FixedPoint2, 3> big{{{-m, -m}, {m, -m}, {-m, m}}};
    const FixedPoint2 corner{m, m};
    CHECK(Integer{edge_function(big[1], big[2], corner)} ==
          wide_edge(big[1], big[2], corner));
    CHECK(edge_function(big[0], big[1], big[2]) == 4 * m * m);
    CHECK_NOTHROW(check_fixed_range(corner));
    CHECK_NOTHROW(snap_in_range({max_fixed_coordinate_px, -max_fixed_coordinate_px}));
    // One unit beyond, and anything not finite, is refused with the value in the message.
    CHECK_THROWS_WITH_AS(check_fixed_range({m + 1, 0}),
                         doctest::Contains("1048576.00390625"), Error);
    CHECK_THROWS_WITH_AS(check_fixed_range({0, -m - 1}),
                         doctest::Contains("-1048576.00390625"), Error);
    CHECK_THROWS_WITH_AS(snap_in_range({1048576.5, 0}), doctest::Contains("1048576.5"),
                         Error);
    CHECK_THROWS_AS(snap_in_range({std::nan(""), 0}), Error);
    CHECK_THROWS_AS(snap_in_range({0, std::numeric_limits<double>::infinity()}), Error);
}

namespace {
/// The nearest integer to 256 v, halves up: floor(256 v + 1/2) of v's exact value,
/// computed without rounding, for any finite v.
Integer exact_snap(double v) {
    return floor_of(Rational(1 << subpixel_bits) * exact(v) + Rational(1, 2));
}
} // namespace

TEST_CASE("snapping rounds 256 v to the nearest integer exactly, halves up") {
    // The classic fault of floor(256 v + 0.5): just below a half, the sum rounds up to 1.
    const double below_half = 0.49999999999999994 / 256.0;
    CHECK(0.49999999999999994 + 0.5 == 1.0); // the sum the old formula rounded
    CHECK(snap_to_subpixel(below_half) == 0);
    CHECK(snap_to_subpixel(0.5 / 256.0) == 1);   // a half rounds up
    CHECK(snap_to_subpixel(-0.5 / 256.0) == 0);  // towards +infinity
    CHECK(snap_to_subpixel(-1.5 / 256.0) == -1); // likewise
    CHECK(snap_in_range({-1.5 / 256.0, -0.0}) == FixedPoint2{-1, 0});
    CHECK(snap_in_range({-max_fixed_coordinate_px, max_fixed_coordinate_px}) ==
          FixedPoint2{-max_fixed_coordinate, max_fixed_coordinate});
    CHECK(snap_in_range({-below_half, -3.0 / 256.0}) == FixedPoint2{0, -3});
    // Every neighbour of every half-integer tried, against the exact fraction.
    std::mt19937_64 rng(15);
    std::uniform_int_distribution<std::int64_t> k(-max_fixed_coordinate,
                                                  max_fixed_coordinate);
    std::uniform_real_distribution<double> any(-max_fixed_coordinate_px,
                                               max_fixed_coordinate_px);
    int checked = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const double half = (static_cast<double>(k(rng)) + 0.5) / 256.0;
        for (const double v :
             {half, std::nextafter(half, -1e300), std::nextafter(half, 1e300), any(rng),
              std::ldexp(any(rng), -40), -below_half, below_half}) {
            REQUIRE(Integer{snap_to_subpixel(v)} == exact_snap(v));
            if (std::abs(v) <= max_fixed_coordinate_px) { // snap_in_range's own floor
                const FixedPoint2 both = snap_in_range({v, -v});
                REQUIRE(Integer{both.x} == exact_snap(v));
                REQUIRE(Integer{both.y} == exact_snap(-v));
            }
            ++checked;
        }
    }
    CHECK(checked == 140000);
}

TEST_CASE("snapping refuses NaN, infinity and values too large for int64") {
    // Converting any of these to an integer is undefined behaviour in C++; the old
    // snap did it, and UBSan's float-cast-overflow check stops there.
    const double inf = std::numeric_limits<double>::infinity();
    for (const double v : {inf, -inf, std::nan(""), 0x1p54, -0x1p54, 1e300}) {
        CAPTURE(v);
        CHECK_THROWS_WITH_AS(snap_to_subpixel(v), doctest::Contains("cannot be snapped"),
                             Error);
    }
    // The largest accepted magnitude converts exactly.
    const double largest = std::nextafter(0x1p54, 0.0);
    CHECK(snap_to_subpixel(largest) == static_cast<std::int64_t>(largest * 256.0));
    CHECK(snap_to_subpixel(-largest) == -static_cast<std::int64_t>(largest * 256.0));
}
