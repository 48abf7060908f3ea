// Chapter 4 tests: under perspective, u = p / q with p = u/w and q = 1/w, and the
// numerator of du/dx (@eq:numerator) is the same at every point of a row
// (@eq:numerator-constant), even across 1/w = 0, and its sign is the sign of du/dx, which
// is that of dc/dx (c = u - 1/2 differs from u by a constant); in float it is within a
// stated bound; per row it can differ across a triangle.
#include "exactpixels/base/exact.hpp"
#include "exactpixels/texture/rounding.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace exactpixels;
using testing::record_fact;

namespace {

constexpr int span_count = 600; // random spans per test (a few seconds under ASan)
constexpr int span_length = 160;

using Coordinate = ProjectedCoordinate<Rational>;

/// A random coordinate around pixel 0 of a span along x: p, q, dp/dx, dq/dx dyadic
/// (exact in float too). q crosses zero inside the span for every other span: at
/// t_zero, which is a pixel itself (q = 0 exactly there) in a quarter of them.
struct RandomSpan {
    Coordinate c;  // at t = 0, with exact values
    double t_zero; // where q = 0, or NaN when q keeps its sign
};

RandomSpan random_span(std::mt19937& random, int index) {
    std::uniform_int_distribution<int> mantissa(-(1 << 20), 1 << 20);
    std::uniform_int_distribution<int> crossing(1, 16 * (span_length - 2));
    const Rational p(mantissa(random), 1 << 16), dp(mantissa(random), 1 << 22);
    const Rational dq_dy(mantissa(random), 1 << 22), dp_dy(mantissa(random), 1 << 22);
    Rational q, dq;
    double t_zero = std::numeric_limits<double>::quiet_NaN();
    if (index % 2 == 0) {
        // q keeps one sign over the span: q(t) = q0 + dq t with |dq| t small.
        q = Rational(std::abs(mantissa(random)) + (1 << 14), 1 << 16);
        q = index % 4 == 0 ? q : -q;
        dq = Rational(mantissa(random), 1 << 30);
    } else {
        // q crosses zero at t_zero (a multiple of 1/16; every fourth span exactly at an
        // integer, so one pixel has q = 0 and no u at all).
        int zero16 = crossing(random);
        zero16 = index % 4 == 1 ? zero16 - zero16 % 16 : zero16;
        t_zero = zero16 / 16.0;
        std::uniform_int_distribution<int> small(-(1 << 10), 1 << 10);
        dq = Rational(small(random) | 1, 1 << 16); // odd: never zero; q0 fits a float
        q = -dq * Rational(zero16, 16);
    }
    return {{p, q, {dp, dp_dy}, {dq, dq_dy}}, t_zero};
}

Rational along_x(const Coordinate& c, const Rational& t, bool q_part) {
    return q_part ? c.q + c.dq.dx * t : c.p + c.dp.dx * t;
}

} // namespace

TEST_CASE("the numerator is the same at every point of a row, exactly") {
    // Moving along x by any amount t adds t * dp/dx to p and t * dq/dx to q; the
    // numerator dp/dx q - p dq/dx gains t (dp/dx dq/dx - dp/dx dq/dx) = 0
    // (@eq:numerator-constant). Moving along y by s changes it by s (dp/dx dq/dy - dp/dy
    // dq/dx): linear in y.
    std::mt19937 random(48);
    std::uniform_int_distribution<int> step(-5000, 5000);
    for (int i = 0; i < span_count; ++i) {
        const Coordinate c = random_span(random, i).c;
        const Rational n = numerator_x(c);
        for (int j = 0; j < 20; ++j) {
            const Rational t(step(random), 7); // any real step, not only whole pixels
            const Rational s(step(random), 3);
            INFO("coordinate " << i << ", t = " << t << ", s = " << s);
            CHECK(numerator_x(moved_by(c, t, Rational(0))) == n);
            CHECK(numerator_y(moved_by(c, Rational(0), s)) == numerator_y(c));
            const Rational cross = c.dp.dx * c.dq.dy - c.dp.dy * c.dq.dx;
            CHECK(numerator_x(moved_by(c, t, s)) == n + s * cross);
        }
    }
}

TEST_CASE("one pixel step changes c by the numerator over q q', exactly") {
    // u(t) = p(t) / q(t); u(t+1) - u(t) = n / (q(t) q(t+1)) wherever both q are non-zero,
    // and c = u - 1/2 steps by the same amount.
    std::mt19937 random(480);
    for (int i = 0; i < span_count / 4; ++i) {
        const Coordinate c = random_span(random, i).c;
        const Rational n = numerator_x(c);
        for (int t = 0; t + 1 < span_length; ++t) {
            const Rational q0 = along_x(c, Rational(t), true);
            const Rational q1 = along_x(c, Rational(t + 1), true);
            if (q0 == Rational(0) || q1 == Rational(0)) {
                continue;
            }
            const Rational u0 = along_x(c, Rational(t), false) / q0;
            const Rational u1 = along_x(c, Rational(t + 1), false) / q1;
            INFO("coordinate " << i << ", pixel " << t);
            CHECK(u1 - u0 == n / (q0 * q1));
        }
    }
}

TEST_CASE("the numerator's sign is the sign of dc/dx at every pixel, across 1/w = 0") {
    // du/dx (= dc/dx) at pixel t is measured without the numerator: the exact secant of
    // u = p/q over a step h = 2^-20 px towards the side where q keeps its sign. On both
    // sides of q = 0 it has the numerator's sign; the whole-pixel step that jumps across
    // q = 0 does not (u runs off to infinity and comes back from the other side), which
    // is why a mapper must not take the rule from u's difference between two pixels.
    std::mt19937 random(4800);
    const Rational h(1, 1 << 20);
    int pixels = 0, crossing_steps = 0, pixels_on_zero = 0, negative_q = 0;
    for (int i = 0; i < span_count; ++i) {
        const RandomSpan span = random_span(random, i);
        const Coordinate& c = span.c;
        const int n_sign = sign(numerator_x(c));
        REQUIRE(n_sign != 0); // random dyadic data: a zero numerator is not expected
        for (int t = 0; t < span_length; ++t) {
            const Rational q = along_x(c, Rational(t), true);
            if (q == Rational(0)) {
                ++pixels_on_zero; // no u here at all; the numerator is still n
                CHECK(numerator_x(moved_by(c, Rational(t), Rational(0))) ==
                      numerator_x(c));
                continue;
            }
            // Step away from the zero of q so both points are on one side of it.
            const bool zero_ahead = !std::isnan(span.t_zero) && span.t_zero > t;
            const Rational step = zero_ahead ? -h : h;
            const Rational q2 = along_x(c, Rational(t) + step, true);
            REQUIRE(sign(q2) == sign(q));
            const Rational secant = (along_x(c, Rational(t) + step, false) / q2 -
                                     along_x(c, Rational(t), false) / q) /
                                    step;
            INFO("span " << i << ", pixel " << t << ", q = " << q);
            CHECK(sign(secant) == n_sign);
            ++pixels;
            negative_q += sign(q) < 0;
            // The step to the next pixel, where it crosses q = 0.
            const Rational q_next = along_x(c, Rational(t + 1), true);
            if (sign(q_next) == -sign(q)) {
                const Rational jump = along_x(c, Rational(t + 1), false) / q_next -
                                      along_x(c, Rational(t), false) / q;
                CHECK(sign(jump) == -n_sign);
                ++crossing_steps;
            }
        }
    }
    MESSAGE(pixels << " pixels (" << negative_q << " behind the eye, 1/w < 0), "
                   << crossing_steps << " steps across 1/w = 0, " << pixels_on_zero
                   << " pixels exactly on it");
    CHECK(crossing_steps > span_count / 8);
    CHECK(pixels_on_zero > span_count / 8);
}

TEST_CASE("the float numerator is within the stated rounding bound of the exact one") {
    // Evaluated per pixel in float as a mapper would, p = p0 + dp t, q = q0 + dq t,
    // n = dp q - p dq, each operation rounds once (relative error <= e = 2^-24), so
    //   |n_float - n| <= g4 (|dp| (|q0| + |dq t|) + |dq| (|p0| + |dp t|)),
    // g4 = 4e / (1 - 4e): each product carries at most four roundings. Where |n| exceeds
    // the bound the float sign is the exact sign.
    std::mt19937 random(48000);
    const double e = std::ldexp(1.0, -24);
    const double g4 = 4 * e / (1 - 4 * e);
    double worst = 0; // largest error / bound seen
    int sign_checks = 0;
    for (int i = 0; i < span_count; ++i) {
        const Coordinate c = random_span(random, i).c;
        const auto p0 = static_cast<float>(to_double(c.p)); // exact: dyadic, 21 bits
        const auto q0 = static_cast<float>(to_double(c.q));
        const auto dp = static_cast<float>(to_double(c.dp.dx));
        const auto dq = static_cast<float>(to_double(c.dq.dx));
        REQUIRE(exact(p0) == c.p);
        REQUIRE(exact(q0) == c.q);
        REQUIRE(exact(dq) == c.dq.dx);
        const Rational n = numerator_x(c);
        for (int t = 0; t < span_length; ++t) {
            const auto tf = static_cast<float>(t);
            const float p = p0 + dp * tf;
            const float q = q0 + dq * tf;
            const float n_float = dp * q - p * dq;
            const double bound =
                g4 * (std::abs(double{dp}) *
                          (std::abs(double{q0}) + std::abs(double{dq} * t)) +
                      std::abs(double{dq}) *
                          (std::abs(double{p0}) + std::abs(double{dp} * t)));
            const Rational error = abs(exact(n_float) - n);
            INFO("span " << i << ", pixel " << t);
            CHECK(error <= exact(bound));
            worst = std::max(worst, to_double(error) / bound);
            if (abs(n) > exact(bound)) {
                CHECK(sign(exact(n_float)) == sign(n));
                ++sign_checks;
            }
        }
    }
    MESSAGE("worst float error: " << worst << " of the bound; " << sign_checks
                                  << " pixels had |n| above the bound");
    record_fact("ch04_float_numerator_of_bound", worst);
    CHECK(sign_checks > span_count * span_length / 2);
}

TEST_CASE("the chosen rule can differ between rows of one perspective triangle" *
          doctest::description("points: 2; exercise: ch04-choose-rule")) {
    // A wall seen at an angle: its near edge at x = 10 (w = 1, v from 0 to 64) and its
    // far corner at x = 74 (w = 4, v = 0). Lines of constant v meet at one point on the
    // horizon row y = 42.5 (the eye's height, where v = 32): above that row v falls to
    // the right, below it v rises. Every row's rule is checked against the exact secant
    // of v between two points of the row. All inputs are dyadic, so the gradients are
    // exact in double and the horizon row's x numerator is exactly zero.
    const std::array<TexturedVertex, 3> wall{{{{10.0, 10.5}, 1.0, {0.0, 0.0}},
                                              {{74.0, 34.5}, 4.0, {64.0, 0.0}},
                                              {{10.0, 74.5}, 1.0, {0.0, 64.0}}}};
    auto v_at = [&](const Rational& x, const Rational& y) {
        // Exact barycentric interpolation of v/w and 1/w, then the divide.
        std::array<Rational, 3> vx, vy, q, pv;
        for (int i = 0; i < 3; ++i) {
            vx[i] = exact(wall[i].position.x);
            vy[i] = exact(wall[i].position.y);
            q[i] = Rational(1) / exact(wall[i].w);
            pv[i] = exact(wall[i].uv.y) * q[i];
        }
        auto cross = [&](int i, const Rational& ax, const Rational& ay,
                         const Rational& bx, const Rational& by) {
            return (ax - vx[i]) * (by - vy[i]) - (ay - vy[i]) * (bx - vx[i]);
        };
        const Rational area = cross(0, vx[1], vy[1], vx[2], vy[2]);
        const Rational b1 = cross(0, x, y, vx[2], vy[2]) / area;
        const Rational b2 = cross(0, vx[1], vy[1], x, y) / area;
        const Rational b0 = Rational(1) - b1 - b2;
        return (b0 * pv[0] + b1 * pv[1] + b2 * pv[2]) /
               (b0 * q[0] + b1 * q[1] + b2 * q[2]);
    };
    int rows_differing_from_triangle = 0, rows_checked = 0;
    const TexelRounding whole = choose_rounding(wall);
    for (int y = 12; y < 72; ++y) {
        const double centre_y = y + 0.5;
        const Rational yc = exact(centre_y);
        const int secant_sign = sign(v_at(Rational(13), yc) - v_at(Rational(12), yc));
        const TexelRounding row = choose_rounding_on_row(wall, centre_y);
        INFO("row " << y);
        if (centre_y == 42.5) {
            // The horizon row: v is 32 all along it, dv/dx = 0, and v grows downwards.
            CHECK(secant_sign == 0);
            CHECK(v_at(Rational(12), yc) == Rational(32));
            CHECK(row.v_modifier == texel_modifier(RoundingRule::ties_up));
            continue;
        }
        CHECK(secant_sign == (centre_y < 42.5 ? -1 : 1));
        CHECK(row.v_modifier == texel_modifier(secant_sign > 0
                                                   ? RoundingRule::ties_up
                                                   : RoundingRule::ties_down));
        rows_differing_from_triangle += row.v_modifier != whole.v_modifier;
        ++rows_checked;
    }
    MESSAGE(rows_differing_from_triangle
            << " of " << rows_checked << " rows need the other rule than the centroid's");
    record_fact("ch04_wall_rows_checked", rows_checked);
    record_fact("ch04_wall_rows_other_rule", rows_differing_from_triangle);
    CHECK(rows_differing_from_triangle > 0);
    CHECK(rows_differing_from_triangle < rows_checked);
}

TEST_CASE("with rounding per row, every row samples with its own rule") {
    // The wall of the test above, drawn in 16.16 fixed point with the exact mapper: each
    // pixel's texel row must be the one its own row's rule picks from the v the mapper
    // computed, and the rule must change from row to row (above and below the horizon).
    const std::array<TexturedVertex, 3> wall{{{{10.0, 10.5}, 1.0, {0.0, 0.0}},
                                              {{74.0, 34.5}, 4.0, {64.0, 0.0}},
                                              {{10.0, 74.5}, 1.0, {0.0, 64.0}}}};
    MapperSettings settings;
    settings.precision = Precision::fixed;
    settings.row_rounding = choose_rounding_on_row;
    TexelMap map(96, 96);
    map_textured_triangle(map, wall, settings);
    int pixels = 0;
    std::vector<std::int32_t> modifiers;
    for (int y = 0; y < map.height; ++y) {
        const TexelRounding row = choose_rounding_on_row(wall, y + 0.5);
        bool row_covered = false;
        for (int x = 0; x < map.width; ++x) {
            const std::size_t k = static_cast<std::size_t>(y * map.width + x);
            if (!map.covered[k]) {
                continue;
            }
            const auto V = static_cast<std::int32_t>(std::lround(map.v[k] * texel_scale));
            INFO("pixel (" << x << ", " << y << ")");
            CHECK(map.j[k] == fixed_texel_index(V, row.v_modifier));
            row_covered = true;
            ++pixels;
        }
        if (row_covered) {
            modifiers.push_back(row.v_modifier);
        }
    }
    CHECK(pixels > 1000);
    CHECK(std::count(modifiers.begin(), modifiers.end(),
                     texel_modifier(RoundingRule::ties_up)) > 0);
    CHECK(std::count(modifiers.begin(), modifiers.end(),
                     texel_modifier(RoundingRule::ties_down)) > 0);
}
