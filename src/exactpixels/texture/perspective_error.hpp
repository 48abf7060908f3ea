// perspective_error.hpp: how far the affine and quadratic mappers stray from the exact
// perspective texture coordinate, in closed form.
//
// Usage:
//   double e = affine_error_bound(4.0) * 64.0;   // worst affine error, r = 4, 64 texels
//   double q = quadratic_error_max(4.0) * 64.0;  // worst quadratic error, same span
//
// A span runs from screen parameter t = 0 (depth w0) to t = 1 (depth w1), its texture
// coordinate from u0 to u0 + du. r = w1 / w0 > 0 is the span's depth ratio. Errors are
// given as a fraction of du (multiply by |du| for texels) and are the same for r and
// 1 / r (a span seen from its other end). Chapter 3 derives each formula.
#pragma once

namespace exactpixels {

/// The exact fraction of the span's texel extent reached at screen parameter t in
/// [0, 1]: t / (r - (r - 1) t) (@eq:exact-fraction).
double exact_fraction(double r, double t);

/// The affine mapper's error at t as a fraction of du: t - exact_fraction(r, t)
/// (@eq:affine-error). Positive for r > 1 (affine runs ahead of the exact value).
double affine_error(double r, double t);

/// The largest |affine_error(r, t)| over t in [0, 1]: (sqrt r - 1) / (sqrt r + 1) for
/// r >= 1 and the same with 1 / r for r < 1 (@eq:affine-bound). r > 0.
double affine_error_bound(double r);

/// Where the affine error is largest: t = sqrt r / (sqrt r + 1) (@eq:affine-worst-t).
double affine_worst_t(double r);

/// The quadratic (Pursey) mapper's error at t as a fraction of du: the parabola through
/// t = 0, 1/2, 1 minus the exact fraction,
/// 2 (r - 1)^2 t (t - 1/2) (1 - t) / ((r + 1) (r - (r - 1) t)) (@eq:quadratic-error).
double quadratic_error(double r, double t);

/// The largest |quadratic_error(r, t)| over t in [0, 1], found by a dense search refined
/// by golden-section steps (relative accuracy better than 1e-9). r > 0.
double quadratic_error_max(double r);

/// The largest depth ratio r >= 1 for which a mapper whose worst error is `fraction(r)`
/// (increasing in r) stays within `texels` over a span of extent `du` texels: bisection
/// to relative accuracy 1e-9. Returns +infinity if no r up to 1e12 exceeds it.
double largest_ratio_within(double (*fraction)(double), double du, double texels);

} // namespace exactpixels
