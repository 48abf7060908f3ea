#include "exactpixels/raster/gradient_stability.hpp"

#include "exactpixels/base/split_mix.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cmath>

namespace exactpixels {

namespace {

constexpr double input_grain = 0x1p-40; // every input is a multiple of this

// v rounded to the nearest float: to 24 significant bits, ties to even, for a v that is
// 0 or a normal float's size. Written out, not as a cast to float and back: GCC 12 at
// -O3 for AVX-512 (-march=native, x86-64-v4) vectorizes on_grain's round trips eight at
// a time and drops them, and the study's float rows were measured in double (the native
// preset's chapter 1 and 6 tests found it).
double rounded_to_float(double v) {
    int e = 0;
    const double m = std::frexp(v, &e); // v = m 2^e with 1/2 <= |m| < 1, or m = 0
    return std::ldexp(std::nearbyint(std::ldexp(m, 24)), e - 24);
}

// v rounded to the input grain, and then to float when `as_float` (which keeps it on
// the grain for |v| < 2^12: a float there has at most 24 significant bits, all at or
// above 2^-40 unless |v| < 2^-16, where it has fewer than 24 bits on the grain anyway).
double on_grain(double v, bool as_float) {
    const double g = std::nearbyint(v / input_grain) * input_grain;
    return as_float ? rounded_to_float(g) : g;
}

Integer to_grain_units(double v) {
    const double units = v / input_grain;
    assert(std::abs(v) < 0x1p12 && units == std::nearbyint(units));
    return Integer(static_cast<std::int64_t>(units));
}

template <class Real> PlaneSamples<Real> converted(const PlaneSamples<double>& s) {
    PlaneSamples<Real> r{};
    for (int i = 0; i < 3; ++i) {
        r.x[i] = static_cast<Real>(s.x[i]);
        r.y[i] = static_cast<Real>(s.y[i]);
        r.c[i] = static_cast<Real>(s.c[i]);
    }
    return r;
}

// The exact gradient as integers: (nx / d, ny / d), d = 2A (0: no gradient).
struct ExactRatio {
    Integer nx, ny, d;
};

// @eq:closed-form in integers: x, y and c all in grains, so the scale cancels.
ExactRatio exact_ratio(const PlaneSamples<double>& s) {
    Integer x[3], y[3], c[3];
    for (int i = 0; i < 3; ++i) {
        x[i] = to_grain_units(s.x[i]);
        y[i] = to_grain_units(s.y[i]);
        c[i] = to_grain_units(s.c[i]);
    }
    const Integer dx2 = x[1] - x[0], dy2 = y[1] - y[0], dc2 = c[1] - c[0];
    const Integer dx3 = x[2] - x[0], dy3 = y[2] - y[0], dc3 = c[2] - c[0];
    return {dc2 * dy3 - dc3 * dy2, dc3 * dx2 - dc2 * dx3, dx2 * dy3 - dx3 * dy2};
}

// v = m 2^e exactly, m an integer of at most 53 bits.
Integer mantissa(double v, int& e) {
    const double m = std::frexp(v, &e);
    e -= 53;
    return Integer(static_cast<std::int64_t>(std::ldexp(m, 53)));
}

// |g - exact| / |exact| for g = (gx, gy), exact = (nx, ny) / d: with gx = mx 2^ex and
// gy = my 2^ey, everything times d 2^-e (e the smallest exponent, at most 0) is an
// integer, so the square of the ratio is a quotient of two integers, rounded once to
// double; its square root is correctly rounded too. Within 2^-52 of the true ratio,
// relatively, and the same double on every platform.
double relative_error(const ExactRatio& exact, double gx, double gy) {
    int ex = 0, ey = 0;
    const Integer mx = mantissa(gx, ex), my = mantissa(gy, ey);
    const int e = std::min({ex, ey, 0});
    const Integer x = ((mx * exact.d) << (ex - e)) - (exact.nx << -e);
    const Integer y = ((my * exact.d) << (ey - e)) - (exact.ny << -e);
    const Integer norm2 = exact.nx * exact.nx + exact.ny * exact.ny;
    return std::sqrt(quotient_to_double(x * x + y * y, norm2 << (-2 * e)));
}

// The value below which the fraction q of v lies (v not empty).
double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

template <class Real>
StabilityRow measure(double y_delta, const std::vector<PlaneSamples<double>>& trials,
                     const char* name) {
    const double epsilon = std::numeric_limits<Real>::epsilon();
    std::vector<double> split, closed;
    StabilityRow row;
    row.y_delta = y_delta;
    row.precision = name;
    row.triangles = static_cast<int>(trials.size());
    for (const PlaneSamples<double>& t : trials) {
        const ExactRatio exact = exact_ratio(t);
        const PlaneSamples<Real> s = converted<Real>(t);
        const Gradient<Real> a = split_edge_gradient(s);
        const Gradient<Real> b = closed_form_gradient(s);
        const double ea = relative_error(exact, a.dx, a.dy) / epsilon;
        const double eb = relative_error(exact, b.dx, b.dy) / epsilon;
        split.push_back(ea);
        closed.push_back(eb);
        row.closed_better += eb < ea;
        row.split_better += ea < eb;
    }
    row.split_median = quantile(split, 0.5);
    row.split_p99 = quantile(split, 0.99);
    row.split_max = quantile(split, 1.0);
    row.closed_median = quantile(closed, 0.5);
    row.closed_p99 = quantile(closed, 0.99);
    row.closed_max = quantile(closed, 1.0);
    return row;
}

} // namespace

std::vector<double> stability_y_deltas() {
    return {1e-2, 1e-4, 1e-6, 1e-9, 1e-12, 0.0};
}

Gradient<Rational> exact_gradient(const PlaneSamples<double>& s) {
    const ExactRatio r = exact_ratio(s);
    if (r.d == 0) {
        return {Rational(0), Rational(0)};
    }
    const Rational d(r.d); // a divisor: Rational(n, d) needs d > 0
    return {Rational(r.nx) / d, Rational(r.ny) / d};
}

std::vector<PlaneSamples<double>> stability_triangles(double y_delta, int count,
                                                      std::uint64_t seed, bool as_float,
                                                      double origin) {
    assert(origin >= 0.0 && origin <= 3072.0); // keeps every input below 2^12
    SplitMix random{seed};
    std::vector<PlaneSamples<double>> trials;
    while (static_cast<int>(trials.size()) < count) {
        // Two vertices y_delta apart at y0, the third h below or above them.
        const double y0 = random.uniform(100.0, 900.0);
        const double h = random.uniform(1.0, 64.0) * (random.next() % 2 ? 1.0 : -1.0);
        PlaneSamples<double> s{};
        s.x = {random.uniform(10, 1000), random.uniform(10, 1000),
               random.uniform(10, 1000)};
        s.y = {y0, y0 + y_delta, y0 + h};
        for (int i = 0; i < 3; ++i) {
            s.x[i] += origin;
            s.y[i] += origin;
        }
        s.c = {random.uniform(0, 1), random.uniform(0, 1), random.uniform(0, 1)};
        // Shuffle the vertex order: the closed form starts from vertex 0.
        const int first = static_cast<int>(random.next() % 3);
        std::rotate(s.x.begin(), s.x.begin() + first, s.x.end());
        std::rotate(s.y.begin(), s.y.begin() + first, s.y.end());
        std::rotate(s.c.begin(), s.c.begin() + first, s.c.end());
        for (int i = 0; i < 3; ++i) {
            s.x[i] = on_grain(s.x[i], as_float);
            s.y[i] = on_grain(s.y[i], as_float);
            s.c[i] = on_grain(s.c[i], as_float);
        }
        // Keep triangles whose close pair is at least 1 px apart in x: a sliver is a
        // different question (ill-conditioned for every method).
        const int a = (first == 0) ? 0 : 3 - first, b = (a + 1) % 3;
        if (std::abs(s.x[a] - s.x[b]) < 1.0) {
            continue;
        }
        const ExactRatio g = exact_ratio(s);
        if (g.d == 0 || (g.nx == 0 && g.ny == 0)) {
            continue; // a constant c: relative error undefined
        }
        trials.push_back(s);
    }
    return trials;
}

std::vector<StabilityRow> gradient_stability_study(int count, std::uint64_t seed,
                                                   double origin) {
    std::vector<StabilityRow> rows;
    for (const double delta : stability_y_deltas()) {
        rows.push_back(measure<float>(
            delta, stability_triangles(delta, count, seed, true, origin), "float"));
        rows.push_back(measure<double>(
            delta, stability_triangles(delta, count, seed, false, origin), "double"));
    }
    return rows;
}

std::string stability_table_markdown(const std::vector<StabilityRow>& rows) {
    std::string out = "| y-delta | type | split: median | p99 | max | closed: median "
                      "| p99 | max | closed better | split better |\n"
                      "|---:|:--|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const StabilityRow& r : rows) {
        const double n = r.triangles / 100.0;
        out += fmt::format(
            "| {:g} | {} | {:.2f} | {:.1f} | {:.0f} | {:.2f} | {:.1f} | {:.0f} "
            "| {:.0f}% | {:.0f}% |\n",
            r.y_delta, r.precision, r.split_median, r.split_p99, r.split_max,
            r.closed_median, r.closed_p99, r.closed_max, r.closed_better / n,
            r.split_better / n);
    }
    return out;
}

} // namespace exactpixels
