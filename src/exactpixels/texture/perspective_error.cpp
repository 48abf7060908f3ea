#include "exactpixels/texture/perspective_error.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace exactpixels {

double exact_fraction(double r, double t) {
    return t / (r - (r - 1.0) * t);
}

double affine_error(double r, double t) {
    return t - exact_fraction(r, t);
}

//> affine-bound
double affine_error_bound(double r) {
    assert(r > 0.0);
    const double s = std::sqrt(std::max(r, 1.0 / r)); // the span seen from its near end
    return (s - 1.0) / (s + 1.0);
}
//< affine-bound

double affine_worst_t(double r) {
    assert(r > 0.0);
    return std::sqrt(r) / (std::sqrt(r) + 1.0);
}

double quadratic_error(double r, double t) {
    const double k = r - 1.0;
    return 2.0 * k * k * t * (t - 0.5) * (1.0 - t) / ((r + 1.0) * (r - k * t));
}

double quadratic_error_max(double r) {
    assert(r > 0.0);
    const auto size = [r](double t) { return std::abs(quadratic_error(r, t)); };
    // The error is a cubic over a positive linear function: at most two local maxima
    // in [0, 1]. A dense search brackets the largest; golden sections refine it.
    constexpr int samples = 4096;
    int best = 0;
    for (int k = 1; k <= samples; ++k) {
        if (size(double(k) / samples) > size(double(best) / samples)) {
            best = k;
        }
    }
    double lo = std::max(0.0, double(best - 1) / samples);
    double hi = std::min(1.0, double(best + 1) / samples);
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int step = 0; step < 100 && hi - lo > 1e-15; ++step) {
        const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        (size(a) < size(b) ? lo : hi) = (size(a) < size(b) ? a : b);
    }
    return size(0.5 * (lo + hi));
}

double largest_ratio_within(double (*fraction)(double), double du, double texels) {
    assert(du > 0.0 && texels > 0.0);
    const auto within = [&](double r) { return fraction(r) * du <= texels; };
    if (!within(1.0)) {
        return 1.0;
    }
    double lo = 1.0, hi = 2.0;
    while (within(hi)) {
        if (hi > 1e12) {
            return std::numeric_limits<double>::infinity();
        }
        lo = hi;
        hi *= 2.0;
    }
    while (hi - lo > 1e-9 * lo) {
        const double mid = 0.5 * (lo + hi);
        (within(mid) ? lo : hi) = mid;
    }
    return lo;
}

} // namespace exactpixels
