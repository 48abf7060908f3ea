// Chapter 6, hard cases of coverage: slivers, the 720-sliver fan, coordinates at and past
// the fixed-point limits, zero area after snapping, vertex order and winding, and input
// that is not a number. Each test states its tolerance; "exact" means pixel for pixel
// against an independent brute-force test in exact integers.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/measured_facts.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {

/// Twice the signed area of a, b, p in exact integers (units of 1/65536 px^2).
Integer orient(FixedPoint2 a, FixedPoint2 b, FixedPoint2 p) {
    return Integer{b.x - a.x} * Integer{p.y - a.y} -
           Integer{b.y - a.y} * Integer{p.x - a.x};
}

/// The top-left rule for pixel (x, y) straight from its definition: the centre is
/// strictly inside every edge, or on an edge that is a top edge or a left edge. An
/// independent reference for every rasterizer (no stepping, no bias trick).
bool exactly_covered(std::array<FixedPoint2, 3> v, int x, int y) {
    const Integer area = orient(v[0], v[1], v[2]);
    if (area == 0) {
        return false;
    }
    if (area < 0) {
        std::swap(v[1], v[2]); // now the inside is where orient(a, b, p) > 0 (y down)
    }
    const FixedPoint2 p{std::int64_t{x} * 256 + 128, std::int64_t{y} * 256 + 128};
    for (int i = 0; i < 3; ++i) {
        const FixedPoint2 a = v[static_cast<std::size_t>((i + 1) % 3)];
        const FixedPoint2 b = v[static_cast<std::size_t>((i + 2) % 3)];
        const Integer e = orient(a, b, p);
        // A centre on the edge (e == 0) counts when the point moved by (t, t^2), t > 0
        // as small as need be, is inside: then the sign of e's step along x (-dy)
        // decides, and on a horizontal edge that of its step along y (dx).
        const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
        const bool inside = e != 0 ? e > 0 : (dy != 0 ? -dy > 0 : dx > 0);
        if (!inside) {
            return false;
        }
    }
    return true;
}

std::vector<int> coverage(const std::array<Point2, 3>& v, Viewport vp,
                          RasterizerKind kind, CoveragePrecision precision) {
    std::vector<int> counts(static_cast<std::size_t>(vp.width * vp.height), 0);
    add_coverage(counts, vp, v, kind, precision);
    return counts;
}

constexpr RasterizerKind all_kinds[] = {RasterizerKind::scanline, RasterizerKind::edge,
                                        RasterizerKind::edge8x8};

/// Pixels the brute-force reference covers.
int reference_count(const std::array<Point2, 3>& v, Viewport vp) {
    const std::array<FixedPoint2, 3> f{snap_in_range(v[0]), snap_in_range(v[1]),
                                       snap_in_range(v[2])};
    int n = 0;
    for (int y = 0; y < vp.height; ++y) {
        for (int x = 0; x < vp.width; ++x) {
            n += exactly_covered(f, x, y);
        }
    }
    return n;
}

/// Pixels where a fixed-point rasterizer disagrees with the brute-force reference.
int mismatches_with_reference(const std::array<Point2, 3>& v, Viewport vp,
                              RasterizerKind kind) {
    const std::array<FixedPoint2, 3> f{snap_in_range(v[0]), snap_in_range(v[1]),
                                       snap_in_range(v[2])};
    const std::vector<int> c = coverage(v, vp, kind, CoveragePrecision::fixed);
    int wrong = 0;
    for (int y = 0; y < vp.height; ++y) {
        for (int x = 0; x < vp.width; ++x) {
            wrong += c[static_cast<std::size_t>(y * vp.width + x)] !=
                     int{exactly_covered(f, x, y)};
        }
    }
    return wrong;
}

} // namespace

TEST_CASE("a sliver thinner than a pixel across the frame is covered exactly") {
    // A wedge 1/16 to 1/2 px wide at its end over 600 px of length: most rows hold no
    // centre at all, a few hold one. Exact in fixed point, against the brute-force test.
    const Viewport vp{640, 200};
    int sliver_mismatches = 0;
    for (const double width : {1.0 / 16, 1.0 / 4, 1.0 / 2}) {
        const std::array<Point2, 3> sliver{
            {{10.25, 3.5}, {610.75, 190.25}, {610.75 + width, 190.25}}};
        MESSAGE("sliver " << width << " px wide: " << reference_count(sliver, vp)
                          << " pixels covered");
        CHECK(reference_count(sliver, vp) > 0); // the test is not vacuous
        record_fact("ch06_sliver_pixels_" + std::to_string(int(1 / width)),
                    reference_count(sliver, vp));
        int mismatches = 0;
        for (const RasterizerKind kind : all_kinds) {
            INFO("width " << width << ", rasterizer " << int(kind));
            CHECK(mismatches_with_reference(sliver, vp, kind) == 0);
            mismatches += mismatches_with_reference(sliver, vp, kind);
        }
        sliver_mismatches += mismatches;
    }
    record_fact("ch06_sliver_mismatches", sliver_mismatches);
}

TEST_CASE("the 720-sliver fan covers every pixel of its disc exactly once") {
    // 720 triangles of half a degree share the centre and their spokes. Tolerance: in
    // fixed point every pixel is drawn 0 or 1 times, every centre more than 1 px
    // inside the 720-gon is drawn, none more than 1 px outside it.
    const Viewport vp{256, 256};
    const Point2 centre{128.3, 127.6};
    const double radius = 120.0;
    const auto rim = [&](int k) {
        const double a = k * std::numbers::pi / 360.0;
        return centre + radius * Point2{std::cos(a), std::sin(a)};
    };
    int fan_twice = 0, fan_gaps = 0, fan_outside = 0; // over all three rasterizers
    for (const RasterizerKind kind : all_kinds) {
        std::vector<int> counts(static_cast<std::size_t>(vp.width * vp.height), 0);
        for (int k = 0; k < 720; ++k) {
            add_coverage(counts, vp, {centre, rim(k), rim(k + 1)}, kind,
                         CoveragePrecision::fixed);
        }
        int twice = 0, gaps = 0, outside = 0;
        const double inner = radius * std::cos(std::numbers::pi / 720.0) - 1.0;
        for (int y = 0; y < vp.height; ++y) {
            for (int x = 0; x < vp.width; ++x) {
                const int c = counts[static_cast<std::size_t>(y * vp.width + x)];
                const double r = glm::length(pixel_centre(x, y) - centre);
                twice += c > 1;
                gaps += r < inner && c == 0;
                outside += r > radius + 1.0 && c != 0;
            }
        }
        INFO("rasterizer " << int(kind));
        CHECK(twice == 0);
        CHECK(gaps == 0);
        CHECK(outside == 0);
        fan_twice += twice;
        fan_gaps += gaps;
        fan_outside += outside;
    }
    record_fact("ch06_fan_twice", fan_twice);
    record_fact("ch06_fan_gaps", fan_gaps);
    record_fact("ch06_fan_outside", fan_outside);
}

TEST_CASE("at the fixed-point limit coverage is exact; past it, an Error and no pixel") {
    const double m = max_fixed_coordinate_px; // 2^20 px
    const Viewport vp{64, 64};
    // Huge triangles whose edges cross the viewport at steep and shallow slopes.
    const std::array<Point2, 3> huge[] = {
        {{{-m, -m}, {m, m}, {-m, m}}},                    // the diagonal y = x
        {{{-m, -m / 2 + 32}, {m, m / 2 + 32}, {m, -m}}},  // slope 1/2 through (0, 32)
        {{{20.5, -m}, {40.5 + 1.0 / 256, m}, {-m, 0.0}}}, // almost vertical
    };
    for (const auto& t : huge) {
        CHECK(reference_count(t, vp) > 0);       // the edges cross the viewport:
        CHECK(reference_count(t, vp) < 64 * 64); // some pixels in, some out
        for (const RasterizerKind kind : all_kinds) {
            CHECK(mismatches_with_reference(t, vp, kind) == 0);
        }
    }
    // One sub-pixel step (1/256 px) beyond the limit: refused, nothing counted.
    const std::array<Point2, 3> past{{{-m, -m}, {m + 1.0 / 256, 0.0}, {-m, m}}};
    for (const RasterizerKind kind : all_kinds) {
        std::vector<int> counts(64 * 64, 0);
        CHECK_THROWS_WITH_AS(
            add_coverage(counts, vp, past, kind, CoveragePrecision::fixed),
            doctest::Contains("1048576.00390625"), Error);
        CHECK(std::count(counts.begin(), counts.end(), 0) == 64 * 64);
    }
    Framebuffer frame(64, 64, rgba(1, 2, 3));
    const Framebuffer before = frame;
    const std::array<TexturedVertex, 3> textured{{{past[0], 1.0, {0.0, 0.0}},
                                                  {past[1], 1.0, {1.0, 0.0}},
                                                  {past[2], 1.0, {0.0, 1.0}}}};
    CHECK_THROWS_AS(draw_textured_triangle(frame, textured, f_texture(1), {}), Error);
    CHECK(frame == before);
}

TEST_CASE("NaN and infinite vertex input is rejected with an Error and draws nothing") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const Viewport vp{32, 32};
    for (const double bad : {nan, inf, -inf}) {
        // Every message names the value: "nan", "inf" or "-inf".
        const auto names_it = doctest::Contains(std::isnan(bad) ? "nan" : "inf");
        for (int corner = 0; corner < 3; ++corner) {
            for (int axis = 0; axis < 2; ++axis) {
                std::array<Point2, 3> v{{{1.5, 1.5}, {30.5, 4.5}, {8.5, 29.5}}};
                v[static_cast<std::size_t>(corner)][axis] = bad;
                for (const RasterizerKind kind : all_kinds) {
                    for (const auto precision :
                         {CoveragePrecision::fixed, CoveragePrecision::floating}) {
                        std::vector<int> counts(32 * 32, 0);
                        CHECK_THROWS_WITH_AS(add_coverage(counts, vp, v, kind, precision),
                                             names_it, Error);
                        CHECK(std::count(counts.begin(), counts.end(), 0) == 32 * 32);
                    }
                }
                // Textured: a bad position, then a bad depth, then a bad uv.
                std::array<TexturedVertex, 3> t{{{v[0], 1.0, {0.0, 0.0}},
                                                 {v[1], 2.0, {9.0, 0.0}},
                                                 {v[2], 3.0, {0.0, 9.0}}}};
                Framebuffer frame(32, 32, rgba(9, 9, 9));
                const Framebuffer before = frame;
                const auto texture = f_texture(1);
                CHECK_THROWS_WITH_AS(draw_textured_triangle(frame, t, texture, {}),
                                     names_it, Error);
                t = {{{{1.5, 1.5}, 1.0, {0.0, 0.0}},
                      {{30.5, 4.5}, 2.0, {9.0, 0.0}},
                      {{8.5, 29.5}, 3.0, {0.0, 9.0}}}};
                t[static_cast<std::size_t>(corner)].w = bad;
                CHECK_THROWS_WITH_AS(draw_textured_triangle(frame, t, texture, {}),
                                     names_it, Error);
                t[static_cast<std::size_t>(corner)].w = 1.0;
                t[static_cast<std::size_t>(corner)].uv[axis] = bad;
                CHECK_THROWS_WITH_AS(draw_textured_triangle(frame, t, texture, {}),
                                     names_it, Error);
                CHECK(frame == before);
            }
        }
    }
}

TEST_CASE("one function checks the exact range, with one message, for every rasterizer") {
    // One sub-pixel step beyond 2^20 px. The five entries that check chapter 2's range
    // worded it five ways (in 1/256 px, "not finite or beyond +-2^20 px", "the float
    // rasterizers' range"...); each now calls check_pixel_range and adds only where.
    const std::string message =
        "coordinate 1048576.00390625 px is outside the exact range [-1048576, 1048576]";
    const auto message_of = [](const auto& call) -> std::string {
        try {
            call();
        } catch (const Error& error) {
            return error.what();
        }
        return "no Error";
    };
    const Point2 past{max_fixed_coordinate_px + 1.0 / 256, 0.0};
    const FixedPoint2 fixed_past{max_fixed_coordinate + 1, 0};
    CHECK(message_of([&] { (void)snap_in_range(past); }) == message);
    CHECK(message_of([&] { check_fixed_range(fixed_past); }) == message);
    const std::array<FixedPoint2, 3> fixed{{{0, 0}, fixed_past, {0, 256}}};
    CHECK(message_of([&] {
              scanline_spans(fixed, Viewport{4, 4}, [](Span) {});
          }) == "scanline_spans: vertex 1: " + message);
    const std::array<Point2, 3> corners{{{0.0, 0.0}, past, {0.0, 1.0}}};
    CHECK(message_of([&] { check_float_triangle(corners); }) == "vertex 1: " + message);
    Framebuffer frame(4, 4);
    const std::array<TexturedVertex, 3> textured{{{corners[0], 1.0, {0.0, 0.0}},
                                                  {corners[1], 1.0, {1.0, 0.0}},
                                                  {corners[2], 1.0, {0.0, 1.0}}}};
    CHECK(message_of([&] {
              draw_textured_triangle(frame, textured, f_texture(1), {});
          }) == "textured triangle: vertex 1: " + message);
}

TEST_CASE("a triangle that snaps to zero area draws nothing and makes no NaN") {
    // Before snapping the area is tiny but not zero; after snapping to 1/256 px the
    // three vertices are collinear: (10, 10), (50, 50), (30, 30).
    const std::array<Point2, 3> v{{{10.001, 10.001}, {50.0, 50.0}, {30.0015, 30.0}}};
    const std::array<FixedPoint2, 3> f{snap_in_range(v[0]), snap_in_range(v[1]),
                                       snap_in_range(v[2])};
    REQUIRE(orient(f[0], f[1], f[2]) == 0);
    const Viewport vp{64, 64};
    for (const RasterizerKind kind : all_kinds) {
        const std::vector<int> c = coverage(v, vp, kind, CoveragePrecision::fixed);
        CHECK(std::count(c.begin(), c.end(), 0) == 64 * 64);
    }
    TexelMap map(64, 64);
    for (const MapperKind kind : {MapperKind::exact, MapperKind::affine,
                                  MapperKind::quadratic, MapperKind::subdivided}) {
        map_textured_triangle(map,
                              {{{v[0], 1.0, {0.0, 0.0}},
                                {v[1], 5.0, {64.0, 0.0}},
                                {v[2], 2.0, {0.0, 64.0}}}},
                              {{kind, 16}, Precision::fixed, {}, Wrap::repeat});
    }
    CHECK(std::count(map.covered.begin(), map.covered.end(), true) == 0);
}

TEST_CASE("rotating the vertex order or reversing the winding changes no pixel") {
    // Coverage: exact, identical for all six orders. Texels: the planes are set up from
    // a different first vertex, so u and v may differ by rounding; tolerance 1e-9
    // texels, and the texel indices must agree everywhere on these inputs.
    std::uint64_t state = 99;
    const auto uniform = [&](double lo, double hi) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return lo + (hi - lo) * double(state >> 11) * 0x1p-53;
    };
    const Viewport vp{96, 96};
    const int orders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1},
                              {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    int index_mismatches = 0;
    double worst_uv = 0.0;
    for (int trial = 0; trial < 40; ++trial) {
        std::array<TexturedVertex, 3> t{};
        for (TexturedVertex& p : t) {
            p = {{uniform(-10, 106), uniform(-10, 106)},
                 uniform(1, 9),
                 {uniform(0, 64), uniform(0, 64)}};
        }
        for (const MapperKind kind : {MapperKind::exact, MapperKind::affine,
                                      MapperKind::quadratic, MapperKind::subdivided}) {
            const MapperSettings s{{kind, 8}, Precision::float64, {}, Wrap::repeat};
            TexelMap first(vp.width, vp.height);
            map_textured_triangle(first, t, s);
            for (const auto& o : orders) {
                TexelMap other(vp.width, vp.height);
                map_textured_triangle(other, {t[o[0]], t[o[1]], t[o[2]]}, s);
                REQUIRE(other.covered == first.covered);
                for (std::size_t k = 0; k < first.covered.size(); ++k) {
                    if (first.covered[k]) {
                        index_mismatches +=
                            other.i[k] != first.i[k] || other.j[k] != first.j[k];
                        worst_uv = std::max({worst_uv, std::abs(other.u[k] - first.u[k]),
                                             std::abs(other.v[k] - first.v[k])});
                    }
                }
            }
        }
    }
    MESSAGE("largest u/v change over all orders: " << worst_uv << " texels");
    record_fact("ch06_order_uv_change", worst_uv);
    CHECK(worst_uv <= 1e-9);
    CHECK(index_mismatches == 0);
}
