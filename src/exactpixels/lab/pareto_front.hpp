// pareto_front.hpp: chapter 5's Pareto front of mapper settings over three measures,
// time, worst texel error and wrong texels at ties, with times compared within the
// noise of the run that measured them.
//
// Usage:
//   const double noise = repetition_noise({{7.10, 7.32, 7.15}, {3.81, 3.90, 3.86}});
//   std::vector<Setting> s = {{3.82, 0.0, 29952}, {3.81, 0.0, 0}};
//   std::vector<int> n = beaten_by(s, noise);   // n[k] == 0: s[k] is on the front
//
// Times are in any one unit (ns per pixel, or ratios to one baseline), all > 0. noise
// is relative, >= 0: two times t and t' are tied when max(t, t') <= (1 + noise) *
// min(t, t'), so a difference the run cannot tell from its own scatter ranks nothing.
// Errors are exact (deterministic counts and texel distances): they compare as they are.
#pragma once

#include <cstdint>
#include <vector>

namespace exactpixels {

/// One setting's three measures.
struct Setting {
    double time = 0.0;              ///< per pixel, > 0 (one unit for all settings)
    double worst = 0.0;             ///< worst texel error, texels
    std::int64_t wrong_at_ties = 0; ///< pixels at ties whose texel differs
};

/// True when the times are within the noise of each other (@eq:time-tie).
bool tied_in_time(double t, double t_other, double noise);

/// True when `b` beats `a` (@eq:pareto): at least as good on all three measures (time
/// within the noise counts as equal) and better on one (time: faster beyond the noise).
bool beats(const Setting& b, const Setting& a, double noise);

/// For each setting, how many others beat it; the front is the settings beaten by none.
/// Never empty: with noise >= 0 no chain of beats returns to where it began.
std::vector<int> beaten_by(const std::vector<Setting>& settings, double noise);

/// The noise of a repeated run: for each benchmark, its slowest repetition over its
/// fastest, minus 1; the median of that over the benchmarks. Error when a benchmark has
/// fewer than two repetitions, a time that is not > 0, or there are none.
double repetition_noise(const std::vector<std::vector<double>>& repetitions);

} // namespace exactpixels
