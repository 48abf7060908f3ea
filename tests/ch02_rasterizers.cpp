// Chapter 2 tests: what the edge-function rasterizers draw. Exact masks, watertight
// meshes, agreement between the traversals and with chapter 1's scanline rasterizer,
// invariances, block classification, the range limits, and where float differs.
#include "ch02_grid.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/naive_rasterizer.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "support/printing.hpp"
#include "support/meshes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

using namespace exactpixels;
using ch02::Grid;
using ch02::Raster;
using exactpixels::testing::grid_mesh;
using exactpixels::testing::sliver_fan;

namespace {

constexpr std::array<Raster, 6> all_rasters{
    Raster::scanline_fixed, Raster::pixels_fixed, Raster::blocks_fixed,
    Raster::pixels_float,   Raster::blocks_float, Raster::scanline_double};

Grid draw_one(int width, int height, const std::array<FixedPoint2, 3>& v, Raster r) {
    Grid g{width, height};
    ch02::draw(g, v, r);
    return g;
}

/// Counts, over the frame, pixels drawn 0 times where `expected` wants 1 and pixels
/// drawn more than once: the two ways a mesh can fail to be watertight.
struct MeshFaults {
    int gaps = 0;     ///< covered by none of the triangles
    int overlaps = 0; ///< covered by two or more
};

MeshFaults faults(const Grid& g, int x0, int y0, int x1, int y1) {
    MeshFaults f;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            f.gaps += g.at(x, y) == 0;
            f.overlaps += g.at(x, y) > 1;
        }
    }
    return f;
}

} // namespace

TEST_CASE("the absolute convention: 15 and 10 pixels for every rasterizer" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    // Vertices on pixel centres: the diagonal passes through centres, the top edge runs
    // along a row of centres, the right edge along a column.
    const auto upper = ch02::snap3({0.5, 0.5}, {5.5, 0.5}, {5.5, 5.5});
    const auto lower = ch02::snap3({0.5, 5.5}, {0.5, 0.5}, {5.5, 5.5});
    const std::string upper_mask = "#####...\n"
                                   ".####...\n"
                                   "..###...\n"
                                   "...##...\n"
                                   "....#...\n"
                                   "........\n";
    const std::string lower_mask = "........\n"
                                   "#.......\n"
                                   "##......\n"
                                   "###.....\n"
                                   "####....\n"
                                   "........\n";
    for (const Raster r : all_rasters) {
        INFO(ch02::name_of(r));
        CHECK(draw_one(8, 6, upper, r).mask() == upper_mask); // 15 pixels
        CHECK(draw_one(8, 6, lower, r).mask() == lower_mask); // 10 pixels
    }
}

TEST_CASE("a centre on a shared edge goes to exactly one triangle" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    // A 4 x 4 px square with corners on pixel centres, split along each diagonal in
    // turn: every tie case (top, left, bottom, right, the diagonal both ways) occurs.
    const Point2 a{1.5, 1.5}, b{5.5, 1.5}, c{5.5, 5.5}, d{1.5, 5.5};
    const std::array<std::array<std::array<Point2, 3>, 2>, 2> splits{
        {{{{a, b, c}, {a, c, d}}}, {{{a, b, d}, {b, c, d}}}}};
    const std::string square = "........\n"
                               ".####...\n"
                               ".####...\n"
                               ".####...\n"
                               ".####...\n"
                               "........\n"
                               "........\n";
    for (const auto& split : splits) {
        for (const Raster r : all_rasters) {
            INFO(ch02::name_of(r));
            Grid g{8, 7};
            for (const auto& t : split) {
                ch02::draw(g, ch02::snap3(t[0], t[1], t[2]), r);
            }
            CHECK(g.mask() == square); // the top and left sides in, bottom and right out
        }
    }
}

TEST_CASE("meshes are watertight: every pixel exactly once" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    constexpr int size = 72;
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> wobble(-3.0, 3.0);
    const auto none = [](int, int) { return Point2{0, 0}; };
    const auto jittered = [&](int, int) { return Point2{wobble(rng), wobble(rng)}; };
    struct Case {
        const char* name;
        std::vector<std::array<FixedPoint2, 3>> mesh;
    };
    std::vector<Case> cases;
    cases.push_back({"jittered grid", grid_mesh({2.3, 1.7}, 8, 8.0, jittered)});
    cases.push_back(
        {"all vertices on pixel centres", grid_mesh({2.5, 2.5}, 11, 6.0, none)});
    // 720 slivers around the pixel centre (36.5, 36.5), out to a 33 px circle snapped.
    const Point2 hub{36.5, 36.5};
    cases.push_back({"fan of 720 slivers", sliver_fan(hub, 33.0, 720)});
    for (const Case& c : cases) {
        for (const Raster r : ch02::fixed_rasters) {
            INFO(c.name << ", " << ch02::name_of(r));
            Grid g{size, size};
            Grid whole{size, size}; // the coverage of every triangle counted once
            for (const auto& t : c.mesh) {
                ch02::draw(g, t, r);
            }
            // Every pixel covered at all is covered exactly once, and the union is
            // not small: the mesh really covered its area.
            int covered = 0, multiple = 0;
            for (int v : g.count) {
                covered += v > 0;
                multiple += v > 1;
            }
            CHECK(multiple == 0);
            CHECK(g.outside == 0);
            CHECK(covered > 2000);
            if (std::string(c.name) != "fan of 720 slivers") {
                // The grid meshes cover a square: no gap inside it either.
                const auto& m = c.mesh;
                const FixedPoint2 lo = m.front()[0], hi = m.back()[1];
                const int x0 = static_cast<int>(std::ceil(to_pixels(lo).x - 0.5));
                const int x1 = static_cast<int>(std::ceil(to_pixels(hi).x - 0.5));
                const MeshFaults f = faults(g, x0, x0, x1, x1);
                CHECK(f.gaps == 0);
                CHECK(f.overlaps == 0);
            } else {
                // The fan covers the snapped 720-gon; every centre well inside it
                // (distance <= 32 px from the hub) must be covered.
                int inner_gaps = 0;
                for (int y = 0; y < size; ++y) {
                    for (int x = 0; x < size; ++x) {
                        const Point2 centre = pixel_centre(x, y) - hub;
                        inner_gaps += glm::length(centre) <= 32.0 && g.at(x, y) == 0;
                    }
                }
                CHECK(inner_gaps == 0);
            }
        }
    }
    // With every vertex on a pixel centre, float arithmetic is exact too.
    for (const Raster r : {Raster::pixels_float, Raster::blocks_float}) {
        INFO(ch02::name_of(r));
        Grid g{size, size};
        for (const auto& t : cases[1].mesh) {
            ch02::draw(g, t, r);
        }
        const MeshFaults f = faults(g, 2, 2, 68, 68);
        CHECK(f.gaps == 0);
        CHECK(f.overlaps == 0);
    }
}

TEST_CASE("pixel and 8x8 block traversals draw the same pixels") {
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < ch02::trials; ++trial) {
        // Sizes from slivers to triangles larger than the 70 x 50 frame.
        const double spread = trial % 3 == 0 ? 8.0 : trial % 3 == 1 ? 40.0 : 120.0;
        const auto v = trial % 4 == 3 ? ch02::random_tie_triangle(rng, -10, 100)
                                      : ch02::random_triangle(rng, -spread / 4, spread);
        INFO("trial " << trial);
        const Grid pixels = draw_one(70, 50, v, Raster::pixels_fixed);
        REQUIRE(draw_one(70, 50, v, Raster::blocks_fixed) == pixels); // the fast variant
        // The plain block traversal (every block through classify_block) as well.
        const EdgeSetup<FixedEdge> s = setup_edges(v);
        Grid plain{70, 50};
        auto hit = [&](int x, int y) { plain.hit(x, y); };
        if (!s.empty) {
            traverse_blocks(s, pixel_bounds(v, plain.viewport()), hit);
        }
        REQUIRE(plain == pixels);
    }
}

TEST_CASE("float traversals differ only within rounding distance of an edge") {
    // In float the two traversals step to a pixel along different paths (k additions
    // from the bounding box's corner, or from the block's corner), so their values
    // differ by rounding. Each addition or product rounds by at most 2^-24 of the
    // largest magnitude involved, M = (|dx| + |dy|) * 128 px for this frame; after at
    // most k = width + height steps the error is below (k + 4) * 2^-24 * M. A pixel on
    // which the two disagree must have some exact edge value within that of zero.
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<float> u(-10.0f, 110.0f);
    const Viewport viewport{70, 50};
    int differing_pixels = 0, differing_triangles = 0, drawn = 0;
    for (int trial = 0; trial < ch02::trials; ++trial) {
        const std::array<Point2f, 3> v{Point2f{u(rng), u(rng)}, Point2f{u(rng), u(rng)},
                                       Point2f{u(rng), u(rng)}};
        Grid a{70, 50}, b{70, 50};
        edge_rasterize_pixels(v, viewport, [&](int x, int y) { a.hit(x, y); });
        edge_rasterize_blocks(v, viewport, [&](int x, int y) { b.hit(x, y); });
        drawn += a.count != std::vector<int>(a.count.size());
        bool differs = false;
        for (int y = 0; y < viewport.height; ++y) {
            for (int x = 0; x < viewport.width; ++x) {
                if (a.at(x, y) == b.at(x, y)) {
                    continue;
                }
                differs = true;
                ++differing_pixels;
                double nearest = 1e300; // smallest |exact E| / tolerance over the edges
                for (int i = 0; i < 3; ++i) {
                    const Point2 p = pixel_centre(x, y), e0 = v[(i + 1) % 3],
                                 e1 = v[(i + 2) % 3];
                    const double dx = e1.x - e0.x, dy = e1.y - e0.y; // exact in double
                    const double exact = dx * (p.y - e0.y) - dy * (p.x - e0.x);
                    const double tolerance = (viewport.width + viewport.height + 4) *
                                             std::ldexp(1.0, -24) *
                                             (std::abs(dx) + std::abs(dy)) * 128.0;
                    nearest = std::min(nearest, std::abs(exact) / tolerance);
                }
                INFO("trial " << trial << ", pixel " << x << ", " << y);
                REQUIRE(nearest <= 1.0);
            }
        }
        differing_triangles += differs;
    }
    CHECK(drawn > ch02::trials / 2);
    // Rare, but not never: the chapter quotes these counts.
    MESSAGE("float pixel vs block traversal: " << differing_pixels << " pixels differ in "
                                               << differing_triangles << " of "
                                               << ch02::trials << " triangles");
    CHECK(differing_triangles < ch02::trials / 50);
}

TEST_CASE("edge functions agree with chapter 1's scanline on random triangles" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    std::mt19937_64 rng(8);
    int drawn = 0;
    for (int trial = 0; trial < ch02::trials; ++trial) {
        // Every other triangle has its vertices on the half-pixel grid: edges through
        // pixel centres, where only the fill rule decides.
        const auto v = trial % 2 ? ch02::random_triangle(rng, -10.0, 75.0)
                                 : ch02::random_tie_triangle(rng, -5, 70);
        const Grid scan = draw_one(64, 48, v, Raster::scanline_fixed);
        INFO("trial " << trial);
        REQUIRE(draw_one(64, 48, v, Raster::pixels_fixed) == scan);
        REQUIRE(draw_one(64, 48, v, Raster::blocks_fixed) == scan);
        drawn += scan.count != std::vector<int>(scan.count.size());
    }
    CHECK(drawn > ch02::trials / 2);
}

TEST_CASE("vertex order and winding change nothing; both windings are drawn") {
    std::mt19937_64 rng(9);
    for (int trial = 0; trial < ch02::trials / 4; ++trial) {
        const auto v = trial % 2 ? ch02::random_triangle(rng, -5.0, 45.0)
                                 : ch02::random_tie_triangle(rng, -3, 43);
        for (const Raster r : {Raster::pixels_fixed, Raster::blocks_fixed,
                               Raster::pixels_float, Raster::blocks_float}) {
            const Grid g = draw_one(40, 40, v, r);
            // The three rotations keep the winding; the three reflections reverse it.
            const std::array<std::array<FixedPoint2, 3>, 5> orders{{{v[1], v[2], v[0]},
                                                                    {v[2], v[0], v[1]},
                                                                    {v[0], v[2], v[1]},
                                                                    {v[2], v[1], v[0]},
                                                                    {v[1], v[0], v[2]}}};
            for (const auto& o : orders) {
                INFO(ch02::name_of(r) << ", trial " << trial);
                REQUIRE(draw_one(40, 40, o, r) == g);
            }
        }
    }
}

TEST_CASE("shifts below half a sub-pixel step change nothing; zero area draws nothing") {
    std::mt19937_64 rng(10);
    std::uniform_real_distribution<double> tiny(-0.49 / subpixel_scale,
                                                0.49 / subpixel_scale);
    for (int trial = 0; trial < ch02::trials / 4; ++trial) {
        // Vertices on the 1/256 grid, then moved by less than half a step each.
        const auto v = ch02::random_triangle(rng, -5.0, 45.0);
        std::array<FixedPoint2, 3> moved;
        for (int i = 0; i < 3; ++i) {
            moved[i] = snap_to_subpixel(to_pixels(v[i]) + Point2{tiny(rng), tiny(rng)});
        }
        REQUIRE(moved == v); // snapping undoes the shift ...
        for (const Raster r : ch02::fixed_rasters) {
            REQUIRE(draw_one(40, 40, moved, r) ==
                    draw_one(40, 40, v, r)); // ... so do the pixels
        }
    }
    // Collinear, coincident, and a sliver that snaps flat: nothing at all.
    const std::array<std::array<Point2, 3>, 3> flat{
        {{{{1, 1}, {30, 30}, {15.5, 15.5}}},
         {{{5, 5}, {5, 5}, {5, 5}}},
         {{{2, 10.5}, {35, 10.5001}, {20, 10.5}}}}};
    for (const auto& t : flat) {
        const auto v = ch02::snap3(t[0], t[1], t[2]);
        REQUIRE(edge_function(v[0], v[1], v[2]) == 0);
        for (const Raster r : ch02::fixed_rasters) {
            CHECK(draw_one(40, 40, v, r) == Grid{40, 40});
        }
    }
}

TEST_CASE(
    "in float a test of the four corner centres can reject a block with a pixel in it") {
    // Exercise 2.5's example. The edge v0 -> v1 is not top-left (it runs right and down,
    // the inside below it). At the centre (2513.5, 309.5), the bottom-left corner of the
    // 8 x 8 block whose top-left pixel is (2513, 302), its exact value is positive, so
    // the pixel is covered; `at` rounds it to 0 in float, which fails the edge, and so do
    // the block's three other corners: a test of the four corner centres would reject the
    // block. classify_block (@eq:edge-block) keeps it for the pixel test.
    const std::array<Point2f, 3> v{
        {{2237.98999f, 267.386047f}, {3158.59766f, 408.108429f}, {2238.0f, 1000.0f}}};
    const EdgeSetup<FloatEdge> s = setup_edges(v);
    const FloatEdge& e = s.edge[2];
    REQUIRE_FALSE(e.top_left);
    const auto exact_edge = [&](int x, int y) { // the edge value at a centre, exactly
        const auto r = [](float f) { return exact(f); };
        const Rational px = Rational(2 * x + 1, 2), py = Rational(2 * y + 1, 2);
        return (r(v[1].x) - r(v[0].x)) * (py - r(v[0].y)) -
               (r(v[1].y) - r(v[0].y)) * (px - r(v[0].x));
    };
    CHECK(exact_edge(2513, 309) > 0); // covered
    CHECK(e.at(2513, 309) == 0.0f);   // but rounded to 0
    int corners_passing = 0;
    for (const auto& [x, y] : {std::pair{2513, 302}, std::pair{2520, 302},
                               std::pair{2513, 309}, std::pair{2520, 309}}) {
        corners_passing += covers(e, e.at(x, y));
    }
    CHECK(corners_passing == 0); // four corners: "outside"
    CHECK(classify_block(s, PixelRect{2513, 302, 2521, 310}) != BlockClass::outside);
}

TEST_CASE("blocks are classified by their corners") {
    // The triangle (0, 0), (64, 0), (0, 64) px: the block of pixels [0, 8) x [0, 8) is
    // deep inside, [56, 64) x [56, 64) entirely below the hypotenuse, and
    // [24, 32) x [32, 40) crosses it.
    const auto s = setup_edges(ch02::snap3({0, 0}, {64, 0}, {0, 64}));
    CHECK(classify_block(s, PixelRect{0, 0, 8, 8}) == BlockClass::inside);
    CHECK(classify_block(s, PixelRect{56, 56, 64, 64}) == BlockClass::outside);
    CHECK(classify_block(s, PixelRect{24, 32, 32, 40}) == BlockClass::partial);
    // The block [32, 40) x [24, 32) touches the hypotenuse only at its top-left corner
    // pixel's centre? No: its top-left centre (32.5, 24.5) has x + y = 57 < 64, inside;
    // its bottom-right centre (39.5, 31.5) has x + y = 71 > 64: partial.
    CHECK(classify_block(s, PixelRect{32, 24, 40, 32}) == BlockClass::partial);
    // On a large triangle most pixels come from blocks filled without a test.
    const auto big = ch02::snap3({0.3, 0.2}, {300.7, 10.1}, {20.2, 290.9});
    const auto e = setup_edges(big);
    int inside = 0, outside = 0, partial = 0;
    for (int by = 0; by < 296; by += 8) {
        for (int bx = 0; bx < 304; bx += 8) {
            switch (classify_block(e, PixelRect{bx, by, bx + 8, by + 8})) {
            case BlockClass::inside:
                ++inside;
                break;
            case BlockClass::outside:
                ++outside;
                break;
            case BlockClass::partial:
                ++partial;
                break;
            }
        }
    }
    CHECK(inside > 500);
    CHECK(outside > 500);
    CHECK(partial < inside / 3);
}

TEST_CASE("classification is never wrong: a block called inside or outside is") {
    std::mt19937_64 rng(11);
    std::uniform_int_distribution<int> corner(0, 40), side(1, 8);
    for (int trial = 0; trial < ch02::trials; ++trial) {
        const auto v = ch02::random_triangle(rng, -5.0, 50.0);
        const auto s = setup_edges(v);
        const int x = corner(rng), y = corner(rng);
        const PixelRect b{x, y, x + side(rng), y + side(rng)};
        const BlockClass c = classify_block(s, b);
        if (c == BlockClass::partial) {
            continue;
        }
        for (int py = b.y_begin; py < b.y_end; ++py) {
            for (int px = b.x_begin; px < b.x_end; ++px) {
                bool in = true;
                for (const FixedEdge& e : s.edge) {
                    in = in && covers(e, e.at(px, py));
                }
                REQUIRE(in == (c == BlockClass::inside));
            }
        }
    }
}

TEST_CASE("triangles at the edge of the exact range rasterize exactly") {
    // The reference: edge functions in exact integers at every pixel centre of the
    // window, inside when all three have the sign of the area. The data has no centre
    // exactly on an edge (checked), so no fill rule is needed.
    const auto wide = [](FixedPoint2 a, FixedPoint2 b, FixedPoint2 p) {
        return Integer{b.x - a.x} * Integer{p.y - a.y} -
               Integer{b.y - a.y} * Integer{p.x - a.x};
    };
    const auto reference = [&](const std::array<FixedPoint2, 3>& v, PixelRect window) {
        Grid g{window.x_end - window.x_begin, window.y_end - window.y_begin};
        const bool positive = wide(v[0], v[1], v[2]) > 0;
        for (int y = window.y_begin; y < window.y_end; ++y) {
            for (int x = window.x_begin; x < window.x_end; ++x) {
                int inside = 0;
                for (int i = 0; i < 3; ++i) {
                    const Integer e =
                        wide(v[(i + 1) % 3], v[(i + 2) % 3], fixed_pixel_centre(x, y));
                    REQUIRE(e != 0); // no ties in the data
                    inside += (e > 0) == positive;
                }
                if (inside == 3) {
                    g.hit(x - window.x_begin, y - window.y_begin);
                }
            }
        }
        return g;
    };
    const std::int64_t m = max_fixed_coordinate;
    const int far = static_cast<int>(max_fixed_coordinate_px); // 2^20 px
    struct Case {
        std::array<FixedPoint2, 3> v;
        PixelRect window; // the viewport is [0, x_end) x [0, y_end); pixels outside the
                          // window cannot be covered (the triangles are chosen so)
    };
    const std::array<Case, 4> cases{{
        // Vertices at the corners of the range, edges crossing a 64 x 64 frame at the
        // origin: edge function values near 2^57.
        {{{{-m, -m}, {m, -m + 3 * 256 * 40 + 77}, {-m + 101, m}}}, {0, 0, 64, 64}},
        {{{{m, m}, {-m, 5 * 256 * 12 + 3}, {13 * 256 + 9, -m}}}, {0, 0, 64, 64}},
        // Small triangles at the far corner of the range: pixel indices near 2^20.
        {{{{m - 3, m - 1},
           {m - 60 * 256 - 5, m - 7 * 256 + 1},
           {m - 31 * 256 + 3, m - 59 * 256 - 9}}},
         {far - 64, far - 64, far, far}},
        {{{{-m + 7, m - 2},
           {-m + 50 * 256 + 1, m - 60 * 256 + 3},
           {-m + 3, m - 40 * 256 - 1}}},
         {0, far - 64, 1, far}},
    }};
    int covered = 0;
    for (const Case& c : cases) {
        const PixelRect& w = c.window;
        const Grid expected = reference(c.v, w);
        for (int n : expected.count) {
            covered += n;
        }
        for (const Raster r : ch02::fixed_rasters) {
            Grid got{w.x_end - w.x_begin, w.y_end - w.y_begin};
            const auto hit = [&](int x, int y) { got.hit(x - w.x_begin, y - w.y_begin); };
            const Viewport viewport{w.x_end, w.y_end};
            if (r == Raster::scanline_fixed) {
                scanline_spans(c.v, viewport, [&](Span s) {
                    for (int x = s.x_begin; x < s.x_end; ++x) {
                        hit(x, s.y);
                    }
                });
            } else if (r == Raster::pixels_fixed) {
                edge_rasterize_pixels(c.v, viewport, hit);
            } else {
                edge_rasterize_blocks(c.v, viewport, hit);
            }
            INFO(ch02::name_of(r));
            CHECK(got.outside == 0);
            CHECK(got == expected);
        }
    }
    CHECK(covered > 2000);
    // One unit beyond the range is refused, naming the vertex and the value.
    const std::array<FixedPoint2, 3> beyond{{{0, 0}, {m + 1, 0}, {0, 256}}};
    const auto nothing = [](int, int) {};
    CHECK_THROWS_WITH_AS(edge_rasterize_pixels(beyond, Viewport{8, 8}, nothing),
                         doctest::Contains("vertex 1: coordinate 1048576.00390625 px"),
                         Error);
    CHECK_THROWS_WITH_AS(edge_rasterize_blocks(beyond, Viewport{8, 8}, nothing),
                         doctest::Contains("1048576.00390625"), Error);
    const std::array<Point2f, 3> not_finite{{{0, 0}, {1, 0}, {0, std::nanf("")}}};
    CHECK_THROWS_WITH_AS(edge_rasterize_pixels(not_finite, Viewport{8, 8}, nothing),
                         doctest::Contains("vertex 2"), Error);
}

namespace {

// The edge's value, bias included, at the point (X, Y) in 1/256 px, from its definition
// (@eq:edge-function): exact in 64 bits for the small triangles here.
std::int64_t edge_value_at(const FixedEdge& e, std::int64_t X, std::int64_t Y) {
    return e.dx * (Y - e.a.y) - e.dy * (X - e.a.x) + e.bias;
}

// What a block's squares say, from the four corners of the rectangle they cover (a value
// linear in the point is largest and smallest at corners of a rectangle).
BlockClass area_class_by_corners(const EdgeSetup<FixedEdge>& s, PixelRect b) {
    bool inside = true;
    for (const FixedEdge& e : s.edge) {
        bool some_pass = false, all_pass = true;
        for (const int x : {b.x_begin, b.x_end}) {
            for (const int y : {b.y_begin, b.y_end}) {
                const bool pass = covers(
                    e, edge_value_at(e, std::int64_t{x} * 256, std::int64_t{y} * 256));
                some_pass = some_pass || pass;
                all_pass = all_pass && pass;
            }
        }
        if (!some_pass) {
            return BlockClass::outside;
        }
        inside = inside && all_pass;
    }
    return inside ? BlockClass::inside : BlockClass::partial;
}

} // namespace

TEST_CASE("a block's squares are classified by the corners of the area they cover" *
          doctest::description("points: 12; exercise: ch02-block-area")) {
    std::mt19937_64 rng(21);
    std::uniform_int_distribution<int> corner(-4, 40), side(1, 9);
    int decided = 0;
    for (int trial = 0; trial < ch02::trials; ++trial) {
        // Half of the triangles with vertices on whole pixels, where an edge can run
        // along a block's border.
        const auto v = trial % 2 == 0
                           ? ch02::random_triangle(rng, -5.0, 50.0)
                           : ch02::snap3({double(corner(rng)), double(corner(rng))},
                                         {double(corner(rng)), double(corner(rng))},
                                         {double(corner(rng)), double(corner(rng))});
        const auto s = setup_edges(v);
        if (s.empty) {
            continue;
        }
        const int x = corner(rng), y = corner(rng);
        const PixelRect b{x, y, x + side(rng), y + side(rng)};
        const BlockClass expected = area_class_by_corners(s, b);
        INFO("block [" << b.x_begin << ", " << b.x_end << ") x [" << b.y_begin << ", "
                       << b.y_end << ")");
        REQUIRE(classify_block_area(s, b) == expected);
        decided += expected != BlockClass::partial;
    }
    CHECK(decided > ch02::trials / 10);
    // The triangle (0, 0), (64, 0), (0, 64) px: the block [0, 8) x [0, 8) is inside it
    // by its centres, but its squares reach the top and left edges, where a point is in
    // only on a top or left edge (both are), and its top-left corner (0, 0) is a vertex.
    const auto t = setup_edges(ch02::snap3({0, 0}, {64, 0}, {0, 64}));
    CHECK(classify_block_area(t, PixelRect{0, 0, 8, 8}) ==
          area_class_by_corners(t, {0, 0, 8, 8}));
    CHECK(classify_block_area(t, PixelRect{8, 8, 16, 16}) == BlockClass::inside);
    // [28, 36) x [28, 36): its bottom-right centre (35.5, 35.5) is out, but its top-left
    // corner point (28, 28) is in.
    CHECK(classify_block_area(t, PixelRect{28, 28, 36, 36}) == BlockClass::partial);
    // [32, 40) x [32, 40): every centre is out and its top-left corner (32, 32) lies on
    // the hypotenuse, which is not a top or left edge: outside.
    CHECK(classify_block_area(t, PixelRect{32, 32, 40, 40}) == BlockClass::outside);
}

TEST_CASE("a block called outside by its squares has no point in the triangle" *
          doctest::description("points: 8; exercise: ch02-block-area")) {
    // Checked at every point of a 1/8 px grid over the block's squares, borders included:
    // outside means some edge fails there, inside that every edge passes.
    std::mt19937_64 rng(22);
    std::uniform_int_distribution<int> corner(0, 40), side(1, 6);
    int outside = 0, inside = 0;
    for (int trial = 0; trial < ch02::trials / 4; ++trial) {
        const auto v = ch02::random_triangle(rng, -5.0, 50.0);
        const auto s = setup_edges(v);
        if (s.empty) {
            continue;
        }
        const int x = corner(rng), y = corner(rng);
        const PixelRect b{x, y, x + side(rng), y + side(rng)};
        const BlockClass c = classify_block_area(s, b);
        if (c == BlockClass::partial) {
            continue;
        }
        (c == BlockClass::outside ? outside : inside) += 1;
        for (std::int64_t Y = b.y_begin * 256; Y <= b.y_end * 256; Y += 32) {
            for (std::int64_t X = b.x_begin * 256; X <= b.x_end * 256; X += 32) {
                bool in = true;
                for (const FixedEdge& e : s.edge) {
                    in = in && covers(e, edge_value_at(e, X, Y));
                }
                INFO("point (" << X / 256.0 << ", " << Y / 256.0 << ")");
                REQUIRE(in == (c == BlockClass::inside));
            }
        }
    }
    CHECK(outside > 0);
    CHECK(inside > 0);
}
