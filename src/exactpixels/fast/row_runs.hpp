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
#include <cassert>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

namespace exactpixels {

//> run-of-row
/// The columns k = 0 .. n - 1 (offsets from the row's first pixel) that pass all three
/// edges, whose values at k = 0 are w: [k_begin, k_end), empty when k_begin >= k_end.
/// Each edge's w + k step >= 0 is a half line of k (@eq:fast-run); a zero step passes
/// every k or none.
inline std::pair<std::int64_t, std::int64_t>
run_of_row(const EdgeSetup<FixedEdge>& s, const std::array<std::int64_t, 3>& w, int n) {
    //> exercise ch10-run-of-row: each edge bounds k from one side (@eq:fast-run).
    // w + k step >= 0 is k >= ceil(-w / step) for step > 0, k <= floor(w / -step) for
    // step < 0.
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
    //< exercise ch10-run-of-row
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

//> run-end
/// One end of the covered runs, the crossing of one edge with s_x != 0, stepped down the
/// rows without a division (@eq:fast-step). With s = |s_x| and s_y = Q s + R,
/// 0 <= R < s: for s_x > 0, k is the first column that passes; for s_x < 0, one past
/// the last (@eq:fast-run). e in [0, s) is the edge's value at the
/// column k (s_x > 0) or k - 1 (s_x < 0), which tells when a row's step crosses one
/// column more than Q.
struct RunEnd {
    std::int64_t k = 0; ///< the end on the current row (a column offset, unclamped)
    std::int64_t e = 0; ///< the remainder, 0 <= e < s
    std::int64_t s = 1; ///< |s_x| > 0
    std::int64_t q = 0; ///< Q = floor(s_y / s)
    std::int64_t r = 0; ///< R = s_y - Q s
    /// Moves to the next row: k changes by Q or Q + 1 (carry), with no branch.
    /// `sign` is -1 for a first column (s_x > 0: k falls as w rises), +1 for an end.
    void step(std::int64_t sign) {
        const std::int64_t t = e + r - s;  // >= 0 exactly when e + R reaches s
        const std::int64_t keep = t >> 63; // -1 (no carry) or 0 (carry), arithmetic
        k += sign * (q + 1 + keep);        // Q + carry
        e = t + (keep & s);                // back into [0, s)
    }
};

/// The crossing of an edge whose value at column 0 of the row is w and whose steps are
/// s_x != 0 and s_y (@eq:fast-run, one exact division each, once per triangle).
inline RunEnd run_end(std::int64_t w, std::int64_t step_x, std::int64_t step_y) {
    RunEnd end;
    end.s = step_x > 0 ? step_x : -step_x;
    end.q = floor_div(step_y, end.s);
    end.r = step_y - end.q * end.s;
    //> gives-away ch10-run-of-row
    if (step_x > 0) {
        end.k = ceil_div(-w, end.s);
        end.e = w + end.k * end.s;
    } else {
        end.k = floor_div(w, end.s) + 1;
        end.e = w - (end.k - 1) * end.s;
    }
    //| (void)w; // stub: k = e = 0, the end not found
    //< gives-away ch10-run-of-row
    return end;
}
//< run-end

/// floor(a / s) and a - floor(a / s) s for s > 0 (floor_div's quotient; tested), without
/// an integer division when |a| < 2^50: inv = 1 / s rounds once and a * inv once, each by
/// a relative 2^-53, so a * inv is within |a| 2^-51 < 1/2 of a / s; rounded to the nearest
/// integer (adding and subtracting 1.5 * 2^52) it is floor(a / s) or one more, which the
/// sign of the remainder tells. A 64-bit division costs tens of cycles; this, a few.
inline std::pair<std::int64_t, std::int64_t> floor_div_near(std::int64_t a, std::int64_t s,
                                                            double inv) {
    constexpr std::int64_t near_limit = std::int64_t{1} << 50;
    if (a <= -near_limit || a >= near_limit) { // beyond the bound: the exact division
        const std::int64_t r = a % s; // a - q s with q = floor(a / s) could overflow
        return {floor_div(a, s), r < 0 ? r + s : r};
    }
    constexpr double round = 0x1.8p52; // 1.5 * 2^52: sums keep no fraction bits
    const double nearest = (static_cast<double>(a) * inv + round) - round;
    const std::int64_t q = static_cast<std::int64_t>(nearest); // floor(a / s) + {0, 1}
    const std::int64_t r = a - q * s;                           // in [-s, s)
    const std::int64_t over = r >> 63; // -1 when q is one too many, else 0
    return {q + over, r + (over & s)};
}

/// The fast variant of run_end (the same end; tested): one reciprocal in double instead
/// of two 64-bit divisions, both quotients by floor_div_near.
inline RunEnd run_end_fast(std::int64_t w, std::int64_t step_x, std::int64_t step_y) {
    RunEnd end;
    end.s = step_x > 0 ? step_x : -step_x;
    const double inv = 1.0 / static_cast<double>(end.s);
    std::tie(end.q, end.r) = floor_div_near(step_y, end.s, inv);
    //> gives-away ch10-run-of-row
    const auto [f, e] = floor_div_near(w, end.s, inv); // f = floor(w / s), e = w - f s
    end.k = step_x > 0 ? -f : f + 1;                    // as run_end's k, either sign
    end.e = e;
    //| (void)w, (void)inv; // stub: k = e = 0, the end not found
    //< gives-away ch10-run-of-row
    return end;
}

//> traverse-runs-stepped
/// The stepped variant of traverse_runs (the same runs; tested): every crossing is
/// found once, on r's first row (run_end_fast), and stepped down the rows by RunEnd::step. A
/// horizontal edge (s_x = 0) keeps or removes whole rows, so it narrows the rows
/// instead. At most two edges bound each side (the three s_x sum to zero); a missing
/// one is a RunEnd that stays at 0 (first column) or n (end).
template <class SpanFn>
void traverse_runs_stepped(const EdgeSetup<FixedEdge>& s, PixelRect r, SpanFn&& emit) {
    if (r.empty()) {
        return;
    }
    int y_begin = r.y_begin, y_end = r.y_end;
    for (const FixedEdge& edge : s.edge) { // horizontal edges: the rows that pass
        const std::int64_t sy = edge.step_y(), w = edge.at(r.x_begin, r.y_begin);
        if (edge.step_x() != 0) {
            continue;
        }
        if (sy != 0) { // down the rows w changes by s_y: an end, as run_end finds it
            const std::int64_t row = r.y_begin + run_end(w, sy, 0).k;
            (sy > 0 ? y_begin : y_end) =
                static_cast<int>(std::clamp<std::int64_t>(row, y_begin, y_end));
        } else if (w < 0) {
            return;
        }
    }
    const int n = r.x_end - r.x_begin;
    std::array<RunEnd, 2> first{}, end{}; // first columns (s_x > 0), ends (s_x < 0)
    end[0].k = end[1].k = n;
    std::size_t firsts = 0, ends = 0;
    for (const FixedEdge& edge : s.edge) {
        const std::int64_t sx = edge.step_x();
        if (sx == 0) {
            continue;
        }
        const RunEnd e = run_end_fast(edge.at(r.x_begin, y_begin), sx, edge.step_y());
        assert(sx > 0 ? firsts < 2 : ends < 2); // the three s_x sum to zero
        (sx > 0 ? first[firsts++] : end[ends++]) = e;
    }
    // The rows, with the number of ends of each side known to the compiler: (2, 1),
    // (1, 2), or (1, 1) with a horizontal edge, so that no unused end is stepped.
    const auto rows = [&]<std::size_t F, std::size_t E>() {
        for (int y = y_begin; y < y_end; ++y) {
            std::int64_t k_begin = 0, k_end = n;
            for (std::size_t i = 0; i < F; ++i) {
                k_begin = std::max(k_begin, first[i].k);
                first[i].step(-1);
            }
            for (std::size_t i = 0; i < E; ++i) {
                k_end = std::min(k_end, end[i].k);
                end[i].step(1);
            }
            if (k_begin < k_end) {
                emit(Span{y, r.x_begin + static_cast<int>(k_begin),
                          r.x_begin + static_cast<int>(k_end)});
            }
        }
    };
    if (firsts == 2 && ends == 1) {
        rows.template operator()<2, 1>();
    } else if (firsts == 1 && ends == 2) {
        rows.template operator()<1, 2>();
    } else if (firsts == 1 && ends == 1) {
        rows.template operator()<1, 1>();
    } else {
        rows.template operator()<2, 2>(); // fewer: the missing ends stay at 0 and n
    }
}
//< traverse-runs-stepped

} // namespace exactpixels
