// row_runs.hpp: a triangle's coverage handed out as whole covered runs, one per row,
// found from the edge functions by division instead of by testing every pixel.
//
// Usage:
//   const EdgeSetup<FixedEdge> s = setup_edges(v);                  // chapter 2
//   traverse_runs(s, pixel_bounds(v, viewport), [&](Span run) {     // span.hpp
//       std::fill(row(run.y) + run.x_begin, row(run.y) + run.x_end, colour);
//   });
//
// On row y an edge value is linear in x: w(x) = w(x0) + (x - x0) step_x, so the pixels
// that pass one edge are a half line of columns, and those that pass all three are one
// run (a triangle is convex). The run holds exactly the pixels traverse_pixels emits on
// that row, bit for bit (tested); empty rows hand out nothing. Fixed point only.
#pragma once

#include "exactpixels/base/integer_division.hpp"
#include "exactpixels/raster/edge_function.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#include "exactpixels/raster/span.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace exactpixels {

//> run-of-row
/// The columns k = 0 .. n - 1 (offsets from the row's first pixel) that pass all three
/// edges, whose values at k = 0 are w: [k_begin, k_end), empty when k_begin >= k_end.
/// w + k step >= 0 is k >= ceil(-w / step) for step > 0 and k <= floor(w / -step) for
/// step < 0; a zero step passes every k or none.
inline std::pair<std::int64_t, std::int64_t>
run_of_row(const EdgeSetup<FixedEdge>& s, const std::array<std::int64_t, 3>& w, int n) {
    //> exercise ch09-run-of-row: each edge bounds k from one side (@eq:fast-run).
    std::int64_t k_begin = 0, k_end = n;
    for (std::size_t i = 0; i < 3; ++i) {
        const std::int64_t step = s.edge[i].step_x();
        if (step > 0) {
            k_begin = std::max(k_begin, ceil_div(-w[i], step));
        } else if (step < 0) {
            k_end = std::min(k_end, floor_div(w[i], -step) + 1);
        } else if (w[i] < 0) {
            return {0, 0};
        }
    }
    return {k_begin, k_end};
    //| (void)s, (void)w, (void)n;
    //| return {0, 0}; // stub: an empty run on every row, so nothing is drawn
    //< exercise ch09-run-of-row
}
//< run-of-row

//> run-of-row-fast
/// The fast variant of run_of_row (the same run; tested): the quotient is estimated in
/// double with a reciprocal computed once per triangle (inv[i] = 1 / |step_x|), clamped
/// to [0, n] and truncated, then corrected by exact integer tests, which move it a step
/// or two at most. No division and no floor or ceil (a library call without SSE4.1).
inline std::pair<std::int64_t, std::int64_t>
run_of_row_fast(const EdgeSetup<FixedEdge>& s, const std::array<std::int64_t, 3>& w,
                const std::array<double, 3>& inv, int n) {
    const double last = static_cast<double>(n);
    std::int64_t k_begin = 0, k_end = n;
    for (std::size_t i = 0; i < 3; ++i) {
        const std::int64_t step = s.edge[i].step_x();
        const auto passes = [&](std::int64_t k) { return w[i] + k * step >= 0; };
        const double estimate = static_cast<double>(w[i]) * inv[i]; // w / |step|
        if (step > 0) { // the first k that passes: about -estimate
            auto k = static_cast<std::int64_t>(std::clamp(-estimate, 0.0, last));
            while (k > 0 && passes(k - 1)) {
                --k;
            }
            while (k < n && !passes(k)) {
                ++k;
            }
            k_begin = std::max(k_begin, k);
        } else if (step < 0) { // one past the last k that passes: about estimate + 1
            auto k = static_cast<std::int64_t>(std::clamp(estimate + 1.0, 0.0, last));
            while (k < n && passes(k)) {
                ++k;
            }
            while (k > 0 && !passes(k - 1)) {
                --k;
            }
            k_end = std::min(k_end, k);
        } else if (w[i] < 0) {
            return {0, 0};
        }
    }
    return {k_begin, k_end};
}
//< run-of-row-fast

//> traverse-runs
/// Hands emit(Span) the covered run of every row of r that has one, top to bottom.
/// Each edge value is evaluated once at r's top-left pixel and stepped down the rows.
template <class SpanFn>
void traverse_runs(const EdgeSetup<FixedEdge>& s, PixelRect r, SpanFn&& emit) {
    if (r.empty()) {
        return;
    }
    std::array<std::int64_t, 3> w;
    for (std::size_t i = 0; i < 3; ++i) {
        w[i] = s.edge[i].at(r.x_begin, r.y_begin);
    }
    const int n = r.x_end - r.x_begin;
    for (int y = r.y_begin; y < r.y_end; ++y) {
        const auto [k_begin, k_end] = run_of_row(s, w, n);
        if (k_begin < k_end) {
            emit(Span{y, r.x_begin + static_cast<int>(k_begin),
                      r.x_begin + static_cast<int>(k_end)});
        }
        for (std::size_t i = 0; i < 3; ++i) {
            w[i] += s.edge[i].step_y();
        }
    }
}
//< traverse-runs

/// The fast variant of traverse_runs (the same runs; tested): run_of_row_fast, with
/// the reciprocals of the three steps computed once.
template <class SpanFn>
void traverse_runs_fast(const EdgeSetup<FixedEdge>& s, PixelRect r, SpanFn&& emit) {
    if (r.empty()) {
        return;
    }
    std::array<std::int64_t, 3> w;
    std::array<double, 3> inv;
    for (std::size_t i = 0; i < 3; ++i) {
        w[i] = s.edge[i].at(r.x_begin, r.y_begin);
        const std::int64_t step = s.edge[i].step_x();
        inv[i] = step == 0 ? 0.0 : 1.0 / static_cast<double>(step > 0 ? step : -step);
    }
    const int n = r.x_end - r.x_begin;
    for (int y = r.y_begin; y < r.y_end; ++y) {
        const auto [k_begin, k_end] = run_of_row_fast(s, w, inv, n);
        if (k_begin < k_end) {
            emit(Span{y, r.x_begin + static_cast<int>(k_begin),
                      r.x_begin + static_cast<int>(k_end)});
        }
        for (std::size_t i = 0; i < 3; ++i) {
            w[i] += s.edge[i].step_y();
        }
    }
}

} // namespace exactpixels
