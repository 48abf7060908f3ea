// Chapter 3 tests: Pursey's quadratic and Thellier's form of it, forward differencing,
// and the closed-form errors of the affine and quadratic mappers, checked in exact
// rational arithmetic wherever the claim is exact.
#include "exactpixels/base/exact.hpp"
#include "exactpixels/texture/perspective_error.hpp"
#include "exactpixels/texture/quadratic.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {
/// The exact u at screen parameter t of a span from (u0, depth w0) to (u2, depth w2):
/// u/w and 1/w interpolated linearly, then divided (eq:exact-divide), in exact
/// arithmetic.
Rational exact_u(Rational u0, Rational w0, Rational u2, Rational w2, Rational t) {
    const Rational one(1);
    const Rational u_w = (one - t) * (u0 / w0) + t * (u2 / w2);
    const Rational one_w = (one - t) * (one / w0) + t * (one / w2);
    return u_w / one_w;
}
} // namespace

TEST_CASE("Thellier's coefficients equal Pursey's in exact arithmetic") {
    std::mt19937 random(3);
    std::uniform_int_distribution<int> texel(-2000, 2000), depth(1, 1000), steps(1, 512);
    for (int trial = 0; trial < 2000; ++trial) {
        const Rational u0(texel(random)), u2(texel(random));
        const Rational w0(depth(random), depth(random)), w2(depth(random), depth(random));
        const Rational n(steps(random));
        const Quadratic<Rational> p = pursey_quadratic(u0, w0, u2, w2, n);
        const Quadratic<Rational> t = thellier_quadratic(u0, w0, u2, w2, n);
        INFO("u0 = " << u0 << ", w0 = " << w0 << ", u2 = " << u2 << ", w2 = " << w2
                     << ", n = " << n);
        REQUIRE(t.a == p.a);
        REQUIRE(t.b == p.b);
        REQUIRE(t.u0 == p.u0);
    }
}

TEST_CASE("Thellier's and Pursey's coefficients agree in float within the stated bound") {
    // Both forms, run in float, are compared with the exact coefficients of the same
    // float inputs. Pursey's 2 u0 - 4 u1 + 2 u2 cancels: its rounding error is a few ulps
    // of the largest |u| involved, so a and b are allowed 32 float epsilons of
    // (|u0| + |u2|) / n^2 and (|u0| + |u2|) / n.
    std::mt19937 random(7);
    std::uniform_real_distribution<float> texel(-1000.0f, 1000.0f), depth(0.01f, 100.0f);
    std::uniform_int_distribution<int> steps(1, 1024);
    const double eps = std::numeric_limits<float>::epsilon();
    double worst = 0.0; // largest error as a fraction of the allowance
    for (int trial = 0; trial < 2000; ++trial) {
        const float u0 = texel(random), u2 = texel(random), w0 = depth(random),
                    w2 = depth(random), n = float(steps(random));
        const auto R = [](float x) { return exact(x); };
        const Quadratic<Rational> exact =
            pursey_quadratic(R(u0), R(w0), R(u2), R(w2), R(n));
        const double scale = std::abs(double(u0)) + std::abs(double(u2));
        for (const Quadratic<float>& q : {pursey_quadratic(u0, w0, u2, w2, n),
                                          thellier_quadratic(u0, w0, u2, w2, n)}) {
            const double a_error = std::abs(q.a - to_double(exact.a));
            const double b_error = std::abs(q.b - to_double(exact.b));
            const double a_allowed = 32 * eps * scale / (double(n) * n);
            const double b_allowed = 32 * eps * scale / n;
            CHECK(a_error <= a_allowed);
            CHECK(b_error <= b_allowed);
            worst = std::max({worst, a_error / a_allowed, b_error / b_allowed});
        }
    }
    MESSAGE("largest float error: " << worst << " of the allowance");
}

TEST_CASE("the parabola passes through the exact values at both ends and the middle") {
    std::mt19937 random(11);
    std::uniform_int_distribution<int> texel(-500, 500), depth(1, 200), steps(1, 300);
    for (int trial = 0; trial < 1000; ++trial) {
        const Rational u0(texel(random)), u2(texel(random));
        const Rational w0(depth(random), 7), w2(depth(random), 3);
        const Rational n(steps(random));
        const Quadratic<Rational> q = thellier_quadratic(u0, w0, u2, w2, n);
        CHECK(evaluate(q, Rational(0)) == u0);
        CHECK(evaluate(q, n / Rational(2)) == exact_u(u0, w0, u2, w2, Rational(1, 2)));
        CHECK(evaluate(q, n) == u2);
        CHECK(perspective_midpoint(u0, w0, u2, w2) ==
              exact_u(u0, w0, u2, w2, Rational(1, 2)));
    }
}

TEST_CASE("forward differences reproduce the parabola exactly") {
    std::mt19937 random(13);
    std::uniform_int_distribution<int> small(-4096, 4096);
    for (int trial = 0; trial < 200; ++trial) {
        // Exact arithmetic: every step equals a t^2 + b t + u0.
        const Quadratic<Rational> q{Rational(small(random), 97),
                                    Rational(small(random), 13), Rational(small(random))};
        ForwardDifferences<Rational> f = forward_differences(q);
        for (int t = 0; t <= 64; ++t) {
            REQUIRE(f.u == evaluate(q, Rational(t)));
            step(f);
        }
        // Double, with coefficients of 12 significant bits (multiples of 2^-10, |.| < 4):
        // every sum up to t = 64 is a multiple of 2^-10 below 2^22, so exact in double.
        const Quadratic<double> d{std::ldexp(small(random), -10),
                                  std::ldexp(small(random), -10), double(small(random))};
        ForwardDifferences<double> g = forward_differences(d);
        for (int t = 0; t <= 64; ++t) {
            REQUIRE(g.u == evaluate(d, double(t)));
            step(g);
        }
    }
}

TEST_CASE("forward differences in float stay within the stated bound over long spans") {
    // Each float addition is off by at most half an ulp of its result. After t steps du
    // has drifted by at most t eps/2 max|du| and u by the sum of those drifts plus its
    // own roundings: |error(t)| <= eps/2 (t max|u| + t^2 max|du|), eps = 2^-23.
    // The text quotes, for the spans of 2047 pixels, the bound at the last pixel and the
    // drift measured: two different numbers.
    const double eps = std::numeric_limits<float>::epsilon();
    double longest_bound_lo = 1e300, longest_bound_hi = 0.0, longest_drift = 0.0;
    for (const double r : {1.5, 4.0, 16.0}) {
        for (const int n : {256, 1024, 2047}) {
            const float w0 = 1.0f, w2 = float(r);
            const Quadratic<float> q =
                thellier_quadratic(3.25f, w0, 700.5f, w2, float(n));
            const Quadratic<Rational> q_exact{exact(q.a), exact(q.b), exact(q.u0)};
            ForwardDifferences<float> f = forward_differences(q);
            double max_u = 0.0, max_du = 0.0, worst = 0.0, bound = 0.0;
            for (int t = 0; t <= n; ++t) {
                const double truth = to_double(evaluate(q_exact, Rational(t)));
                max_u = std::max(max_u, std::abs(truth));
                max_du = std::max(max_du, std::abs(double(f.du)));
                bound = eps / 2 * (t * max_u + double(t) * t * max_du) + 1e-12;
                const double error = std::abs(f.u - truth);
                REQUIRE(error <= bound);
                worst = std::max(worst, error);
                step(f);
            }
            MESSAGE("r = " << r << ", n = " << n << ": worst float drift " << worst
                           << " texels, bound at the last pixel " << bound);
            if (n == 2047) {
                longest_bound_lo = std::min(longest_bound_lo, bound);
                longest_bound_hi = std::max(longest_bound_hi, bound);
                longest_drift = std::max(longest_drift, worst);
            }
        }
    }
    CHECK(longest_drift < longest_bound_lo); // the bound holds with room on every span
    record_fact("ch03_fd_bound_2047_lo", longest_bound_lo);
    record_fact("ch03_fd_bound_2047_hi", longest_bound_hi);
    record_fact("ch03_fd_drift_2047", longest_drift);
}

TEST_CASE("the affine and quadratic errors have the closed forms derived in the text") {
    // u0 = 0, u2 = 1, w0 = 1, w2 = r, one step (n = 1): the error at t is the mapper's
    // value minus the exact one, as a fraction of the span's extent.
    const Rational one(1), half(1, 2);
    for (const Rational& r :
         {Rational(2), Rational(1, 3), Rational(9), Rational(100), Rational(7, 5)}) {
        const Quadratic<Rational> q = pursey_quadratic(Rational(0), one, one, r, one);
        const Rational k = r - one;
        for (int i = 0; i <= 40; ++i) {
            const Rational t(i, 40);
            const Rational exact = exact_u(Rational(0), one, one, r, t);
            CHECK(exact == t / (r - k * t)); // eq:exact-fraction
            // eq:affine-error
            CHECK(t - exact == k * t * (one - t) / (r - k * t));
            // eq:quadratic-error
            CHECK(evaluate(q, t) - exact == Rational(2) * k * k * t * (t - half) *
                                                (one - t) / ((r + one) * (r - k * t)));
            // The double forms in perspective_error.hpp compute the same functions.
            CHECK(affine_error(to_double(r), to_double(t)) ==
                  doctest::Approx(to_double(t - exact)).epsilon(1e-12).scale(1.0));
            CHECK(quadratic_error(to_double(r), to_double(t)) ==
                  doctest::Approx(to_double(evaluate(q, t) - exact)).scale(1.0));
        }
    }
}

TEST_CASE("the affine error peaks at sqrt r / (sqrt r + 1) with the derived bound") {
    // r = (p/q)^2 makes sqrt r rational, so the peak and the bound are exact rationals.
    const Rational one(1);
    for (const auto& [p, q] :
         {std::pair{2, 1}, {3, 1}, {10, 1}, {5, 2}, {1, 3}, {7, 4}}) {
        const Rational s(p, q), r = s * s, k = r - one;
        const auto error = [&](Rational t) { return t - t / (r - k * t); };
        const Rational t_star = s / (s + one);
        const Rational bound = (s - one) / (s + one); // eq:affine-bound (signed)
        CHECK(error(t_star) == bound);
        for (int i = 0; i <= 200; ++i) {
            const Rational t(i, 200);
            CHECK(abs(error(t)) <= abs(bound)); // the peak is the largest error
        }
        CHECK(affine_error_bound(to_double(r)) == doctest::Approx(to_double(abs(bound))));
        CHECK(affine_worst_t(to_double(r)) == doctest::Approx(to_double(t_star)));
    }
}

TEST_CASE("quadratic_error_max is the largest quadratic error over the span") {
    for (const double r : {1.1, 2.0, 4.0, 10.0, 100.0, 0.25}) {
        const double peak = quadratic_error_max(r);
        double sampled = 0.0;
        for (int i = 0; i <= 100000; ++i) {
            sampled = std::max(sampled, std::abs(quadratic_error(r, i / 100000.0)));
        }
        CHECK(peak >= sampled);
        CHECK(peak <= sampled * (1 + 1e-6));
        // The quadratic is always better than affine, by a wide margin for mild r.
        CHECK(peak < affine_error_bound(r));
    }
    // A span seen from its other end has the same worst error.
    CHECK(quadratic_error_max(0.2) == doctest::Approx(quadratic_error_max(5.0)));
}

TEST_CASE("u is linear along lines of constant 1/w and bends along every other line") {
    // u/w = p(X, Y) and 1/w = q(X, Y) are affine (@eq:linear-in-screen), u = p / q. Along
    // the line through P with direction d, the second difference of u at three equally
    // spaced points is zero exactly when d is along a line of constant q (or u does not
    // change along d at all). Exact rationals, random planes and directions.
    std::mt19937 random(15);
    std::uniform_int_distribution<int> small(-40, 40), positive(20, 60);
    int bent = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Rational p0(small(random)), px(small(random), 16), py(small(random), 16);
        const Rational q0(positive(random)), qx(small(random), 64), qy(small(random), 64);
        const auto u_at = [&](Rational x, Rational y) {
            return (p0 + px * x + py * y) / (q0 + qx * x + qy * y);
        };
        const Rational x(small(random), 8), y(small(random), 8);
        const auto second_difference = [&](Rational dx, Rational dy) {
            return u_at(x + 2 * dx, y + 2 * dy) - 2 * u_at(x + dx, y + dy) + u_at(x, y);
        };
        // q > 0 at all three points: q0 >= 20, |qx|, |qy| <= 40/64, |x|, |y| <= 5 + 2.
        CHECK(second_difference(-qy, qx) == Rational(0)); // along constant 1/w
        const Rational dx(small(random)), dy(small(random));
        const bool constant_q = qx * dx + qy * dy == Rational(0);
        const bool constant_u = (px * dx + py * dy) * (q0 + qx * x + qy * y) ==
                                (qx * dx + qy * dy) * (p0 + px * x + py * y);
        if (!constant_q && !constant_u) {
            CHECK(second_difference(dx, dy) != Rational(0));
            ++bent;
        }
    }
    CHECK(bent > 1000);
}

TEST_CASE("Pursey's parabola is monotonic exactly when the depth ratio is in [1/3, 3]") {
    // Slopes at both ends (@eq:pursey-slopes), exact, for every r = i / j with i, j in
    // 1..24, on spans of 64 texels and 37 pixel steps.
    const Rational du(64), n(37);
    int monotonic = 0, not_monotonic = 0;
    for (int i = 1; i <= 24; ++i) {
        for (int j = 1; j <= 24; ++j) {
            const Rational r(i, j);
            const Quadratic<Rational> q =
                thellier_quadratic(Rational(5), Rational(1), Rational(5) + du, r, n);
            const Rational first = q.b, last = Rational(2) * q.a * n + q.b;
            CHECK(first == (Rational(3) - r) / (Rational(1) + r) * du / n);
            CHECK(last == (Rational(3) * r - Rational(1)) / (Rational(1) + r) * du / n);
            const bool one_sign = first >= Rational(0) && last >= Rational(0);
            CHECK(one_sign == pursey_is_monotonic(r));
            CHECK(one_sign == (Rational(1, 3) <= r && r <= Rational(3)));
            (one_sign ? monotonic : not_monotonic) += 1;
        }
    }
    CHECK(monotonic > 0);
    CHECK(not_monotonic > 0);
}

TEST_CASE("beyond r = 3 the parabola overshoots its ends; by 8/15 texel at r = 4") {
    // The extreme of a t^2 + b t + u0 is at t = -b / 2a with value u0 - b^2 / 4a: compare
    // it, exactly, with pursey_overshoot for r = i / j, on spans seen from either end.
    for (int i = 1; i <= 30; ++i) {
        for (int j = 1; j <= 30; ++j) {
            const Rational r(i, j), du(64), n(63);
            const Quadratic<Rational> q =
                thellier_quadratic(Rational(0), Rational(1), du, r, n);
            const Rational overshoot = pursey_overshoot(r) * du;
            if (!pursey_is_monotonic(r)) {
                const Rational t = -q.b / (Rational(2) * q.a);
                CHECK(Rational(0) < t);
                CHECK(t < n);
                const Rational extreme = evaluate(q, t);
                CHECK((r > Rational(1) ? -extreme : extreme - du) == overshoot);
                CHECK(overshoot > Rational(0));
                CHECK(overshoot < du / Rational(8)); // approaches du / 8 as r grows
            } else {
                CHECK(overshoot == Rational(0));
            }
        }
    }
    // The span of figure 3.3: r = 4, 64 texels over 64 pixels (63 steps): u dips to
    // -8/15 texel at t = 63/12, where the exact u is positive.
    const Quadratic<Rational> q = thellier_quadratic(
        Rational(0), Rational(1), Rational(64), Rational(4), Rational(63));
    const Rational t = -q.b / (Rational(2) * q.a);
    CHECK(t == Rational(63, 12));
    CHECK(evaluate(q, t) == Rational(-8, 15));
    CHECK(exact_u(Rational(0), Rational(1), Rational(64), Rational(4), t / Rational(63)) >
          Rational(0));
}

TEST_CASE("the depth at the screen midpoint is 2 w0 w2 / (w0 + w2), not the mean") {
    // 1/w is linear on screen: at t = 1/2 it is the mean of 1/w0 and 1/w2, so w there is
    // the harmonic mean. The arithmetic mean (the source's z1) is larger unless w0 = w2;
    // the source's u1 (perspective_midpoint) is the exact u at the same point.
    std::mt19937 random(17);
    std::uniform_int_distribution<int> depth(1, 500), texel(-300, 300);
    for (int trial = 0; trial < 1000; ++trial) {
        const Rational w0(depth(random), 3), w2(depth(random), 7);
        const Rational half(1, 2);
        const Rational one_w = (Rational(1) - half) / w0 + half / w2; // linear on screen
        const Rational w_mid = Rational(1) / one_w;
        CHECK(w_mid == Rational(2) * w0 * w2 / (w0 + w2));
        CHECK((w_mid == (w0 + w2) / Rational(2)) == (w0 == w2));
        CHECK(w_mid <= (w0 + w2) / Rational(2));
        const Rational u0(texel(random)), u2(texel(random));
        CHECK(perspective_midpoint(u0, w0, u2, w2) == exact_u(u0, w0, u2, w2, half));
    }
}

TEST_CASE("the quarter-point parabola passes through the exact values at 0, n/4 and n" *
          doctest::description("points: 20; exercise: ch03-quarter-point")) {
    // In exact arithmetic, against u/w and 1/w interpolated and divided (exact_u): the
    // parabola a t^2 + b t + u0 must take the exact value at the span's first pixel, a
    // quarter of the way along and at its last pixel, for every depth ratio.
    std::mt19937 random(13);
    std::uniform_int_distribution<int> texel(-2000, 2000), depth(1, 1000), steps(1, 512);
    int curved = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const Rational u0(texel(random)), u2(texel(random));
        const Rational w0(depth(random), depth(random)), w2(depth(random), depth(random));
        const Rational n(steps(random));
        const Quadratic<Rational> q = quarter_point_quadratic(u0, w0, u2, w2, n);
        const auto at = [&](Rational t) { return q.u0 + q.b * t + q.a * t * t; };
        INFO("u0 = " << u0 << ", w0 = " << w0 << ", u2 = " << u2 << ", w2 = " << w2
                     << ", n = " << n);
        REQUIRE(at(Rational(0)) == u0);
        REQUIRE(at(n / 4) == exact_u(u0, w0, u2, w2, Rational(1, 4)));
        REQUIRE(at(n) == u2);
        curved += q.a != Rational(0);
    }
    CHECK(curved > 1900);
    // Equal depths: the exact u is linear, and so is the parabola.
    const Quadratic<Rational> flat = quarter_point_quadratic(
        Rational(3), Rational(2), Rational(35), Rational(2), Rational(8));
    CHECK(flat.a == Rational(0));
    CHECK(flat.b == Rational(4));
}
