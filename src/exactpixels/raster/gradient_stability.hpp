// gradient_stability.hpp: chapter 1's measurement of how accurately the split-edge and
// closed-form gradients come out when two vertices have almost the same y.
//
// Usage:
//   auto rows = gradient_stability_study(2000, 1);  // 2000 triangles per y-delta
//   for (const StabilityRow& r : rows) ...           // one row per (delta, precision)
//
// Each trial triangle has two vertices a small y-delta apart (nominally 1e-2 .. 1e-12
// px, or exactly 0) and the third 1 to 64 px above or below them; x spans up to 1000
// px, c lies in [0, 1]. Every input is a multiple of 2^-40 below 2^10 in magnitude (for
// the float trials also rounded to float, where a y-delta below the spacing of floats
// near y, 2^-17 .. 2^-14 px, becomes 0 or one spacing), and the reference is the exact
// gradient, a ratio of two integers (@eq:closed-form with integer inputs) kept as an
// exact Rational (exactpixels/base/exact.hpp). With an `origin`
// (chapter 1's Exercise 5) every x and y is moved by that many px before the rounding, so
// the same triangles lie near the origin instead (inputs then below 2^12 in magnitude).
// The error of a computed gradient g is the relative error of the vector: |g - g_exact| /
// |g_exact|, in units of the precision's machine epsilon (float 2^-23, double 2^-52),
// computed exactly and rounded once to double (its square; then a square root): the same
// numbers on every platform.
#pragma once

#include "exactpixels/base/exact.hpp"
#include "exactpixels/raster/gradients.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace exactpixels {

/// The measured error of both gradient methods for one y-delta and one precision.
struct StabilityRow {
    double y_delta = 0;       ///< the nominal y-delta between the two close vertices, px
    std::string precision;    ///< "float" or "double"
    int triangles = 0;        ///< trials measured
    double split_median = 0;  ///< split edge: median error, in machine epsilons
    double split_p99 = 0;     ///< split edge: 99th percentile of the error, in epsilons
    double split_max = 0;     ///< split edge: largest error, in machine epsilons
    double closed_median = 0; ///< closed form: median error, in machine epsilons
    double closed_p99 = 0;    ///< closed form: 99th percentile of the error, in epsilons
    double closed_max = 0;    ///< closed form: largest error, in machine epsilons
    int closed_better = 0;    ///< trials where the closed form was strictly more accurate
    int split_better = 0;     ///< trials where the split edge was strictly more accurate
};

/// The y-deltas the study measures, largest first; the last one is exactly 0.
std::vector<double> stability_y_deltas();

/// The exact gradient of the triangle (@eq:closed-form), each component an exact ratio
/// of two integers, with no rounding at all. Every input must be a multiple of 2^-40
/// with magnitude below 2^12 (asserted); zero area gives {0, 0}.
Gradient<Rational> exact_gradient(const PlaneSamples<double>& s);

/// The trial triangles for one y-delta: `count` of them from a fixed pseudo-random
/// sequence (`seed`), identical on every platform. Inputs obey exact_gradient's rule;
/// with `as_float` they are also exact floats (so the y-delta itself may round to 0).
/// `origin` (px, 0 to 3072) is added to every x and y before rounding: the same draws,
/// moved to where floats are coarser (up to 2^-12 px apart below 4096 px).
std::vector<PlaneSamples<double>> stability_triangles(double y_delta, int count,
                                                      std::uint64_t seed, bool as_float,
                                                      double origin = 0.0);

/// Runs the whole study: for each y-delta and for float and double, `count` triangles,
/// moved by `origin` px in x and y (see stability_triangles).
std::vector<StabilityRow> gradient_stability_study(int count, std::uint64_t seed,
                                                   double origin = 0.0);

/// The study as a Markdown table (the chapter pulls it in as a generated fragment).
std::string stability_table_markdown(const std::vector<StabilityRow>& rows);

} // namespace exactpixels
