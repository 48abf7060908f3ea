// Chapter 1 tests, part 1: the gradient identities. Where the claim is exact algebra the
// test runs the library's own templates in exact rational arithmetic; where it is a
// floating-point claim it states its tolerance and why.
#include "exactpixels/base/exact.hpp"
#include "exactpixels/raster/gradient_stability.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <tuple>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {

#ifdef NDEBUG
constexpr int trials = 20000;
#else
constexpr int trials = 2000; // sanitizer builds: fewer, same properties
#endif

// A triangle with small integer coordinates and values, as exact rationals.
PlaneSamples<Rational> random_integer_triangle(std::mt19937_64& random, int range) {
    std::uniform_int_distribution<int> coordinate(-range, range);
    PlaneSamples<Rational> s{};
    for (int i = 0; i < 3; ++i) {
        s.x[i] = Rational(coordinate(random));
        s.y[i] = Rational(coordinate(random));
        s.c[i] = Rational(coordinate(random));
    }
    return s;
}

Rational twice_area(const PlaneSamples<Rational>& s) {
    return (s.x[2] - s.x[0]) * (s.y[1] - s.y[0]) - (s.x[1] - s.x[0]) * (s.y[2] - s.y[0]);
}

template <class T>
PlaneSamples<T> permuted(const PlaneSamples<T>& s, std::array<int, 3> o) {
    return {{s.x[o[0]], s.x[o[1]], s.x[o[2]]},
            {s.y[o[0]], s.y[o[1]], s.y[o[2]]},
            {s.c[o[0]], s.c[o[1]], s.c[o[2]]}};
}

// Random double triangles: vertices in [0, 1000)^2, values in [0, 1).
PlaneSamples<double> random_triangle(std::mt19937_64& random) {
    std::uniform_real_distribution<double> coordinate(0.0, 1000.0), value(0.0, 1.0);
    PlaneSamples<double> s{};
    for (int i = 0; i < 3; ++i) {
        s.x[i] = coordinate(random);
        s.y[i] = coordinate(random);
        s.c[i] = value(random);
    }
    return s;
}

// How badly shaped the triangle is: (longest edge)^2 / (twice the area). About 1 for
// an equilateral triangle, large for a sliver. Rounding errors of any gradient formula
// are amplified by up to this factor (chapter 1, "How accurate are they?").
double shape_factor(const PlaneSamples<double>& s) {
    double longest = 0;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        longest = std::max(longest, std::hypot(s.x[j] - s.x[i], s.y[j] - s.y[i]));
    }
    const double area2 = // 2A (@eq:split-denominator); its sign does not matter here
        (s.x[1] - s.x[0]) * (s.y[2] - s.y[0]) - (s.x[2] - s.x[0]) * (s.y[1] - s.y[0]);
    return longest * longest / std::abs(area2);
}

// The size of the terms a gradient formula adds up: (largest |c_i - c_j|) / (longest
// edge) + |g|. Rounding errors are about eps kappa times this (chapter 1,
// @eq:error-estimate).
double term_size(const PlaneSamples<double>& s, double gradient_norm) {
    double longest = 0, c_range = 0;
    for (int i = 0; i < 3; ++i) {
        const int j = (i + 1) % 3;
        longest = std::max(longest, std::hypot(s.x[j] - s.x[i], s.y[j] - s.y[i]));
        c_range = std::max(c_range, std::abs(s.c[j] - s.c[i]));
    }
    return c_range / longest + gradient_norm;
}

template <class T> double norm(Gradient<T> g) {
    return std::hypot(static_cast<double>(g.dx), static_cast<double>(g.dy));
}

} // namespace

TEST_CASE("split edge and closed form are the same number in exact arithmetic") {
    std::mt19937_64 random(11);
    int checked = 0;
    for (int trial = 0; trial < trials / 10; ++trial) {
        const PlaneSamples<Rational> s = random_integer_triangle(random, 50);
        if (twice_area(s) == Rational(0)) {
            continue;
        }
        const Gradient<Rational> a = split_edge_gradient(s);
        const Gradient<Rational> b = closed_form_gradient(s);
        INFO("dc/dx: split " << a.dx << ", closed " << b.dx);
        INFO("dc/dy: split " << a.dy << ", closed " << b.dy);
        REQUIRE(a.dx == b.dx);
        REQUIRE(a.dy == b.dy);
        // And the plane through the gradient reproduces c at all three vertices.
        for (int i = 0; i < 3; ++i) {
            CHECK(s.c[0] + b.dx * (s.x[i] - s.x[0]) + b.dy * (s.y[i] - s.y[0]) == s.c[i]);
        }
        ++checked;
    }
    CHECK(checked > trials / 20);
}

TEST_CASE("closed form is unchanged by every vertex order") {
    const std::array<std::array<int, 3>, 6> orders{
        {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    std::mt19937_64 random(12);
    for (int trial = 0; trial < trials / 20; ++trial) {
        const PlaneSamples<Rational> s = random_integer_triangle(random, 100);
        const Gradient<Rational> first = closed_form_gradient(s);
        if (twice_area(s) != Rational(0)) {
            // It is the plane's gradient (not merely the same wrong answer six times):
            // stepping from vertex 0 reaches c at the other two vertices exactly.
            for (int i = 1; i < 3; ++i) {
                REQUIRE(s.c[0] + first.dx * (s.x[i] - s.x[0]) +
                            first.dy * (s.y[i] - s.y[0]) ==
                        s.c[i]);
            }
        }
        for (const auto& order : orders) {
            const Gradient<Rational> g = closed_form_gradient(permuted(s, order));
            REQUIRE(g.dx == first.dx); // exactly, not within a tolerance
            REQUIRE(g.dy == first.dy);
        }
    }
    // In double the six orders round differently, but only by a few units in the last
    // place times the shape factor: the bound of "split edge and closed form agree".
    for (int trial = 0; trial < trials / 10; ++trial) {
        const PlaneSamples<double> s = random_triangle(random);
        const double kappa = shape_factor(s);
        if (!(kappa < 1e6)) {
            continue;
        }
        const Gradient<double> first = closed_form_gradient(s);
        for (const auto& order : orders) {
            const Gradient<double> g = closed_form_gradient(permuted(s, order));
            const double difference =
                norm(Gradient<double>{g.dx - first.dx, g.dy - first.dy});
            REQUIRE(difference <= 64 * kappa * 0x1p-52 * term_size(s, norm(first)));
        }
    }
}

TEST_CASE("split edge and closed form agree on random triangles") {
    // Both formulas divide a difference of products by a difference of products. The
    // products round by eps relative, so the error is about eps kappa times the size
    // of the terms (@eq:error-estimate): the test allows 32 eps kappa (|delta c| / L +
    // |g|) for each method against the exact gradient of the same input, in float and
    // double (the worst seen over these trials is recorded for the text).
    std::mt19937_64 random(13);
    double worst_double = 0, worst_float = 0;
    int checked = 0;
    for (int trial = 0; trial < trials; ++trial) {
        PlaneSamples<double> s = random_triangle(random);
        for (int i = 0; i < 3;
             ++i) { // on the 2^-40 grid, float-exact: see exact_gradient
            s.x[i] = static_cast<float>(std::nearbyint(s.x[i] * 0x1p12) * 0x1p-12);
            s.y[i] = static_cast<float>(std::nearbyint(s.y[i] * 0x1p12) * 0x1p-12);
            s.c[i] = static_cast<float>(std::nearbyint(s.c[i] * 0x1p20) * 0x1p-20);
        }
        const double kappa = shape_factor(s);
        const Gradient<Rational> exact = exact_gradient(s);
        if (!(kappa < 1e5)) {
            continue; // near-degenerate: the error bound grows without limit
        }
        const double size =
            term_size(s, std::hypot(to_double(exact.dx), to_double(exact.dy)));
        const auto error = [&](auto g) { // the difference exact, rounded once
            return std::hypot(to_double(Rational(g.dx) - exact.dx),
                              to_double(Rational(g.dy) - exact.dy)) /
                   size;
        };
        PlaneSamples<float> f{};
        for (int i = 0; i < 3; ++i) {
            f.x[i] = float(s.x[i]), f.y[i] = float(s.y[i]), f.c[i] = float(s.c[i]);
        }
        const double eps_d = std::numeric_limits<double>::epsilon();
        const double eps_f = std::numeric_limits<float>::epsilon();
        const double errors_d[] = {error(split_edge_gradient(s)),
                                   error(closed_form_gradient(s))};
        const double errors_f[] = {error(split_edge_gradient(f)),
                                   error(closed_form_gradient(f))};
        for (const double e : errors_d) {
            REQUIRE(e <= 32 * kappa * eps_d);
            worst_double = std::max(worst_double, e / (kappa * eps_d));
        }
        for (const double e : errors_f) {
            REQUIRE(e <= 32 * kappa * eps_f);
            worst_float = std::max(worst_float, e / (kappa * eps_f));
        }
        ++checked;
    }
    MESSAGE("worst error / (kappa eps): double " << worst_double << ", float "
                                                 << worst_float);
    record_fact("ch01_gradient_worst_k", std::max(worst_double, worst_float));
    CHECK(checked > trials / 2);
}

TEST_CASE("both edge slopes are the same number in exact arithmetic") {
    std::mt19937_64 random(14);
    for (int trial = 0; trial < trials / 10; ++trial) {
        const PlaneSamples<Rational> s = random_integer_triangle(random, 50);
        if (twice_area(s) == Rational(0)) {
            continue;
        }
        const Gradient<Rational> g = closed_form_gradient(s);
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3;
            const Rational direct =
                edge_slope_direct(s.x[a], s.y[a], s.c[a], s.x[b], s.y[b], s.c[b]);
            const Rational via =
                edge_slope_from_gradient(g, s.x[a], s.y[a], s.x[b], s.y[b]);
            REQUIRE(direct == via);
            // The slope is the same walked either way along the edge.
            REQUIRE(edge_slope_direct(s.x[b], s.y[b], s.c[b], s.x[a], s.y[a], s.c[a]) ==
                    direct);
        }
    }
}

TEST_CASE("both edge slopes agree in floating point") {
    // The form from the gradient inherits the gradient's error (32 eps kappa times the
    // term size, see above) times (1 + |dx/dy|); the direct form rounds twice. The
    // tolerance is the sum.
    std::mt19937_64 random(15);
    for (int trial = 0; trial < trials; ++trial) {
        const PlaneSamples<double> s = random_triangle(random);
        const double kappa = shape_factor(s);
        if (!(kappa < 1e5)) {
            continue;
        }
        const Gradient<double> g = closed_form_gradient(s);
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3;
            const glm::dvec2 pa{s.x[a], s.y[a]}, pb{s.x[b], s.y[b]};
            const double direct = edge_slope_direct(pa, s.c[a], pb, s.c[b]);
            const double via = edge_slope_from_gradient(g, pa, pb);
            const double dxdy = (pb.x - pa.x) / (pb.y - pa.y);
            const double eps = 0x1p-52;
            const double tolerance =
                32 * kappa * eps * term_size(s, norm(g)) * (1 + std::abs(dxdy)) +
                4 * eps * std::abs(direct);
            REQUIRE(std::abs(direct - via) <= tolerance);
        }
    }
}

TEST_CASE("flat-top and flat-bottom triangles need no special case") {
    // c = 1 + 2x + 3y sampled at integer vertices: every formula is exact in double.
    const auto plane = [](double x, double y) { return 1 + 2 * x + 3 * y; };
    const std::array<std::array<glm::dvec2, 3>, 4> triangles{{
        {{{0, 0}, {8, 0}, {3, 5}}}, // flat top (y down: the third vertex below)
        {{{3, 0}, {0, 5}, {8, 5}}}, // flat bottom
        {{{8, 0}, {3, 5}, {0, 0}}}, // flat top, other order
        {{{0, 5}, {3, 0}, {8, 5}}}, // flat bottom, other order
    }};
    for (const auto& p : triangles) {
        const std::array<double, 3> c{plane(p[0].x, p[0].y), plane(p[1].x, p[1].y),
                                      plane(p[2].x, p[2].y)};
        const Gradient<double> closed = closed_form_gradient(p, c);
        CHECK(closed.dx == 2.0);
        CHECK(closed.dy == 3.0);
        const Gradient<double> split = split_edge_gradient(p, c);
        CHECK(split.dx == 2.0);
        CHECK(std::abs(split.dy - 3.0) <= 4 * std::numeric_limits<double>::epsilon() * 3);
        const std::array<glm::vec2, 3> pf{glm::vec2(p[0]), glm::vec2(p[1]),
                                          glm::vec2(p[2])};
        const std::array<float, 3> cf{float(c[0]), float(c[1]), float(c[2])};
        const Gradient<float> closed_f = closed_form_gradient(pf, cf);
        CHECK(closed_f.dx == 2.0f); // integer products, one division: exact
        CHECK(closed_f.dy == 3.0f);
        // The split edge's dc/dy subtracts two rounded quotients (c3 - c1)/(y3 - y1)
        // and dc/dx (x3 - x1)/(y3 - y1): within a few float ulps of 3, not exactly 3.
        const Gradient<float> split_f = split_edge_gradient(pf, cf);
        CHECK(split_f.dx == 2.0f);
        CHECK(std::abs(split_f.dy - 3.0f) <=
              4 * std::numeric_limits<float>::epsilon() * 3);
    }
}

TEST_CASE("zero-area triangles have a zero gradient and no NaN") {
    const std::array<std::array<glm::dvec2, 3>, 5> degenerate{{
        {{{1, 1}, {1, 1}, {1, 1}}}, // one point
        {{{0, 0}, {2, 2}, {5, 5}}}, // collinear, slanted
        {{{0, 3}, {4, 3}, {9, 3}}}, // collinear on one row: no y-delta at all
        {{{2, 0}, {2, 4}, {2, 9}}}, // collinear in one column
        {{{0, 0}, {4, 4}, {0, 0}}}, // two vertices coincide
    }};
    const std::array<double, 3> c{0.25, 1.0, -3.0};
    for (const auto& p : degenerate) {
        for (const Gradient<double> g :
             {closed_form_gradient(p, c), split_edge_gradient(p, c)}) {
            CHECK(g.dx == 0.0);
            CHECK(g.dy == 0.0);
        }
        const std::array<glm::vec2, 3> pf{glm::vec2(p[0]), glm::vec2(p[1]),
                                          glm::vec2(p[2])};
        const std::array<float, 3> cf{0.25f, 1.0f, -3.0f};
        for (const Gradient<float> g :
             {closed_form_gradient(pf, cf), split_edge_gradient(pf, cf)}) {
            CHECK(g.dx == 0.0f);
            CHECK(g.dy == 0.0f);
        }
        // A horizontal edge has no slope down it: 0, not a division by zero.
        CHECK(edge_slope_direct(glm::dvec2{0, 3}, 1.0, glm::dvec2{4, 3}, 2.0) == 0.0);
        CHECK(edge_slope_from_gradient(Gradient<double>{1, 1}, glm::dvec2{0, 3},
                                       glm::dvec2{4, 3}) == 0.0);
    }
}

TEST_CASE("the stability study's reference is the exact gradient") {
    // exact_gradient computes @eq:closed-form in integers (every input in units of
    // 2^-40) and keeps each component as an exact fraction. Check it against the
    // library's closed form run in Rational arithmetic on the exact values of the same
    // doubles (also for the triangles moved to about 4000 px, Exercise 5, in double and
    // rounded to float): a second, independent computation, which must give the very
    // same fractions. Neither rounds, so the reference is the same on every platform,
    // finer than any floating type (the former one, a wider float, was a plain double
    // on MSVC and Apple Silicon).
    int compared = 0;
    for (const auto& [delta, origin, as_float] :
         {std::tuple{1e-2, 0.0, false}, std::tuple{1e-9, 0.0, false},
          std::tuple{0.0, 0.0, false}, std::tuple{1e-2, 3072.0, false},
          std::tuple{1e-2, 3072.0, true}, std::tuple{1e-9, 3072.0, true}}) {
        for (const PlaneSamples<double>& s :
             stability_triangles(delta, 50, 7, as_float, origin)) {
            PlaneSamples<Rational> r{};
            for (int i = 0; i < 3; ++i) {
                r.x[i] = exact(s.x[i]);
                r.y[i] = exact(s.y[i]);
                r.c[i] = exact(s.c[i]);
            }
            const Gradient<Rational> g = closed_form_gradient(r);
            const Gradient<Rational> e = exact_gradient(s);
            INFO("dc/dx " << g.dx << " vs " << e.dx << ", dc/dy " << g.dy << " vs "
                          << e.dy);
            REQUIRE(e.dx == g.dx);
            REQUIRE(e.dy == g.dy);
            compared += g.dx != 0 || g.dy != 0;
        }
    }
    CHECK(compared == 6 * 50); // the study keeps only triangles with a gradient
}

TEST_CASE("neither gradient loses accuracy as the y-delta shrinks") {
    // The chapter's stability table, re-measured on fewer triangles. What it claims:
    // on typical triangles (the median) both methods are accurate to within one
    // machine epsilon at every y-delta down to 1e-12 px and at exactly 0; 99% of
    // triangles are within 64 eps. In double with a non-zero y-delta the closed form is
    // the more accurate one (smaller median, wins more trials); at y-delta exactly 0
    // the split edge is (its point 4 is then a vertex, computed without rounding).
    const auto rows = gradient_stability_study(trials / 4, 1);
    for (const StabilityRow& r : rows) {
        INFO("y-delta " << r.y_delta << ", " << r.precision);
        CHECK(r.split_median <= 1.0);
        CHECK(r.closed_median <= 1.0);
        CHECK(r.split_p99 <= 64.0);
        CHECK(r.closed_p99 <= 64.0);
        if (r.precision == "double" && r.y_delta > 0) {
            CHECK(r.closed_median < r.split_median);
            CHECK(r.closed_better > r.split_better);
        }
        if (r.y_delta == 0) {
            CHECK(r.split_better > r.closed_better);
        }
    }
}

namespace {

// A triangle in space with small integer coordinates and values, as exact rationals.
struct SpaceTriangle {
    std::array<Vector3<Rational>, 3> p;
    std::array<Rational, 3> c;
};

SpaceTriangle random_space_triangle(std::mt19937_64& random, int range) {
    std::uniform_int_distribution<int> coordinate(-range, range);
    SpaceTriangle t{};
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < 3; ++k) {
            t.p[i][k] = Rational(coordinate(random));
        }
        t.c[i] = Rational(coordinate(random));
    }
    return t;
}

Rational dot(const Vector3<Rational>& a, const Vector3<Rational>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

Vector3<Rational> minus(const Vector3<Rational>& a, const Vector3<Rational>& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// The normal e2 x e3, computed here, not by the library.
Vector3<Rational> normal_of(const SpaceTriangle& t) {
    const Vector3<Rational> a = minus(t.p[1], t.p[0]), b = minus(t.p[2], t.p[0]);
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0]};
}

} // namespace

TEST_CASE("the gradient in space gives every edge's change of c" *
          doctest::description("points: 10; exercise: ch01-gradient-3d")) {
    // The plane c[0] + g . (p - p[0]) must take the value c[i] at every vertex: g . e
    // is the change of c along each edge e, exactly, in every vertex order.
    std::mt19937_64 random(31);
    int checked = 0;
    for (int trial = 0; trial < trials / 20; ++trial) {
        const SpaceTriangle t = random_space_triangle(random, 30);
        if (dot(normal_of(t), normal_of(t)) == Rational(0)) {
            continue;
        }
        for (const auto& o :
             std::array<std::array<int, 3>, 3>{{{0, 1, 2}, {1, 2, 0}, {2, 1, 0}}}) {
            const std::array<Vector3<Rational>, 3> p{t.p[o[0]], t.p[o[1]], t.p[o[2]]};
            const std::array<Rational, 3> c{t.c[o[0]], t.c[o[1]], t.c[o[2]]};
            const Vector3<Rational> g = closed_form_gradient_3d(p, c);
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j) {
                    INFO("from vertex " << i << " to vertex " << j << ", g = (" << g[0]
                                        << ", " << g[1] << ", " << g[2] << ")");
                    REQUIRE(dot(g, minus(p[j], p[i])) == c[j] - c[i]);
                }
            }
        }
        ++checked;
    }
    CHECK(checked > trials / 40);
}

TEST_CASE("the gradient in space lies in the triangle's plane" *
          doctest::description("points: 5; exercise: ch01-gradient-3d")) {
    // Along the normal c does not change on the triangle, so the steepest direction has
    // no part along it: g . n = 0. (Without it, g + k n would also pass the edges' test.)
    // A triangle whose c varies has a gradient that is not zero.
    std::mt19937_64 random(32);
    int checked = 0;
    for (int trial = 0; trial < trials / 20; ++trial) {
        const SpaceTriangle t = random_space_triangle(random, 30);
        const Vector3<Rational> n = normal_of(t);
        if (dot(n, n) == Rational(0) || (t.c[0] == t.c[1] && t.c[1] == t.c[2])) {
            continue;
        }
        const Vector3<Rational> g = closed_form_gradient_3d(t.p, t.c);
        CHECK(dot(g, n) == Rational(0));
        CHECK(dot(g, g) != Rational(0));
        ++checked;
    }
    CHECK(checked > trials / 40);
}

TEST_CASE(
    "on the screen plane the gradient in space is chapter 1's, and zero area gives 0" *
    doctest::description("points: 5; exercise: ch01-gradient-3d")) {
    // With every z = 0 the plane is the screen's: (g_x, g_y) is @eq:closed-form's
    // gradient and g_z = 0. A triangle without area has no plane: {0, 0, 0}.
    std::mt19937_64 random(33);
    int checked = 0;
    for (int trial = 0; trial < trials / 20; ++trial) {
        const PlaneSamples<Rational> s = random_integer_triangle(random, 50);
        if (twice_area(s) == Rational(0)) {
            continue;
        }
        const std::array<Vector3<Rational>, 3> p{{{s.x[0], s.y[0], Rational(0)},
                                                  {s.x[1], s.y[1], Rational(0)},
                                                  {s.x[2], s.y[2], Rational(0)}}};
        const Vector3<Rational> g = closed_form_gradient_3d(p, s.c);
        const Gradient<Rational> flat = split_edge_gradient(s);
        CHECK(g[0] == flat.dx);
        CHECK(g[1] == flat.dy);
        CHECK(g[2] == Rational(0));
        ++checked;
    }
    CHECK(checked > trials / 40);
    const std::array<Vector3<double>, 3> line{{{0, 0, 0}, {1, 2, 3}, {2, 4, 6}}};
    const Vector3<double> none = closed_form_gradient_3d(line, {1.0, 2.0, 4.0});
    CHECK(none[0] == 0.0);
    CHECK(none[1] == 0.0);
    CHECK(none[2] == 0.0);
}
