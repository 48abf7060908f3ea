// Figure data: how the stepping error of chapter 1 (@sec:stepping) grows with the
// triangle's size, for Exercise 6's solution. Right triangles with legs of 8, 16, ...,
// 1024 px (at a random sub-pixel position, 16 per size, one random value per vertex in
// [-1, 1]) are drawn by scanline_interpolate; every pixel's value is compared with the
// plane of the same computed gradient evaluated exactly at the pixel's centre (the
// difference rounded once to double), so only the stepping is measured, as in the
// chapter's test. Writes
// ch01_stepping.txt into the folder argv[1], one fact per line:
//   worst_L   the worst |stepped - plane| / (eps S) over the triangles of leg L
//   mean_L    the mean of the same over every pixel of those triangles
//   bound_L   the bound of @sec:stepping, rows + columns + 4 = 2L + 4
//   slope_worst, slope_mean  least-squares slopes of log(error) against log(2L)
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/base/split_mix.hpp"
#include "exactpixels/raster/scanline.hpp"
#include "support/figure_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <vector>

namespace {

using namespace exactpixels;

/// The plane c0 + gx (x + 1/2 - x0) + gy (y + 1/2 - y0) at pixel centres, exactly: every
/// term is a dyadic fraction, so the plane is an integer in units of 2^-shift, and each
/// pixel costs integer products and sums, no fraction reduced.
class ExactPlane {
  public:
    /// The plane of gradient g through value c0 at (x0, y0).
    ExactPlane(double c0, Gradient<double> g, double x0, double y0) {
        const Rational half(1, 2);
        const Rational at_origin = exact(c0) + exact(g.dx) * (half - exact(x0)) +
                                   exact(g.dy) * (half - exact(y0)); // pixel (0, 0)
        shift_ = std::max({bits_below_one(at_origin), bits_below_one(exact(g.dx)),
                           bits_below_one(exact(g.dy))});
        origin_ = units(at_origin);
        dx_ = units(exact(g.dx));
        dy_ = units(exact(g.dy));
    }
    /// |a - the plane at the centre of pixel (x, y)|: the difference exact, then rounded
    /// once to double.
    double distance(double a, int x, int y) const {
        const Integer plane = origin_ + dx_ * x + dy_ * y; // units of 2^-shift
        int e = 0;
        const double m = std::frexp(a, &e); // a = m 2^e, 1/2 <= |m| < 1
        const auto mantissa = static_cast<std::int64_t>(std::ldexp(m, 53));
        const int a_shift = shift_ + e - 53; // a = mantissa 2^a_shift units
        if (a_shift < 0) { // a has bits finer than the plane's: a fraction after all
            return to_double(abs(exact(a) - Rational(plane, Integer(1) << shift_)));
        }
        const Integer difference = (Integer(mantissa) << a_shift) - plane;
        return std::ldexp(to_double(Rational(abs(difference))), -shift_); // exact scaling
    }

  private:
    // The power of two in r's denominator (r is dyadic: a sum of products of doubles).
    static int bits_below_one(const Rational& r) {
        return static_cast<int>(boost::multiprecision::msb(denominator(r)));
    }
    Integer units(const Rational& r) const {
        return numerator(r) << (shift_ - bits_below_one(r));
    }
    int shift_ = 0;
    Integer origin_, dx_, dy_;
};

/// The stepping error of one size: worst and mean over every drawn pixel, in eps S.
struct SizeError {
    double worst = 0;
    double mean = 0;
};

SizeError stepping_error(int leg, int triangles, SplitMix& random) {
    const Viewport viewport{leg + 8, leg + 8};
    double worst = 0, sum = 0;
    long pixels = 0;
    for (int t = 0; t < triangles; ++t) {
        const double x0 = random.uniform(2.0, 3.0), y0 = random.uniform(2.0, 3.0);
        const std::array<Point2, 3> v{{{x0, y0}, {x0 + leg, y0}, {x0, y0 + leg}}};
        const std::array<Attributes<1>, 3> c{{{random.uniform(-1.0, 1.0)},
                                              {random.uniform(-1.0, 1.0)},
                                              {random.uniform(-1.0, 1.0)}}};
        const Gradient<double> g =
            closed_form_gradient<double>(v, {c[0][0], c[1][0], c[2][0]});
        // S of @sec:stepping: bounds every term of the sum (X = Y = x0 + leg at most).
        const double size =
            std::max({std::abs(c[0][0]), std::abs(c[1][0]), std::abs(c[2][0])}) +
            (std::abs(g.dx) + std::abs(g.dy)) * (x0 + leg + 1.0);
        const double eps_s = 0x1p-52 * size;
        const ExactPlane plane(c[0][0], g, x0, y0);
        scanline_interpolate(v, c, viewport, [&](int x, int y, const Attributes<1>& a) {
            const double e = plane.distance(a[0], x, y) / eps_s;
            worst = std::max(worst, e);
            sum += e;
            ++pixels;
        });
    }
    return {worst, pixels > 0 ? sum / static_cast<double>(pixels) : 0.0};
}

/// The least-squares slope of log(y) against log(x).
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        mx += std::log(x[i]) / static_cast<double>(x.size());
        my += std::log(y[i]) / static_cast<double>(x.size());
    }
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
        sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
    }
    return sxy / sxx;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    SplitMix random{6};
    std::ostringstream facts;
    facts << "# chapter 1, Exercise 6: stepping error against triangle size (in eps S)\n";
    std::vector<double> steps, worst, mean;
    for (int leg = 8; leg <= 1024; leg *= 2) {
        const SizeError e = stepping_error(leg, 16, random);
        steps.push_back(2.0 * leg);
        worst.push_back(e.worst);
        mean.push_back(e.mean);
        facts << "worst_" << leg << ' ' << e.worst << '\n'
              << "mean_" << leg << ' ' << e.mean << '\n'
              << "bound_" << leg << ' ' << 2 * leg + 4 << '\n';
    }
    facts << "slope_worst " << log_log_slope(steps, worst) << '\n'
          << "slope_mean " << log_log_slope(steps, mean) << '\n';
    try {
        write_figure_file(folder / "ch01_stepping.txt", facts.str());
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch01_stepping: %s\n", error.what());
        return 1;
    }
}
