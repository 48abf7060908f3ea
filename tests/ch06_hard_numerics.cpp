// Chapter 6, hard cases of arithmetic: near-zero y-deltas in the gradient setup, tiny
// triangles far from the origin, triangles nearly edge-on to the camera, and long spans
// stepped in float. Each test states its tolerance and where it comes from.
#include "exactpixels/base/exact.hpp"
#include "exactpixels/base/fixed_point.hpp"
#include "exactpixels/raster/gradient_stability.hpp"
#include "exactpixels/raster/gradients.hpp"
#include "exactpixels/texture/quadratic.hpp"
#include "exactpixels/texture/span_mappers.hpp"
#include "exactpixels/texture/texture_mapper.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {
#ifdef NDEBUG
constexpr int trials = 1000; // Release
#else
constexpr int trials = 200; // Debug and sanitizer builds: the same checks, fewer cases
#endif
} // namespace

TEST_CASE("near-zero y-deltas: both gradient setups stay finite and close to exact") {
    // Chapter 1's study, fewer triangles: y-deltas from 1e-2 px down to 1e-12 px and 0.
    // The reference is the exact gradient (exact rationals). Tolerance, in machine
    // epsilons of the precision, on the largest error over all triangles: 2^8 for the
    // closed form, and the same for the split edge; never NaN or infinite.
    const std::vector<StabilityRow> rows = gradient_stability_study(trials, 5);
    std::map<std::string, double> worst; // the chapter quotes each method's worst
    for (const StabilityRow& r : rows) {
        worst["closed_" + r.precision] =
            std::max(worst["closed_" + r.precision], r.closed_max);
        worst["split_" + r.precision] =
            std::max(worst["split_" + r.precision], r.split_max);
        INFO("y-delta " << r.y_delta << ", " << r.precision);
        MESSAGE("y-delta " << r.y_delta << " " << r.precision << ": closed max "
                           << r.closed_max << " eps, split max " << r.split_max
                           << " eps");
        CHECK(std::isfinite(r.closed_max));
        CHECK(std::isfinite(r.split_max));
        CHECK(r.closed_max <= 256.0);
        CHECK(r.split_max <= 256.0);
    }
    record_fact("ch06_ydelta_trials", trials);
    for (const auto& [name, value] : worst) {
        record_fact("ch06_ydelta_" + name, value);
    }
}

TEST_CASE("near-zero y-delta triangles keep twice their area far from zero") {
    // The closed form divides by twice the area 2A, which depends on all three vertices:
    // two of them on almost one row leave 2A about (their x distance) x (the third's
    // height). For the study's triangles, in float and double grids, |2A| stays at least
    // 1 px^2 whatever the y-delta, and its smallest value does not fall as the delta
    // does.
    double smallest_at_largest_delta = 0.0;
    for (const double delta : stability_y_deltas()) {
        double smallest = std::numeric_limits<double>::infinity();
        for (const bool as_float : {false, true}) {
            for (const PlaneSamples<double>& s :
                 stability_triangles(delta, trials, 5, as_float)) {
                const double area2 = (s.x[1] - s.x[0]) * (s.y[2] - s.y[0]) -
                                     (s.x[2] - s.x[0]) * (s.y[1] - s.y[0]);
                smallest = std::min(smallest, std::abs(area2));
            }
        }
        MESSAGE("y-delta " << delta << ": smallest |twice the area| " << smallest
                           << " px^2");
        CHECK(smallest >= 1.0);
        if (smallest_at_largest_delta == 0.0) {
            smallest_at_largest_delta = smallest; // the first delta is the largest
        }
        CHECK(smallest >= smallest_at_largest_delta / 2);
    }
}

namespace {
/// The plane through three vertices and their values c, exactly: the reference for the
/// far-from-origin and edge-on cases. Its gradient is @eq:closed-form written out
/// again (not the library's template) in exact rationals, so nothing rounds.
class ExactPlane {
  public:
    /// The plane through (v[i], c[i]); the vertices must not be collinear.
    ExactPlane(const std::array<Point2, 3>& v, const std::array<double, 3>& c)
        : x0_(exact(v[0].x)), y0_(exact(v[0].y)), c0_(exact(c[0])) {
        const Rational x1 = exact(v[1].x) - x0_, y1 = exact(v[1].y) - y0_;
        const Rational x2 = exact(v[2].x) - x0_, y2 = exact(v[2].y) - y0_;
        const Rational c1 = exact(c[1]) - c0_, c2 = exact(c[2]) - c0_;
        const Rational area = x2 * y1 - x1 * y2;
        REQUIRE(area != 0);
        gx_ = (c2 * y1 - c1 * y2) / area;
        gy_ = (c1 * x2 - c2 * x1) / area;
    }
    /// c at screen point p, exactly.
    Rational at(Point2 p) const {
        return c0_ + gx_ * (exact(p.x) - x0_) + gy_ * (exact(p.y) - y0_);
    }

  private:
    Rational x0_, y0_, c0_, gx_, gy_;
};

/// |computed - truth|, the difference exact and rounded once.
double error(double computed, const Rational& truth) {
    return to_double(abs(exact(computed) - truth));
}
} // namespace

TEST_CASE("a tiny far triangle: float loses it, relative coordinates keep it") {
    // A 2-px triangle a million pixels from the origin, c from 0 to 1 across it. Near
    // 2^20 float spacing is 1/16 px, so rounding the corners to float moves them by up
    // to 1/32 px: a few percent of the triangle. Tolerances (on c in [0, 1]): double,
    // absolute coordinates: 1e-9; float after subtracting vertex 0 in double: 1e-5;
    // fixed point: exact corners (1/256 px), then double: 1e-9 against the plane through
    // the snapped corners. Float with absolute coordinates must fail by more than 1e-3.
    const Point2 base{1.0e6, 1.0e6};
    const std::array<Point2, 3> v{base + Point2{0.3, 0.7}, base + Point2{2.1, 0.9},
                                  base + Point2{0.8, 2.6}};
    const std::array<double, 3> c{0.0, 1.0, 0.5};
    const std::array<Point2, 3> snapped{to_pixels(snap_in_range(v[0])),
                                        to_pixels(snap_in_range(v[1])),
                                        to_pixels(snap_in_range(v[2]))};
    const std::array<glm::vec2, 3> vf{glm::vec2(v[0]), glm::vec2(v[1]), glm::vec2(v[2])};
    const std::array<glm::vec2, 3> rf{glm::vec2(v[0] - v[0]), glm::vec2(v[1] - v[0]),
                                      glm::vec2(v[2] - v[0])};
    const std::array<float, 3> cf{0.0f, 1.0f, 0.5f};
    const Gradient<double> gd = closed_form_gradient<double>(v, c);
    const Gradient<double> gs = closed_form_gradient<double>(snapped, c);
    const Gradient<float> gf = closed_form_gradient<float>(vf, cf);
    const Gradient<float> gr = closed_form_gradient<float>(rf, cf);
    const ExactPlane plane(v, c), plane_snapped(snapped, c);
    double e_float = 0, e_relative = 0, e_double = 0, e_fixed = 0;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            const Point2 p = base + Point2{i + 0.5, j + 0.5};
            const Rational truth = plane.at(p), truth_snapped = plane_snapped.at(p);
            const glm::vec2 pf(p);        // exact: half-integers near 1e6
            const glm::vec2 pr(p - v[0]); // the safeguard: relative first
            const float c_float = gf.dx * (pf.x - vf[0].x) + gf.dy * (pf.y - vf[0].y);
            const float c_rel = gr.dx * pr.x + gr.dy * pr.y;
            const double c_double = gd.dx * (p.x - v[0].x) + gd.dy * (p.y - v[0].y);
            const double c_fixed =
                gs.dx * (p.x - snapped[0].x) + gs.dy * (p.y - snapped[0].y);
            e_float = std::max(e_float, error(c_float, truth));
            e_relative = std::max(e_relative, error(c_rel, truth));
            e_double = std::max(e_double, error(c_double, truth));
            e_fixed = std::max(e_fixed, error(c_fixed, truth_snapped));
        }
    }
    MESSAGE("far tiny triangle, largest error in c: float "
            << e_float << ", float relative " << e_relative << ", double " << e_double
            << ", fixed " << e_fixed);
    record_fact("ch06_far_float", e_float);
    record_fact("ch06_far_float_relative", e_relative);
    record_fact("ch06_far_double", e_double);
    record_fact("ch06_far_fixed", e_fixed);
    CHECK(e_float > 1e-3); // the failure the safeguard exists for
    CHECK(e_relative <= 1e-5);
    CHECK(e_double <= 1e-9);
    CHECK(e_fixed <= 1e-9);
}

TEST_CASE("edge-on: 1/w falls by thousands along a row; double and 16.16 hold") {
    // A quad whose left edge is at depth 1 and whose right edge is 10^4 times deeper:
    // along each row 1/w falls from 1 to nearly 1e-4, and at the far end the divide
    // (u/w) / (1/w) magnifies the rounding of both. The reference evaluates the same
    // planes (through the snapped corners) exactly. Tolerances: double 1e-6
    // texels; 16.16: half a unit (2^-17 texels) plus 1e-6; float: u/w and 1/w are each
    // rounded to about eps of their largest value along the row, so at the far pixel u
    // is off by up to 2 eps R relatively, R the ratio of 1/w across the row (eq.
    // edge-on-error), at most 2 eps R |u|max texels: the allowance is that times 4,
    // 8 * 2^-24 * R * |u|max. R reaches the thousands: the right edge's pixel centres
    // come within a fraction of a pixel of the edge, where 1/w is near 1e-4.
    const TexturedVertex a{{10.3, 20.6}, 1.0, {0.0, 0.0}},
        b{{300.7, 22.1}, 1.0e4, {4096.0, 0.0}}, c{{300.2, 60.9}, 1.0e4, {4096.0, 64.0}},
        d{{12.2, 60.4}, 1.0, {0.0, 64.0}};
    const std::array<TexturedVertex, 3> quad[2] = {{a, b, c}, {a, c, d}};
    double worst[3] = {0, 0, 0};
    double ratio = 1.0; // the largest ratio of 1/w along a row, at pixel centres
    int pixels = 0;
    int float_wrong_texels = 0; // float's texel is not the one under the exact (u, v)
    Rational wrong_q = 1;       // the largest 1/w there (1/w is 1 at the near edge)
    const Precision precisions[3] = {Precision::float64, Precision::fixed,
                                     Precision::float32};
    for (const auto& t : quad) {
        std::array<Point2, 3> p{};
        for (std::size_t k = 0; k < 3; ++k) {
            p[k] = to_pixels(snap_in_range(t[k].position));
        }
        const auto plane = [&](auto f) {
            return ExactPlane(p, {f(t[0]), f(t[1]), f(t[2])});
        };
        const ExactPlane q_plane = plane([](const TexturedVertex& v) { return 1 / v.w; });
        const ExactPlane u_plane =
            plane([](const TexturedVertex& v) { return v.uv.x / v.w; });
        const ExactPlane v_plane =
            plane([](const TexturedVertex& v) { return v.uv.y / v.w; });
        // The exact 1/w, u and v at each pixel centre, made once for all three
        // precisions.
        struct Truth {
            Rational q, u, v;
        };
        std::vector<std::optional<Truth>> truths(320 * 64);
        for (int k = 0; k < 3; ++k) {
            TexelMap map(320, 64);
            map_textured_triangle(
                map, t, {{MapperKind::exact, 16}, precisions[k], {}, Wrap::repeat});
            for (int y = 0; y < 64; ++y) {
                std::optional<Rational> q_lo, q_hi;
                for (int x = 0; x < 320; ++x) {
                    const std::size_t at = std::size_t(y) * 320 + std::size_t(x);
                    if (!map.covered[at]) {
                        continue;
                    }
                    pixels += k == 0;
                    REQUIRE(std::isfinite(map.u[at]));
                    if (!truths[at]) {
                        const Point2 s = pixel_centre(x, y);
                        const Rational q = q_plane.at(s);
                        truths[at] = Truth{q, u_plane.at(s) / q, v_plane.at(s) / q};
                    }
                    const auto& [q, u, v] = *truths[at];
                    q_lo = q_lo ? std::min(*q_lo, q) : q;
                    q_hi = q_hi ? std::max(*q_hi, q) : q;
                    worst[k] =
                        std::max({worst[k], error(map.u[at], u), error(map.v[at], v)});
                    if (k == 2 &&
                        (map.i[at] != floor_of(u) || map.j[at] != floor_of(v))) {
                        ++float_wrong_texels;
                        wrong_q = float_wrong_texels == 1 ? q : std::max(wrong_q, q);
                    }
                }
                if (q_hi) {
                    ratio = std::max(ratio, to_double(*q_hi / *q_lo));
                }
            }
        }
    }
    MESSAGE("edge-on, " << pixels << " pixels, 1/w ratio along a row up to " << ratio
                        << ", worst texel error: double " << worst[0] << ", 16.16 "
                        << worst[1] << ", float " << worst[2]
                        << "; float picks another texel at " << float_wrong_texels
                        << " pixels, 1/w at most " << to_double(wrong_q));
    record_fact("ch06_edge_on_pixels", pixels);
    record_fact("ch06_edge_on_ratio", ratio);
    record_fact("ch06_edge_on_double", worst[0]);
    record_fact("ch06_edge_on_fixed", worst[1]);
    record_fact("ch06_edge_on_float", worst[2]);
    record_fact("ch06_edge_on_float_wrong_texels", float_wrong_texels);
    record_fact("ch06_edge_on_float_wrong_q", to_double(wrong_q));
    CHECK(pixels > 5000);
    CHECK(ratio > 1000.0); // "by thousands": 1/w falls by more than a factor 1000
    CHECK(worst[0] <= 1e-6);
    CHECK(worst[1] <= 0x1p-17 + 1e-6);
    CHECK(worst[2] <= 8 * 0x1p-24 * ratio * 4096.0);
    // Where float takes another texel, it is at the far end: 1/w below a hundredth.
    CHECK((float_wrong_texels == 0 || wrong_q < Rational(1, 100)));
}

TEST_CASE("long spans in float: stepping drifts, re-evaluating the plane does not") {
    // 4096 pixels, u from 0.3 growing by about one texel per pixel. Stepping adds a
    // rounding of at most half a float spacing of |u| per pixel, so after n pixels the
    // drift is at most n * 2^-24 * |u|max; evaluating u0 + k du afresh rounds twice:
    // at most 2^-23 * |u|max. The reference is the same float u0 and du in double.
    const int n = 4096;
    const float u0 = 0.3f, du = 1.0001f;
    float stepped = u0;
    double drift = 0.0, fresh = 0.0;
    const double u_max = double(u0) + n * double(du);
    for (int k = 0; k < n; ++k) {
        const double truth = double(u0) + k * double(du);
        const float evaluated = u0 + float(k) * du;
        drift = std::max(drift, std::abs(double(stepped) - truth));
        fresh = std::max(fresh, std::abs(double(evaluated) - truth));
        stepped += du;
    }
    // The library's float affine mapper steps the same way: same drift, bit for bit.
    double mapper_drift = 0.0;
    map_span_affine(AffineSpan<float>{u0, 0.0f, du, 0.0f, n}, [&](int k, float u, float) {
        mapper_drift =
            std::max(mapper_drift, std::abs(double(u) - (double(u0) + k * double(du))));
    });
    // The fresh variant beside it computes u0 + k du with the same two roundings.
    int fresh_differs = 0;
    map_span_affine_fresh(
        AffineSpan<float>{u0, 0.0f, du, 0.0f, n},
        [&](int k, float u, float) { fresh_differs += u != u0 + float(k) * du; });
    CHECK(fresh_differs == 0);
    MESSAGE("float over " << n << " px: stepping drift " << drift << " texels, fresh "
                          << fresh << " texels, bound " << n * 0x1p-24 * u_max);
    record_fact("ch06_drift_stepped", drift);
    record_fact("ch06_drift_bound", n * 0x1p-24 * u_max);
    record_fact("ch06_drift_fresh", fresh);
    CHECK(drift <= n * 0x1p-24 * u_max);
    CHECK(fresh <= 0x1p-23 * u_max);
    CHECK(mapper_drift == drift);
    CHECK(drift > 16 * fresh); // stepping is the problem, not float as such
}

TEST_CASE("long spans in 16.16: integer steps drift by the step's rounding") {
    // The same span in 16.16 fixed point. The additions are exact, but u0 and du are each
    // rounded to 2^-16 first (an error of at most 2^-17 each) and the step's error is
    // added again at every pixel, so after k pixels U / 2^16 is off by at most
    // (1 + k) 2^-17 texels (chapter 3's bound), whatever |u| is. 1.0001 texels is
    // 65542.55 units, rounded by 0.45 of a unit, so the drift comes close to that bound:
    // 4096 * 2^-17 = 1/32 texel at the end of the span.
    const int n = 4096;
    const double u0 = 0.3, du = 1.0001;
    double drift = 0.0;
    int beyond_bound = 0;
    map_span_affine_fixed(AffineSpan<double>{u0, 0.0, du, 0.0, n},
                          [&](int k, std::int32_t U, std::int32_t) {
                              const double error = std::abs(U / 65536.0 - (u0 + k * du));
                              drift = std::max(drift, error);
                              beyond_bound += error > (1 + k) * 0x1p-17 + 1e-12;
                          });
    const double bound = n * 0x1p-17;
    MESSAGE("16.16 over " << n << " px: drift " << drift << " texels, bound " << bound);
    record_fact("ch06_drift_fixed", drift);
    record_fact("ch06_drift_fixed_bound", bound);
    CHECK(beyond_bound == 0);
    CHECK(drift > bound / 2); // integer steps do drift: the step itself was rounded
}
