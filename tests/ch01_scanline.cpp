// Chapter 1 tests, part 2: the scanline rasterizer. Coverage is checked pixel for pixel
// (ASCII masks, and an exact brute-force reference written straight from the top-left
// rule's definition), watertightness by counting hits, attributes against the plane.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "support/printing.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {

#ifdef NDEBUG
constexpr int trials = 3000;
#else
constexpr int trials = 300; // sanitizer builds: fewer, same properties
#endif

using Mask = std::vector<std::string>;

// A hit count per pixel, filled by the spans a rasterizer emits.
struct Counts {
    int width, height;
    std::vector<int> hits;
    Counts(int w, int h)
        : width(w), height(h), hits(static_cast<std::size_t>(w * h), 0) {}
    int& at(int x, int y) { return hits[static_cast<std::size_t>(y * width + x)]; }
    auto span_counter() {
        return [this](Span s) {
            REQUIRE(s.y >= 0);
            REQUIRE(s.y < height);
            REQUIRE(s.x_begin >= 0);
            REQUIRE(s.x_begin < s.x_end);
            REQUIRE(s.x_end <= width);
            for (int x = s.x_begin; x < s.x_end; ++x) {
                ++at(x, s.y);
            }
        };
    }
    Mask mask() {
        Mask m(static_cast<std::size_t>(height),
               std::string(static_cast<std::size_t>(width), '.'));
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                m[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] =
                    at(x, y) == 0   ? '.'
                    : at(x, y) == 1 ? '#'
                                    : '2';
            }
        }
        return m;
    }
};

template <class Vertex> Mask rasterize(const std::array<Vertex, 3>& v, int w, int h) {
    Counts counts(w, h);
    int last_row = -1;
    scanline_spans(v, Viewport{w, h}, [&](Span s) {
        REQUIRE(s.y > last_row); // one span per row, top to bottom
        last_row = s.y;
        counts.span_counter()(s);
    });
    return counts.mask();
}

std::array<FixedPoint2, 3> snapped(const std::array<Point2, 3>& v) {
    return {snap_to_subpixel(v[0]), snap_to_subpixel(v[1]), snap_to_subpixel(v[2])};
}

bool top_left_inside(const std::array<FixedPoint2, 3>& v, int px, int py);

// Checks both forms against the expected mask, for every vertex order (both windings),
// and the mask itself against the top-left rule's definition (top_left_inside).
void check_mask(std::array<Point2, 3> v, const Mask& expected) {
    const int h = static_cast<int>(expected.size());
    const int w = static_cast<int>(expected[0].size());
    std::array<int, 3> order{0, 1, 2};
    do {
        const std::array<Point2, 3> p{v[order[0]], v[order[1]], v[order[2]]};
        INFO("vertices (" << p[0].x << ", " << p[0].y << "), (" << p[1].x << ", "
                          << p[1].y << "), (" << p[2].x << ", " << p[2].y << ")");
        CHECK(rasterize(p, w, h) == expected);
        CHECK(rasterize(snapped(p), w, h) == expected);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const bool drawn = expected[std::size_t(y)][std::size_t(x)] == '#';
                CHECK(top_left_inside(snapped(p), x, y) == drawn);
            }
        }
    } while (std::next_permutation(order.begin(), order.end()));
}

int covered(const Mask& m) {
    int n = 0;
    for (const std::string& row : m) {
        n += static_cast<int>(std::count(row.begin(), row.end(), '#'));
    }
    return n;
}

// The kind of the edge a-b of a triangle whose third vertex is c, from the definitions of
// chapter 0 in exact integers: horizontal with c below (top) or above (bottom); otherwise
// left when c lies to its right, right when c lies to its left.
enum class EdgeKind { top, bottom, left, right };

EdgeKind edge_kind(FixedPoint2 a, FixedPoint2 b, FixedPoint2 c) {
    if (a.y == b.y) {
        return c.y > a.y ? EdgeKind::top : EdgeKind::bottom;
    }
    // c right of the edge: the edge's x at c.y is less than c.x.
    const std::int64_t right = (c.x - a.x) * (b.y - a.y) - (b.x - a.x) * (c.y - a.y);
    return (right > 0) == (b.y > a.y) ? EdgeKind::left : EdgeKind::right;
}

// The top-left rule straight from its definition, in exact integer arithmetic on the
// snapped vertices: for each edge a-b with third vertex c, the pixel centre p is on c's
// side strictly, or exactly on the edge and the edge is a top edge (horizontal, c below)
// or a left edge (not horizontal, c to its right). Independent of the scanline code.
bool top_left_inside(const std::array<FixedPoint2, 3>& v, int px, int py) {
    const std::int64_t x = px * std::int64_t{256} + 128, y = py * std::int64_t{256} + 128;
    for (int i = 0; i < 3; ++i) {
        const FixedPoint2 a = v[i], b = v[(i + 1) % 3], c = v[(i + 2) % 3];
        const auto side = [&](std::int64_t qx, std::int64_t qy) {
            const std::int64_t e = (b.x - a.x) * (qy - a.y) - (b.y - a.y) * (qx - a.x);
            return (e > 0) - (e < 0);
        };
        const int inside = side(c.x, c.y);
        if (inside == 0) {
            return false; // zero area
        }
        const int s = side(x, y) * inside;
        if (s < 0) {
            return false;
        }
        if (s == 0) {
            const EdgeKind kind = edge_kind(a, b, c);
            if (kind != EdgeKind::top && kind != EdgeKind::left) {
                return false;
            }
        }
    }
    return true;
}

} // namespace

// The masks below are pictures: one string per row, '#' drawn, '.' not.
// clang-format off
TEST_CASE("the absolute convention: a flat-top triangle covers 15 pixels") {
    // Top edge y = 0.5 through six centres (drawn), right edge x = 5.5 (not drawn), the
    // diagonal y = x is a left edge (drawn).
    const Mask expected{
        "#####..",
        ".####..",
        "..###..",
        "...##..",
        "....#..",
        ".......",
        ".......",
    };
    check_mask({{{0.5, 0.5}, {5.5, 0.5}, {5.5, 5.5}}}, expected);
    CHECK(covered(expected) == 15);
}

TEST_CASE("the absolute convention: a flat-bottom triangle covers 10 pixels") {
    // Left edge x = 0.5 (drawn), bottom edge y = 5.5 (not drawn), the diagonal y = x is
    // a right edge (not drawn).
    const Mask expected{
        ".......",
        "#......",
        "##.....",
        "###....",
        "####...",
        ".......",
        ".......",
    };
    check_mask({{{0.5, 5.5}, {0.5, 0.5}, {5.5, 5.5}}}, expected);
    CHECK(covered(expected) == 10);
}

TEST_CASE("vertices on pixel centres and edges through pixel centres") {
    // Pointing right, every vertex on a pixel centre. The vertical edge x = 1.5 is a
    // left edge (drawn); the apex (6.5, 3.5) lies on two right edges (not drawn); the
    // top and bottom vertices each lie on a right edge (not drawn).
    check_mask({{{1.5, 0.5}, {6.5, 3.5}, {1.5, 6.5}}}, {
        "........",
        ".##.....",
        ".####...",
        ".#####..",
        ".####...",
        ".##.....",
        "........",
    });
    // Pointing left: the apex (1.5, 3.5) is where two left edges meet (drawn); the
    // vertical edge x = 6.5 is a right edge (not drawn).
    check_mask({{{6.5, 0.5}, {1.5, 3.5}, {6.5, 6.5}}}, {
        "........",
        ".....#..",
        "...###..",
        ".#####..",
        "...###..",
        ".....#..",
        "........",
    });
    // Vertices between centres: no edge goes through a centre; the plain inside test.
    check_mask({{{0.2, 0.1}, {7.9, 2.3}, {2.6, 5.8}}}, {
        "##......",
        ".####...",
        ".#######",
        "..####..",
        "..###...",
        "..#.....",
    });
}

TEST_CASE("a triangle thinner than a pixel row covers what its centres say") {
    // Between two row centres: no centre inside, nothing drawn.
    check_mask({{{0.0, 1.6}, {7.0, 1.9}, {3.0, 2.4}}}, {
        "....",
        "....",
        "....",
        "....",
    });
    // Its middle vertex (0.2, 1.5) lies on row 1's centre line; the row is drawn from
    // there to the long edge at x = 4.9: centres 0.5 .. 4.5.
    check_mask({{{0.2, 1.5}, {6.8, 1.4}, {3.0, 1.6}}}, {
        ".......",
        "#####..",
        ".......",
    });
}
// clang-format on

TEST_CASE(
    "a vertex on a pixel centre is drawn exactly when both its edges are top or left") {
    // A vertex on a centre lies on two edges at once, so the rule for edges decides it
    // twice. Every kind of tip occurs here: a top edge meeting a left or a right edge, a
    // bottom edge meeting a left or a right edge, two left edges (a tip pointing left),
    // two right edges (pointing right), and a left and a right edge meeting at the top or
    // the bottom. Random triangles with every vertex on a pixel centre, all six vertex
    // orders, both forms: the pixel under each vertex must be drawn exactly when both of
    // its edges, classified from their definitions (edge_kind), are top or left edges.
    const auto name = [](EdgeKind k) {
        return k == EdgeKind::top      ? "top"
               : k == EdgeKind::bottom ? "bottom"
               : k == EdgeKind::left   ? "left"
                                       : "right";
    };
    const std::array<std::string, 8> every_kind{
        "top+left",  "top+right",   "bottom+left",    "bottom+right",
        "left+left", "right+right", "left+right, up", "left+right, down"};
    std::map<std::string, std::array<int, 2>> seen; // kind -> {tips, tips drawn}
    std::mt19937_64 random(24);
    std::uniform_int_distribution<int> centre(0, 11);
    for (int trial = 0; trial < trials; ++trial) {
        std::array<Point2, 3> v{};
        for (Point2& p : v) {
            p = {centre(random) + 0.5, centre(random) + 0.5};
        }
        const std::array<FixedPoint2, 3> f = snapped(v);
        if ((f[1].x - f[0].x) * (f[2].y - f[0].y) ==
            (f[1].y - f[0].y) * (f[2].x - f[0].x)) {
            continue; // no area: no edges to speak of
        }
        for (int k = 0; k < 3; ++k) {
            const FixedPoint2 tip = f[k], a = f[(k + 1) % 3], b = f[(k + 2) % 3];
            std::array<EdgeKind, 2> kinds{edge_kind(tip, a, b), edge_kind(tip, b, a)};
            std::sort(kinds.begin(), kinds.end());
            std::string kind = std::string(name(kinds[0])) + "+" + name(kinds[1]);
            if (kinds[0] == EdgeKind::left && kinds[1] == EdgeKind::right) {
                kind += a.y > tip.y ? ", up" : ", down"; // the other two: below or above
            }
            const bool drawn =
                (kinds[0] == EdgeKind::top || kinds[0] == EdgeKind::left) &&
                (kinds[1] == EdgeKind::top || kinds[1] == EdgeKind::left);
            ++seen[kind][0];
            seen[kind][1] += drawn;
            const int px = static_cast<int>(v[k].x), py = static_cast<int>(v[k].y);
            std::array<int, 3> order{0, 1, 2};
            do {
                const std::array<Point2, 3> p{v[order[0]], v[order[1]], v[order[2]]};
                INFO("tip (" << v[k].x << ", " << v[k].y << ") of kind " << kind
                             << " in triangle (" << p[0].x << ", " << p[0].y << "), ("
                             << p[1].x << ", " << p[1].y << "), (" << p[2].x << ", "
                             << p[2].y << ")");
                const char expected = drawn ? '#' : '.';
                CHECK(rasterize(p, 12, 12)[std::size_t(py)][std::size_t(px)] == expected);
                CHECK(rasterize(snapped(p), 12, 12)[std::size_t(py)][std::size_t(px)] ==
                      expected);
            } while (std::next_permutation(order.begin(), order.end()));
        }
    }
    for (const std::string& kind : every_kind) {
        INFO("tips of kind " << kind << ": " << seen[kind][0] << ", drawn "
                             << seen[kind][1]);
        CHECK(seen[kind][0] > 0); // every kind of tip was tried
    }
    CHECK(seen.size() == every_kind.size()); // and no other kind exists
}

TEST_CASE("fixed-point spans are the exact top-left coverage of the snapped triangle") {
    std::mt19937_64 random(21);
    std::uniform_real_distribution<double> coordinate(-4.0, 36.0);
    std::uniform_int_distribution<int> grid(-8, 72); // half pixels: centres and corners
    const int w = 32, h = 32;
    for (int trial = 0; trial < trials; ++trial) {
        std::array<Point2, 3> v{};
        for (Point2& p : v) { // half the trials on half-pixel positions: many exact ties
            p = trial % 2 ? Point2{coordinate(random), coordinate(random)}
                          : Point2{grid(random) * 0.5, grid(random) * 0.5};
        }
        const std::array<FixedPoint2, 3> f = snapped(v);
        Counts counts(w, h);
        scanline_spans(f, Viewport{w, h}, counts.span_counter());
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                INFO("trial " << trial << ", pixel (" << x << ", " << y << ")");
                REQUIRE(counts.at(x, y) == int(top_left_inside(f, x, y)));
            }
        }
    }
}

TEST_CASE("floating-point spans agree with the exact coverage except at rounding ties") {
    // The double form walks the edges in floating point: a centre within rounding
    // distance of an edge (1e-9 px here) may go either way; every other pixel must
    // match the exact coverage of the same (already snapped) vertices.
    std::mt19937_64 random(22);
    std::uniform_real_distribution<double> coordinate(-4.0, 36.0);
    std::uniform_int_distribution<int> grid(-8, 72);
    const int w = 32, h = 32;
    int ties_seen = 0;
    for (int trial = 0; trial < trials; ++trial) {
        std::array<Point2, 3> v{};
        for (Point2& p : v) {
            p = trial % 2 ? Point2{coordinate(random), coordinate(random)}
                          : Point2{grid(random) * 0.5, grid(random) * 0.5};
        }
        const std::array<FixedPoint2, 3> f = snapped(v);
        const std::array<Point2, 3> exact{to_pixels(f[0]), to_pixels(f[1]),
                                          to_pixels(f[2])};
        Counts counts(w, h);
        scanline_spans(exact, Viewport{w, h}, counts.span_counter());
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                if (counts.at(x, y) == int(top_left_inside(f, x, y))) {
                    continue;
                }
                // A mismatch: the centre must be within 1e-9 px of an edge line.
                double nearest = 1e300;
                for (int i = 0; i < 3; ++i) {
                    const Point2 a = exact[i], b = exact[(i + 1) % 3];
                    const Point2 c = pixel_centre(x, y);
                    const double cross =
                        (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
                    nearest = std::min(nearest, std::abs(cross) / glm::length(b - a));
                }
                INFO("trial " << trial << ", pixel (" << x << ", " << y << ")");
                REQUIRE(nearest <= 1e-9);
                ++ties_seen;
            }
        }
    }
    MESSAGE("pixels decided differently by rounding: " << ties_seen);
    record_fact("ch01_float_span_ties", ties_seen);
}

TEST_CASE("zero-area triangles draw nothing") {
    const std::array<std::array<Point2, 3>, 4> degenerate{{
        {{{2.5, 2.5}, {2.5, 2.5}, {2.5, 2.5}}},
        {{{0.5, 0.5}, {3.5, 3.5}, {6.5, 6.5}}}, // through three pixel centres
        {{{0.5, 2.5}, {4.5, 2.5}, {7.0, 2.5}}}, // along a row of centres
        {{{2.5, 0.0}, {2.5, 4.0}, {2.5, 7.0}}}, // along a column of centres
    }};
    for (const auto& v : degenerate) {
        int calls = 0;
        scanline_spans(v, Viewport{8, 8}, [&](Span) { ++calls; });
        scanline_spans(snapped(v), Viewport{8, 8}, [&](Span) { ++calls; });
        const std::array<Attributes<1>, 3> c{{{0.0}, {1.0}, {2.0}}};
        scanline_interpolate(v, c, Viewport{8, 8},
                             [&](int, int, const Attributes<1>&) { ++calls; });
        CHECK(calls == 0);
    }
}

TEST_CASE("nothing outside the viewport is emitted") {
    // A triangle far larger than the viewport, reaching out on every side.
    const std::array<Point2, 3> v{{{-50.3, -20.1}, {90.7, 3.2}, {10.1, 70.9}}};
    Counts counts(16, 12);
    scanline_spans(v, Viewport{16, 12}, counts.span_counter()); // REQUIREs the bounds
    Counts fixed(16, 12);
    scanline_spans(snapped(v), Viewport{16, 12}, fixed.span_counter());
    for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 16; ++x) {
            CHECK(fixed.at(x, y) == int(top_left_inside(snapped(v), x, y)));
        }
    }
    CHECK(counts.mask() == fixed.mask());
    // An empty viewport gets nothing at all.
    int calls = 0;
    scanline_spans(v, Viewport{0, 0}, [&](Span) { ++calls; });
    scanline_spans(snapped(v), Viewport{0, 5}, [&](Span) { ++calls; });
    CHECK(calls == 0);
}

TEST_CASE("bad coordinates throw an Error naming the value") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const auto ignore = [](Span) {};
    CHECK_THROWS_WITH_AS(scanline_spans(std::array<Point2, 3>{{{0, 0}, {nan, 1}, {2, 2}}},
                                        Viewport{4, 4}, ignore),
                         doctest::Contains("vertex 1"), Error);
    CHECK_THROWS_WITH_AS(
        scanline_spans(std::array<Point2, 3>{{{0, 0}, {1, 1}, {2, 1e30}}}, Viewport{4, 4},
                       ignore),
        doctest::Contains("1000000000000000019884624838656"), Error);
    const std::array<FixedPoint2, 3> far{{{0, 0}, {1 << 29, 0}, {0, 5}}};
    CHECK_THROWS_WITH_AS(scanline_spans(far, Viewport{4, 4}, ignore),
                         doctest::Contains("2097152 px"), Error);
}

TEST_CASE("a jittered grid mesh covers every pixel exactly once") {
    // An 8 x 6 grid of 9.5 px cells; inner grid points jittered by up to 2 px (so every
    // cell stays convex and its two triangles cannot overlap), the
    // border kept straight, each cell split into two triangles along alternating
    // diagonals. Every pixel whose centre lies inside the border rectangle must be hit
    // exactly once: no gaps, no double hits, in both forms.
    std::mt19937_64 random(23);
    std::uniform_real_distribution<double> jitter(-2.0, 2.0);
    const int nx = 8, ny = 6, w = 80, h = 60;
    const double cell = 9.5, x0 = 1.3, y0 = 0.7;
    for (int mesh = 0; mesh < 20; ++mesh) {
        std::vector<Point2> points;
        for (int j = 0; j <= ny; ++j) {
            for (int i = 0; i <= nx; ++i) {
                const bool inner = i > 0 && j > 0 && i < nx && j < ny;
                points.push_back({x0 + i * cell + (inner ? jitter(random) : 0.0),
                                  y0 + j * cell + (inner ? jitter(random) : 0.0)});
            }
        }
        Counts hits(w, h), hits_fixed(w, h);
        for (int j = 0; j < ny; ++j) {
            for (int i = 0; i < nx; ++i) {
                const Point2 a = points[j * (nx + 1) + i],
                             b = points[j * (nx + 1) + i + 1];
                const Point2 c = points[(j + 1) * (nx + 1) + i];
                const Point2 d = points[(j + 1) * (nx + 1) + i + 1];
                const bool flip = (i + j) % 2 == 1;
                const std::array<std::array<Point2, 3>, 2> halves =
                    flip ? std::array<std::array<Point2, 3>, 2>{{{a, b, c}, {b, d, c}}}
                         : std::array<std::array<Point2, 3>, 2>{{{a, b, d}, {a, d, c}}};
                for (const auto& t : halves) {
                    scanline_spans(t, Viewport{w, h}, hits.span_counter());
                    scanline_spans(snapped(t), Viewport{w, h}, hits_fixed.span_counter());
                }
            }
        }
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const Point2 p = pixel_centre(x, y);
                // Inside the rectangle under the top-left rule: [x0, x0 + nx cell) etc.
                const bool inside = p.x >= x0 && p.x < x0 + nx * cell && p.y >= y0 &&
                                    p.y < y0 + ny * cell;
                INFO("mesh " << mesh << ", pixel (" << x << ", " << y << ")");
                REQUIRE(hits.at(x, y) == int(inside));
                REQUIRE(hits_fixed.at(x, y) == int(inside));
            }
        }
    }
}

TEST_CASE("a fan of 720 slivers around a pixel centre covers each pixel once") {
    // 720 triangles of 0.5 degrees each share the vertex at the centre of pixel
    // (20, 20); their outer vertices lie on a circle of radius 18 px. The shared vertex
    // is on 720 edges at once: the top-left rule must give its pixel to exactly one.
    const Point2 centre = pixel_centre(20, 20);
    const int w = 41, h = 41, n = 720;
    const double radius = 18.0;
    std::vector<Point2> rim;
    for (int k = 0; k < n; ++k) {
        const double angle = 2 * std::numbers::pi * k / n;
        rim.push_back(centre + radius * Point2{std::cos(angle), std::sin(angle)});
    }
    Counts hits(w, h), hits_fixed(w, h);
    int fixed_reference = 0;
    for (int k = 0; k < n; ++k) {
        const std::array<Point2, 3> t{centre, rim[k], rim[(k + 1) % n]};
        scanline_spans(t, Viewport{w, h}, hits.span_counter());
        scanline_spans(snapped(t), Viewport{w, h}, hits_fixed.span_counter());
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                fixed_reference += top_left_inside(snapped(t), x, y);
            }
        }
    }
    int total = 0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double r = glm::length(pixel_centre(x, y) - centre);
            INFO("pixel (" << x << ", " << y << "), " << r << " px from the centre");
            REQUIRE(hits.at(x, y) <= 1); // never a double hit
            REQUIRE(hits_fixed.at(x, y) <= 1);
            if (r < radius * std::cos(std::numbers::pi / n) - 1e-9) {
                REQUIRE(hits.at(x, y) == 1); // inside the 720-gon: never a gap
                REQUIRE(hits_fixed.at(x, y) == 1);
            }
            if (r > radius + 1e-9) {
                REQUIRE(hits.at(x, y) == 0);
            }
            total += hits_fixed.at(x, y);
        }
    }
    CHECK(hits.at(20, 20) == 1);
    CHECK(hits_fixed.at(20, 20) == 1);
    CHECK(total == fixed_reference); // and the fan's total is the exact total
}

TEST_CASE("stepped attributes lie on the plane at every pixel centre") {
    // Each drawn value is reached by one prestep down an edge, up to (rows) additions
    // of the edge slope, one prestep along the row and up to (columns) additions of
    // dc/dx. Every addition rounds by at most eps/2 of the running sum, and the edge's
    // x (which the row prestep starts from) drifts the same way. So the error is at most
    // about (rows + columns + 4) eps S, where S = max|c| + |dc/dx| X + |dc/dy| Y bounds
    // every term (X, Y the largest |x|, |y|); the test allows twice that. The reference
    // plane uses the same computed gradient, so gradient rounding is not counted here.
    std::mt19937_64 random(24);
    std::uniform_real_distribution<double> coordinate(-10.0, 110.0), value(-1.0, 1.0);
    const int w = 100, h = 100;
    double worst = 0;
    long drawn_total = 0;
    for (int trial = 0; trial < trials / 10; ++trial) {
        std::array<Point2, 3> v{};
        std::array<Attributes<3>, 3> c{};
        for (int i = 0; i < 3; ++i) {
            v[i] = {coordinate(random), coordinate(random)};
            c[i] = {value(random), 100 * value(random), 1e-3 * value(random)};
        }
        std::array<Gradient<double>, 3> g{};
        for (int k = 0; k < 3; ++k) {
            g[k] = closed_form_gradient<double>(v, {c[0][k], c[1][k], c[2][k]});
        }
        Counts spans(w, h), shaded(w, h);
        scanline_spans(v, Viewport{w, h}, spans.span_counter());
        int rows = 0, columns = 0, last_y = -1, last_x = -1;
        scanline_interpolate(
            v, c, Viewport{w, h}, [&](int x, int y, const Attributes<3>& a) {
                REQUIRE(
                    ((y > last_y) || (y == last_y && x > last_x))); // left to right, down
                rows += y != last_y;
                last_y = y, last_x = x;
                ++shaded.at(x, y);
                ++drawn_total;
                const Point2 p = pixel_centre(x, y);
                for (int k = 0; k < 3; ++k) {
                    const double plane =
                        c[0][k] + g[k].dx * (p.x - v[0].x) + g[k].dy * (p.y - v[0].y);
                    const double size = std::max({std::abs(c[0][k]), std::abs(c[1][k]),
                                                  std::abs(c[2][k])}) +
                                        (std::abs(g[k].dx) + std::abs(g[k].dy)) * 110;
                    const double bound = 2 * (h + w + 4) * 0x1p-52 * size;
                    REQUIRE(std::abs(a[k] - plane) <= bound);
                    worst = std::max(worst, std::abs(a[k] - plane) / (0x1p-52 * size));
                }
                columns = std::max(columns, x);
            });
        CHECK(shaded.hits == spans.hits); // the same pixels as scanline_spans
    }
    MESSAGE("worst |stepped - plane| / (eps S): " << worst << " over " << drawn_total
                                                  << " pixels");
    record_fact("ch01_stepping_worst", worst);
    record_fact("ch01_stepping_bound", 2.0 * (h + w + 4));
    CHECK(drawn_total > 0);
}

TEST_CASE("the first pixel's value is the plane at its centre, not at the vertex") {
    // c = x + 10 y over a triangle whose vertices sit between pixel centres: every
    // drawn pixel must carry c at its own centre, exactly (the edges' dy are powers of
    // two, so every slope and step is a short binary fraction and nothing rounds).
    const std::array<Point2, 3> v{{{1.25, 0.25}, {7.75, 2.25}, {2.25, 4.25}}};
    std::array<Attributes<1>, 3> c{};
    for (int i = 0; i < 3; ++i) {
        c[i] = {v[i].x + 10 * v[i].y};
    }
    int drawn = 0;
    scanline_interpolate(v, c, Viewport{10, 10},
                         [&](int x, int y, const Attributes<1>& a) {
                             INFO("pixel (" << x << ", " << y << ")");
                             CHECK(a[0] == (x + 0.5) + 10 * (y + 0.5));
                             ++drawn;
                         });
    CHECK(drawn > 8);
}

namespace {

// Random inputs on a grid of 1/256 px and values on a grid of 1/256, small enough that
// value + (row + 1/2 - y) * slope is exact in double (a multiple of 2^-16 below 2^20).
struct UpInput {
    double value, slope, y;
};

UpInput random_up_input(std::mt19937_64& random, int trial) {
    std::uniform_int_distribution<int> y(-20 * 256, 60 * 256), number(-4096, 4096);
    // Every fourth y is a multiple of 1/2 px: centres and rows' edges, where the rule
    // decides.
    const int y_units = trial % 4 == 0 ? y(random) / 128 * 128 : y(random);
    return {number(random) / 256.0, number(random) / 256.0, y_units / 256.0};
}

// The lowest row whose centre is at or above y (centre <= y, y down), found by walking
// the rows, not by a formula.
int lowest_row_at_or_above(double y) {
    int row = static_cast<int>(y) + 2;
    while (row + 0.5 > y) {
        --row;
    }
    return row;
}

} // namespace

TEST_CASE("walking up, the first row is the lowest centre at or above the lower end" *
          doctest::description("points: 5; exercise: ch01-prestep-up")) {
    std::mt19937_64 random(41);
    int on_centre = 0;
    for (int trial = 0; trial < trials; ++trial) {
        const UpInput in = random_up_input(random, trial);
        const RowValue r = prestep_up(in.value, in.slope, in.y);
        INFO("y = " << in.y);
        REQUIRE(r.row == lowest_row_at_or_above(in.y));
        on_centre += r.row + 0.5 == in.y;
    }
    // A lower end exactly on a centre: the bottom-left rule draws that row.
    CHECK(prestep_up(0.0, 1.0, 7.5).row == 7);
    CHECK(prestep_up(0.0, 1.0, 7.25).row == 6);
    CHECK(prestep_up(0.0, 1.0, -0.5).row == -1);
    CHECK(prestep_up(0.0, 1.0, -0.75).row == -2);
    CHECK(on_centre > 0);
}

TEST_CASE("walking up, the first value is the edge's value on that row's centre line" *
          doctest::description("points: 5; exercise: ch01-prestep-up")) {
    // The value changes by `slope` per pixel down the edge; on the first row's centre
    // line, (row + 1/2 - y) pixels down (up, as it is negative or zero), it is exactly
    // value + (row + 1/2 - y) * slope: checked in exact rationals.
    std::mt19937_64 random(42);
    for (int trial = 0; trial < trials; ++trial) {
        const UpInput in = random_up_input(random, trial);
        const RowValue r = prestep_up(in.value, in.slope, in.y);
        const int row = lowest_row_at_or_above(in.y);
        const Rational expected =
            exact(in.value) + (Rational(2 * row + 1, 2) - exact(in.y)) * exact(in.slope);
        INFO("value " << in.value << ", slope " << in.slope << ", y " << in.y);
        REQUIRE(exact(r.value) == expected);
    }
}
