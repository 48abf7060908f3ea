// Chapter 10 tests: every fast variant draws exactly the pixels of chapter 2's pixel walk
// (traverse_pixels), on the random, tie, mesh and fan sets of chapter 2 and the hard
// cases of chapter 6 (slivers, the fixed-point limit); the SIMD lanes agree with the
// portable ones; the tiled renderer's picture does not depend on the thread count; the
// textured runs draw the texels of chapter 3's exact mapper under perspective.
#include "ch02_grid.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/fast/block_masks.hpp"
#include "exactpixels/fast/depth_lanes.hpp"
#include "exactpixels/fast/row_runs.hpp"
#include "exactpixels/fast/sign_lanes.hpp"
#include "exactpixels/fast/sign_lanes4.hpp"
#include "exactpixels/fast/textured_runs.hpp"
#include "exactpixels/fast/tiled_rasterizer.hpp"
#include "exactpixels/fast/tiny_triangle.hpp"
#include "support/printing.hpp"
#include "support/meshes.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <type_traits>

using namespace exactpixels;
using ch02::Grid;

namespace {

/// The fast traversals of this chapter, by name.
enum class Fast { runs, runs_fast, runs_stepped, masks_portable, masks_sse2 };

// The plain traversal_runs is the exercise ch10-run-of-row: its own test below.
constexpr Fast all_fast[] = {Fast::runs_fast, Fast::runs_stepped, Fast::masks_portable,
                             Fast::masks_sse2};

const char* name_of(Fast f) {
    switch (f) {
    case Fast::runs:
        return "runs";
    case Fast::runs_fast:
        return "runs (fast)";
    case Fast::runs_stepped:
        return "runs (stepped ends)";
    case Fast::masks_portable:
        return "8x8 masks (portable lanes)";
    case Fast::masks_sse2:
        return "8x8 masks (SSE2 lanes)";
    }
    return "?";
}

/// Counts every pixel fast traversal f hands out for the snapped triangle v into g.
void draw_fast(Grid& g, const std::array<FixedPoint2, 3>& v, Fast f) {
    check_fixed_triangle(v);
    const EdgeSetup<FixedEdge> s = setup_edges(v);
    if (s.empty) {
        return;
    }
    const PixelRect r = pixel_bounds(v, g.viewport());
    const auto run = [&](Span sp) {
        CHECK(sp.x_begin < sp.x_end); // no empty run is handed out
        for (int x = sp.x_begin; x < sp.x_end; ++x) {
            g.hit(x, sp.y);
        }
    };
    const auto mask = [&](BlockMask m) {
        CHECK(m.bits != 0); // no empty block is handed out
        for_each_pixel(m, [&](int x, int y) { g.hit(x, y); });
    };
    switch (f) {
    case Fast::runs:
        traverse_runs(s, r, run);
        break;
    case Fast::runs_fast:
        traverse_runs_fast(s, r, run);
        break;
    case Fast::runs_stepped:
        traverse_runs_stepped(s, r, run);
        break;
    case Fast::masks_portable:
        traverse_block_masks<lanes::Portable>(s, r, mask);
        break;
    case Fast::masks_sse2:
#if defined(__SSE2__)
        traverse_block_masks<lanes::Sse2>(s, r, mask);
#else
        traverse_block_masks<lanes::Portable>(s, r, mask);
#endif
        break;
    }
}

/// Pixels where fast traversal f and the pixel walk differ, over a set of triangles
/// each drawn alone into a width x height frame.
int mismatches(const std::vector<std::array<FixedPoint2, 3>>& set, int width, int height,
               Fast f) {
    int wrong = 0;
    for (const auto& v : set) {
        Grid walk{width, height}, fast{width, height};
        ch02::draw(walk, v, ch02::Raster::pixels_fixed);
        draw_fast(fast, v, f);
        for (std::size_t k = 0; k < walk.count.size(); ++k) {
            wrong += walk.count[k] != fast.count[k];
        }
        wrong += fast.outside;
    }
    return wrong;
}

std::vector<std::array<FixedPoint2, 3>> random_set(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<std::array<FixedPoint2, 3>> set;
    for (int trial = 0; trial < ch02::trials; ++trial) {
        // Slivers to triangles larger than the frame; every fourth on the half-pixel
        // grid, where only the fill rule decides.
        const double spread = trial % 3 == 0 ? 8.0 : trial % 3 == 1 ? 40.0 : 300.0;
        set.push_back(trial % 4 == 3 ? ch02::random_tie_triangle(rng, -10, 140)
                                     : ch02::random_triangle(rng, -spread / 4, spread));
    }
    return set;
}

} // namespace

TEST_CASE("runs and 8x8 masks draw the pixel walk's pixels on random triangles") {
    const auto set = random_set(91);
    for (const Fast f : all_fast) {
        INFO(name_of(f));
        CHECK(mismatches(set, 130, 90, f) == 0);
    }
}

TEST_CASE("runs and 8x8 masks draw the pixel walk's pixels on meshes and the fan") {
    std::mt19937_64 rng(92);
    std::uniform_real_distribution<double> wobble(-3.0, 3.0);
    const auto jittered = [&](int, int) { return Point2{wobble(rng), wobble(rng)}; };
    const auto none = [](int, int) { return Point2{0, 0}; };
    const auto mesh = testing::grid_mesh({2.3, 1.7}, 8, 8.0, jittered);
    const auto centred = testing::grid_mesh({2.5, 2.5}, 11, 6.0, none);
    const auto fan = testing::sliver_fan({36.5, 36.5}, 33.0, 720);
    for (const Fast f : all_fast) {
        INFO(name_of(f));
        CHECK(mismatches(mesh, 72, 72, f) == 0);
        CHECK(mismatches(centred, 72, 72, f) == 0);
        CHECK(mismatches(fan, 72, 72, f) == 0);
    }
}

TEST_CASE("runs and 8x8 masks are exact on slivers and at the fixed-point limit") {
    // Chapter 6's wedges, 1/16 to 1/2 px wide over 600 px, and triangles whose far
    // vertices sit at +-max_fixed_coordinate, where edge values need all 64 bits.
    std::vector<std::array<FixedPoint2, 3>> hard;
    for (const double width : {1.0 / 16, 1.0 / 4, 1.0 / 2}) {
        hard.push_back(
            ch02::snap3({10.25, 3.5}, {610.75, 190.25}, {610.75 + width, 190.25}));
    }
    const std::int64_t m = max_fixed_coordinate;
    hard.push_back({FixedPoint2{-m, -m}, FixedPoint2{m, -m + 3}, FixedPoint2{100, m}});
    hard.push_back({FixedPoint2{m, m}, FixedPoint2{-m, 7000}, FixedPoint2{9000, -m}});
    hard.push_back({FixedPoint2{-m, 5 * 256 + 128}, FixedPoint2{m, 5 * 256 + 128},
                    FixedPoint2{m, 6 * 256}}); // a top edge through a row of centres
    for (const Fast f : all_fast) {
        INFO(name_of(f));
        CHECK(mismatches(hard, 640, 200, f) == 0);
    }
}

TEST_CASE("covered runs by exact division are the pixel walk's runs on every set" *
          doctest::description("points: 20; exercise: ch10-run-of-row")) {
    std::mt19937_64 rng(95);
    std::uniform_real_distribution<double> wobble(-3.0, 3.0);
    const auto jittered = [&](int, int) { return Point2{wobble(rng), wobble(rng)}; };
    std::vector<std::array<FixedPoint2, 3>> hard;
    const std::int64_t m = max_fixed_coordinate;
    hard.push_back(ch02::snap3({10.25, 3.5}, {610.75, 190.25}, {610.8125, 190.25}));
    hard.push_back({FixedPoint2{-m, -m}, FixedPoint2{m, -m + 3}, FixedPoint2{100, m}});
    CHECK(mismatches(random_set(96), 130, 90, Fast::runs) == 0);
    CHECK(mismatches(testing::grid_mesh({2.3, 1.7}, 8, 8.0, jittered), 72, 72,
                     Fast::runs) == 0);
    CHECK(mismatches(testing::sliver_fan({36.5, 36.5}, 33.0, 720), 72, 72, Fast::runs) ==
          0);
    CHECK(mismatches(hard, 640, 200, Fast::runs) == 0);
}

TEST_CASE("a run end stepped by quotient, remainder and carry is the exact division on "
          "every row") {
    // @eq:fast-step: RunEnd::step moves an edge's first column (s_x > 0) or end of run
    // (s_x < 0) down the rows without a division. On every row its column k and its
    // remainder e must be what run_end's exact divisions give for that row's value w,
    // and e must stay in [0, s). Steps of both signs, from 1 to 2^37 (the largest step
    // of a fixed-point edge), quotients Q from -4 to 4, values up to 2^59; rows with a
    // carry and rows without are both common.
    std::mt19937_64 rng(102);
    const auto between = [&](std::int64_t lo, std::int64_t hi) {
        return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
    };
    const std::int64_t s_max[] = {8, std::int64_t{1} << 20, std::int64_t{1} << 37};
    const std::int64_t w_max[] = {200, std::int64_t{1} << 40, std::int64_t{1} << 59};
    long carries = 0, plain = 0, negative_q = 0;
    for (int trial = 0; trial < 30000; ++trial) {
        const std::size_t scale = static_cast<std::size_t>(trial % 3);
        const std::int64_t s = between(1, s_max[scale]);
        const std::int64_t s_x = trial % 2 ? s : -s;
        const std::int64_t s_y = between(-4 * s, 4 * s);
        std::int64_t w = between(-w_max[scale], w_max[scale]);
        RunEnd end = run_end(w, s_x, s_y);
        negative_q += end.q < 0;
        for (int row = 0; row < 64; ++row) {
            // The exact end on this row, and the edge's value there (s_x > 0) or at the
            // last column that passes (s_x < 0), as run_end divides them out.
            const std::int64_t k = s_x > 0 ? ceil_div(-w, s) : floor_div(w, s) + 1;
            const std::int64_t e = s_x > 0 ? w + k * s : w - (k - 1) * s;
            CAPTURE(s_x);
            CAPTURE(s_y);
            CAPTURE(w);
            CAPTURE(row);
            REQUIRE(end.k == k);
            REQUIRE(end.e == e);
            REQUIRE((0 <= end.e && end.e < s));
            (end.e + end.r >= s ? carries : plain) += 1;
            end.step(s_x > 0 ? -1 : 1);
            w += s_y;
        }
    }
    CHECK(carries > 500000); // rows where the end moves by Q + 1
    CHECK(plain > 500000);   // and by Q
    CHECK(negative_q > 10000);
}

TEST_CASE("floor_div_near divides exactly without a division, up to the int64 extremes") {
    // run_end_fast's quotient: floor_div's quotient and remainder, for divisors from 1 to
    // 2^40 (a fixed-point edge's steps reach 2^37) and dividends of every size, on both
    // sides of the 2^50 where the estimate gives way to the division, near the int64
    // extremes, and the hardest for the estimate: a remainder of 0, 1 or s - 1, where
    // a / s lies on or next to an integer.
    std::mt19937_64 rng(1050);
    const auto between = [&](std::int64_t lo, std::int64_t hi) {
        return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
    };
    const std::int64_t limit = std::int64_t{1} << 50;
    const std::int64_t big = std::numeric_limits<std::int64_t>::max() / 2;
    long checked = 0;
    const auto check = [&](std::int64_t a, std::int64_t s) {
        const auto [q, r] = floor_div_near(a, s, 1.0 / static_cast<double>(s));
        CAPTURE(a);
        CAPTURE(s);
        REQUIRE(q == floor_div(a, s));
        // a - q s modulo 2^64 (near the int64 extremes q s itself leaves int64): the
        // remainder lies in [0, s), so the wrapped difference is it
        const std::uint64_t wrapped =
            static_cast<std::uint64_t>(a) -
            static_cast<std::uint64_t>(floor_div(a, s)) * static_cast<std::uint64_t>(s);
        REQUIRE(r == static_cast<std::int64_t>(wrapped));
        ++checked;
    };
    const std::int64_t s_max[] = {8, std::int64_t{1} << 20, std::int64_t{1} << 37,
                                  std::int64_t{1} << 40};
    for (int trial = 0; trial < 200000; ++trial) {
        const std::int64_t s = between(1, s_max[trial % 4]);
        const int bits = static_cast<int>(between(0, 62));
        const std::int64_t a_max = bits == 62 ? big : (std::int64_t{1} << bits);
        check(between(-a_max, a_max), s);
        // a = m s + rest near a multiple, with |a| up to just past 2^50
        const std::int64_t m = between(-(limit + 4 * s) / s, (limit + 4 * s) / s);
        for (const std::int64_t rest : {std::int64_t{0}, std::int64_t{1}, s - 1}) {
            check(m * s + rest, s);
        }
        // the dividends on both sides of the bound
        const std::int64_t edge = trial % 2 ? limit : -limit;
        check(edge + between(-3, 3), s);
    }
    for (const std::int64_t s : {std::int64_t{1}, std::int64_t{2}, std::int64_t{3},
                                 std::int64_t{7}, (std::int64_t{1} << 37) - 1}) {
        for (const std::int64_t a :
             {std::numeric_limits<std::int64_t>::min() + 1,
              std::numeric_limits<std::int64_t>::max(), limit - 1, -(limit - 1), limit,
              -limit, std::int64_t{0}, std::int64_t{-1}}) {
            check(a, s);
        }
    }
    CHECK(checked > 1000000);
}

TEST_CASE("run_end_fast starts every end where run_end's divisions do") {
    // The first row of traverse_runs_stepped: the same column, remainder, quotient and
    // remainder of s_y as run_end, for steps of both signs from 1 to 2^37 and values up
    // to 2^60 (@eq:edge-range), across the 2^50 where floor_div_near divides.
    std::mt19937_64 rng(1051);
    const auto between = [&](std::int64_t lo, std::int64_t hi) {
        return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
    };
    for (int trial = 0; trial < 200000; ++trial) {
        const std::int64_t s = between(1, std::int64_t{1} << between(0, 37));
        const std::int64_t s_x = trial % 2 ? s : -s;
        const std::int64_t s_y = between(-(std::int64_t{1} << 37), std::int64_t{1} << 37);
        const std::int64_t w_max = std::int64_t{1} << between(0, 60);
        const std::int64_t w = between(-w_max, w_max);
        const RunEnd exact = run_end(w, s_x, s_y), fast = run_end_fast(w, s_x, s_y);
        CAPTURE(w);
        CAPTURE(s_x);
        CAPTURE(s_y);
        REQUIRE(fast.k == exact.k);
        REQUIRE(fast.e == exact.e);
        REQUIRE(fast.s == exact.s);
        REQUIRE(fast.q == exact.q);
        REQUIRE(fast.r == exact.r);
    }
}

TEST_CASE(
    "the double estimate of a run's end is one column off below 2^52, two up to 2^60") {
    // Exercise 2 of chapter 10: run_of_row_fast starts each edge's end from the double
    // estimate w * (1 / |s_x|), clamped to the row and truncated, as below. For
    // |w| < 2^52 the start is at most one column from the exact end (computed here in
    // exact integers); above, up to the 2^60 of @eq:edge-range, an edge with s_x > 0
    // whose quotient lies just above an integer can start two columns short, and one
    // with s_x < 0 is never more than one column off. Both worst cases occur.
    std::mt19937_64 rng(97);
    const auto below = [&](std::int64_t limit) {
        return static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(limit));
    };
    const auto floor_div = [](const Integer& a, const Integer& b) { // b > 0
        return a >= 0 ? Integer{a / b} : Integer{-((-a + b - 1) / b)};
    };
    int worst_small = 0, worst_rising = 0, worst_falling = 0;
    long near_2_60 = 0;
    for (int trial = 0; trial < 400000; ++trial) {
        const std::int64_t n = 1 + below(std::int64_t{1} << 20);
        const int bits[] = {12, 30, 40};
        const std::int64_t s = 1 + below(std::int64_t{1} << bits[trial % 3]);
        // A quotient in or just beyond the row, with a remainder that is 0, 1, s - 1 or
        // anything, so that integer quotients and their neighbours occur.
        const std::int64_t q = below(n + 5) - 2;
        const std::int64_t r_choice[] = {0, 1, s - 1, below(s)};
        const std::int64_t r = std::max<std::int64_t>(0, r_choice[(trial / 3) % 4]);
        const Integer w_wide = Integer{q} * s + r;
        if (w_wide >= (Integer{1} << 60) || w_wide <= -(Integer{1} << 60)) {
            continue;
        }
        near_2_60 += w_wide >= (Integer{1} << 59);
        const bool small = w_wide < (Integer{1} << 52) && w_wide > -(Integer{1} << 52);
        const double inv = 1.0 / static_cast<double>(s);
        const double last = static_cast<double>(n);
        for (const bool rising : {true, false}) {
            // rising: step_x = s > 0 and w = -w_wide, the first k with w + k s >= 0;
            // falling: step_x = -s and w = w_wide, one past the last k with w - k s >= 0.
            const auto w = (rising ? -w_wide : w_wide).convert_to<std::int64_t>();
            const double estimate = static_cast<double>(w) * inv;
            const auto start =
                static_cast<std::int64_t>(rising ? std::clamp(-estimate, 0.0, last)
                                                 : std::clamp(estimate + 1.0, 0.0, last));
            const Integer exact =
                rising ? -floor_div(-w_wide, Integer{s}) // ceil(w_wide / s)
                       : floor_div(w_wide, Integer{s}) + 1;
            const auto clamped =
                static_cast<std::int64_t>(std::clamp<Integer>(exact, 0, Integer{n}));
            const auto distance = static_cast<int>(std::abs(start - clamped));
            CAPTURE(w);
            CAPTURE(s);
            CAPTURE(n);
            CAPTURE(rising);
            REQUIRE(distance <= (small || !rising ? 1 : 2));
            int& worst = small ? worst_small : rising ? worst_rising : worst_falling;
            worst = std::max(worst, distance);
        }
    }
    CHECK(worst_small == 1);   // below 2^52 truncation alone misses by one
    CHECK(worst_rising == 2);  // above, the bound of two is reached
    CHECK(worst_falling == 1); // and the other direction stays within one
    CHECK(near_2_60 > 1000);   // edge values near the top of the range were tried
}

namespace {

/// The bits lanes L compute for three edges whose values in lane i are w[k] + i s[k].
template <class L, class T> unsigned lane_bits(const T (&w)[3], const T (&s)[3]) {
    return ((L::broadcast(w[0]) + L::ramp(s[0])) | (L::broadcast(w[1]) + L::ramp(s[1])) |
            (L::broadcast(w[2]) + L::ramp(s[2])))
        .nonnegative_bits();
}

/// The same bits by their definition, one lane at a time, for `lanes` lanes.
template <class T> unsigned defined_bits(const T (&w)[3], const T (&s)[3], int lanes) {
    unsigned bits = 0;
    for (int i = 0; i < lanes; ++i) {
        bits |=
            unsigned{w[0] + i * s[0] >= 0 && w[1] + i * s[1] >= 0 && w[2] + i * s[2] >= 0}
            << i;
    }
    return bits;
}

} // namespace

TEST_CASE("SSE2 lanes compute the portable lanes' bits, up to the int64 extremes") {
    // Rows of values near zero (mixed masks), values across the 2^60 of @eq:edge-range
    // and beyond, and values anywhere in int64, the extremes themselves included, whose
    // steps point towards zero so that no lane's sum leaves int64.
    using Limits = std::numeric_limits<std::int64_t>;
    std::mt19937_64 rng(93);
    std::uniform_int_distribution<std::int64_t> value(-(std::int64_t{1} << 61),
                                                      std::int64_t{1} << 61);
    std::uniform_int_distribution<std::int64_t> anywhere(Limits::min(), Limits::max());
    std::uniform_int_distribution<std::int64_t> step(-(std::int64_t{1} << 40),
                                                     std::int64_t{1} << 40);
    int all_mixed = 0, extremes = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        std::int64_t w[3], s[3];
        for (std::size_t k = 0; k < 3; ++k) {
            s[k] = step(rng) >> (trial % 40);
            if (trial % 4 == 3) { // anywhere; every eighth row starts at min, max, any
                const std::int64_t first[] = {Limits::min(), Limits::max(),
                                              anywhere(rng)};
                w[k] = trial % 8 == 3 ? first[k] : anywhere(rng);
                s[k] = w[k] < 0 ? std::abs(s[k]) : -std::abs(s[k]);
            } else { // near zero half the time, so that masks come out mixed
                w[k] = trial % 2 ? value(rng) : value(rng) >> 40;
            }
        }
        extremes += w[0] == Limits::min() && w[1] == Limits::max();
        const unsigned portable = lane_bits<lanes::Portable>(w, s);
        REQUIRE(portable == defined_bits(w, s, 8));
#if defined(__SSE2__)
        REQUIRE(lane_bits<lanes::Sse2>(w, s) == portable);
#endif
        all_mixed += portable != 0 && portable != 0xff;
    }
    CHECK(all_mixed > 1000); // the test saw many partly covered rows
    CHECK(extremes == 2500); // and rows that start at both extremes of int64
}

TEST_CASE("depth lanes write plot's depth bits and colours, four pixels at a time") {
    // Random depth planes over rows of 40 pixels of stored depths (many of them exactly
    // the plane's own z, so that ties, which must not draw, are common; some +-0, some
    // infinities, some the largest finite float, some NaN, which never draws), every run
    // [x_begin, x_end) and every 8-pixel mask row of each, drawn by both implementations
    // and by plot's definition one pixel at a time (z = plane.at(x, y), drawn when z <
    // stored): the same depth bits and colours.
    std::mt19937_64 rng(95);
    constexpr int width = 40;
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> kind(0, 9), column(0, width), row_of(0, 4095);
    const float big = std::numeric_limits<float>::max();
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float edge_values[] = {0.0f, -0.0f, inf, -inf, big, -big, 1.0f, 0.5f, nan};
    const Rgba8 paint = rgba(10, 200, 30, 77), ground = rgba(1, 2, 3, 4);
    const auto bits_of = [](const std::vector<float>& d) {
        std::vector<std::uint32_t> b;
        for (const float z : d) {
            b.push_back(std::bit_cast<std::uint32_t>(z));
        }
        return b;
    };
    int drawn = 0, kept = 0, ties = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        // Gradients from tiny to steep, a row far down half the time.
        const float scale = std::ldexp(1.0f, trial % 24 - 16);
        const DepthPlane plane{unit(rng), unit(rng) * scale, unit(rng) * scale};
        const int y = trial % 2 ? row_of(rng) : trial % 7;
        std::vector<float> stored(width);
        for (int x = 0; x < width; ++x) {
            const int k = kind(rng);
            stored[static_cast<std::size_t>(x)] =
                k < 3   ? plane.at(x, y)
                : k < 5 ? edge_values[static_cast<std::size_t>(trial + x) % 9]
                        : plane.at(x, y) + unit(rng) * scale;
        }
        // One case: a run [b, e) or a mask row (8 pixels from a multiple of 8, random
        // bits), drawn by `draw` into fresh copies of the row.
        int b = column(rng), e = column(rng);
        if (b > e) {
            std::swap(b, e);
        }
        const int mask_x = 8 * (trial % (width / 8));
        const auto bits = static_cast<std::uint8_t>(rng());
        const bool as_mask = trial % 3 == 0;
        const auto wanted = [&](int x) {
            return as_mask ? x >= mask_x && x < mask_x + 8 && (bits >> (x - mask_x) & 1)
                           : x >= b && x < e;
        };
        const auto draw = [&](auto lanes_type) {
            using L = typename decltype(lanes_type)::type;
            std::vector<float> d = stored;
            std::vector<Rgba8> c(width, ground);
            if (as_mask) {
                // width 37 for the last block: its second half goes pixel by pixel
                const int w = mask_x + 8 == width ? width - 3 : width;
                const auto clipped =
                    static_cast<std::uint8_t>(mask_x + 8 == width ? bits & 0x1f : bits);
                depth_mask_row<L>(plane, paint, y, mask_x, clipped, w, d.data(),
                                  c.data());
            } else {
                depth_run<L>(plane, paint, y, b, e, d.data(), c.data());
            }
            return std::pair{bits_of(d), c};
        };
        std::vector<float> d = stored;
        std::vector<Rgba8> c(width, ground);
        for (int x = 0; x < width; ++x) {
            const bool in =
                wanted(x) && !(as_mask && mask_x + 8 == width && x >= width - 3);
            if (!in) {
                continue;
            }
            ++kept;
            const std::size_t i = static_cast<std::size_t>(x);
            const float z = plane.at(x, y); // plot, pixel by pixel
            ties += z == d[i];
            if (z < d[i]) {
                d[i] = z;
                c[i] = paint;
                ++drawn;
            }
        }
        const auto expected = std::pair{bits_of(d), c};
        REQUIRE(draw(std::type_identity<depth_lanes::Portable>{}) == expected);
#if defined(__SSE2__)
        REQUIRE(draw(std::type_identity<depth_lanes::Sse2>{}) == expected);
#endif
    }
    CHECK(drawn > kept / 4);     // many pixels drawn,
    CHECK(drawn < 3 * kept / 4); // many not,
    CHECK(ties > kept / 10);     // and many of those not drawn were ties
}

TEST_CASE("fill_run writes exactly its run, whatever its length and alignment") {
    const Rgba8 colour = rgba(12, 34, 56, 78), background = rgba(1, 2, 3, 4);
    for (int offset = 0; offset < 4; ++offset) {
        for (int count = 0; count <= 70; ++count) {
            std::vector<Rgba8> row(80, background);
            fill_run(row.data() + offset, count, colour);
            for (int x = 0; x < 80; ++x) {
                const bool inside = x >= offset && x < offset + count;
                REQUIRE(row[static_cast<std::size_t>(x)] ==
                        (inside ? colour : background));
            }
        }
    }
}

TEST_CASE("four int32 SSE2 lanes compute the portable lanes' bits") {
    std::mt19937_64 rng(98);
    std::uniform_int_distribution<std::int32_t> value(-(1 << 29), 1 << 29);
    std::uniform_int_distribution<std::int32_t> step(-(1 << 21), 1 << 21);
    int mixed = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        // Values as large as the steps half the time, so that bits come out mixed.
        const int shift = trial % 24, near = trial % 2 == 0 ? shift : shift + 8;
        const std::int32_t w[3] = {value(rng) >> near, value(rng) >> near,
                                   value(rng) >> near};
        const std::int32_t s[3] = {step(rng) >> shift, step(rng) >> shift,
                                   step(rng) >> shift};
        const unsigned portable = lane_bits<lanes4::Portable>(w, s);
        REQUIRE(portable == defined_bits(w, s, 4));
#if defined(__SSE2__)
        REQUIRE(lane_bits<lanes4::Sse2>(w, s) == portable);
#endif
        mixed += portable != 0 && portable != 0xf;
    }
    CHECK(mixed > 1000);
}

namespace {

/// The pixels traverse_tiny with lanes L hands out for v, in order, or those of the
/// pixel walk (walk = true), over a viewport big enough for any fixed-point vertex.
template <class L>
std::vector<std::pair<int, int>> tiny_pixels(const std::array<FixedPoint2, 3>& v,
                                             Viewport viewport, bool walk) {
    std::vector<std::pair<int, int>> pixels;
    auto emit = [&](int x, int y) { pixels.emplace_back(x, y); };
    const PixelRect r = pixel_bounds(v, viewport);
    if (walk) {
        const EdgeSetup<FixedEdge> s = setup_edges(v);
        if (!s.empty) {
            traverse_pixels(s, r, emit);
        }
    } else {
        traverse_tiny<L>(v, r, emit);
    }
    return pixels;
}

} // namespace

TEST_CASE("tiny triangles in int32 lanes draw the pixel walk's pixels up to 32 px") {
    // Random triangles up to the 32 px limit, ties on the half-pixel grid, clipped by the
    // frame's edges, and far out at the fixed-point limit (in a viewport that reaches
    // it), against traverse_pixels with 64-bit edges: the same pixels in the same order.
    std::mt19937_64 rng(99);
    const std::int64_t m = max_fixed_coordinate;
    const Viewport frame{80, 60}, far{1 << 21, 1 << 21};
    std::vector<std::pair<std::array<FixedPoint2, 3>, Viewport>> set;
    std::uniform_int_distribution<std::int64_t> extent(0, tiny_extent);
    for (int trial = 0; trial < 6000; ++trial) {
        const double size = trial % 3 == 0 ? 3.0 : trial % 3 == 1 ? 12.0 : 31.5;
        if (trial % 4 ==
            3) { // centres on the half-pixel grid: only the fill rule decides
            std::uniform_int_distribution<int> p(-4, 2 * static_cast<int>(size) -
                                                         4); // <= 32 px
            const auto q = [&] { return 0.5 * p(rng) + 20.0; };
            set.push_back({ch02::snap3({q(), q()}, {q(), q()}, {q(), q()}), frame});
        } else if (trial % 4 == 2) { // far out, up to the largest coordinate
            const std::int64_t x0 = m - tiny_extent - (trial % 7 == 0 ? 0 : extent(rng));
            const auto p = [&] {
                return FixedPoint2{x0 + extent(rng), x0 + extent(rng)};
            };
            set.push_back({{p(), p(), p()}, far});
        } else { // anywhere around the frame, partly outside it too
            std::uniform_real_distribution<double> corner(-size, 80.0);
            std::uniform_real_distribution<double> offset(0.0, size);
            const Point2 c{corner(rng), corner(rng)};
            const auto p = [&] { return Point2{c.x + offset(rng), c.y + offset(rng)}; };
            set.push_back({ch02::snap3(p(), p(), p()), frame});
        }
    }
    // Extremes of the bound: vertex boxes exactly 32 px wide and high.
    const std::int64_t e = tiny_extent;
    set.push_back({{FixedPoint2{0, 0}, FixedPoint2{e, 1}, FixedPoint2{1, e}}, frame});
    set.push_back({{FixedPoint2{e, e}, FixedPoint2{0, e}, FixedPoint2{e, 0}}, frame});
    set.push_back(
        {{FixedPoint2{m - e, m}, FixedPoint2{m, m - e}, FixedPoint2{m, m}}, far});
    long pixels = 0, largest = 0;
    for (const auto& [v, viewport] : set) {
        REQUIRE(is_tiny(v));
        const auto walk = tiny_pixels<lanes4::Portable>(v, viewport, true);
        CHECK(tiny_pixels<lanes4::Portable>(v, viewport, false) == walk);
#if defined(__SSE2__)
        CHECK(tiny_pixels<lanes4::Sse2>(v, viewport, false) == walk);
#endif
        pixels += static_cast<long>(walk.size());
        // @eq:tiny-bound: every value the lanes hold (up to seven columns past r's
        // last, the step after its last four, and one row past its last) is below 2^29.
        const PixelRect r = pixel_bounds(v, viewport);
        const EdgeSetup<FixedEdge> s = setup_edges(v);
        for (const FixedEdge& edge : s.edge) {
            for (const int x : {r.x_begin, r.x_end + 6}) {
                for (const int y : {r.y_begin, r.y_end}) {
                    largest = std::max<long>(largest, std::abs(edge.at(x, y)));
                }
            }
        }
    }
    CHECK(pixels > 100000);           // the set covers many pixels
    CHECK(largest < (long{1} << 29)); // the int32 bound holds
    CHECK(largest > (long{1} << 26)); // and the extremes come near it
}

TEST_CASE("the tiled renderer draws the teaching path's picture with 1 to 4 threads") {
    // 3000 overlapping triangles of all sizes, then a jittered mesh, a fan of 720
    // slivers, the hard cases and 300 of them again (depth ties), flat and depth-tested:
    // the picture (and depth buffer) of draw_tiled equals draw_reference's, bit for bit,
    // for every thread count, and the per-triangle fast paths (runs, masks) give it too.
    std::mt19937_64 rng(94);
    constexpr int width = 300, height = 200;
    std::uniform_real_distribution<float> depth(0.0f, 1.0f);
    std::vector<FlatTriangle> tris;
    for (int n = 0; n < 3000; ++n) {
        const double spread = n % 3 == 0 ? 10.0 : n % 3 == 1 ? 60.0 : 400.0;
        const auto v = n % 5 == 4 ? ch02::random_tie_triangle(rng, -10, 310)
                                  : ch02::random_triangle(rng, -spread / 4, spread);
        const auto c = static_cast<std::uint8_t>(n);
        tris.push_back({v, depth_plane(v, {depth(rng), depth(rng), depth(rng)}),
                        rgba(c, static_cast<std::uint8_t>(n >> 8), 255 - c)});
    }
    // Then chapter 2's jittered mesh and fan, and chapter 6's hard cases, on top.
    std::uniform_real_distribution<double> wobble(-3.0, 3.0);
    const auto jittered = [&](int, int) { return Point2{wobble(rng), wobble(rng)}; };
    auto extra = testing::grid_mesh({20.3, 10.7}, 10, 17.0, jittered);
    for (const auto& t : testing::sliver_fan({200.5, 100.5}, 90.0, 720)) {
        extra.push_back(t);
    }
    const std::int64_t m = max_fixed_coordinate;
    extra.push_back(ch02::snap3({10.25, 3.5}, {290.75, 190.25}, {290.8125, 190.25}));
    extra.push_back({FixedPoint2{-m, -m}, FixedPoint2{m, -m + 3}, FixedPoint2{100, m}});
    for (std::size_t n = 0; n < extra.size(); ++n) {
        const auto c = static_cast<std::uint8_t>(7 * n);
        tris.push_back({extra[n],
                        depth_plane(extra[n], {depth(rng), depth(rng), depth(rng)}),
                        rgba(255 - c, c, static_cast<std::uint8_t>(n >> 4))});
    }
    // The first 300 again, same planes, new colours: with depth every pixel is a tie
    // (z equal to the stored z), which must not draw.
    for (std::size_t n = 0; n < 300; ++n) {
        FlatTriangle again = tris[n];
        again.colour = rgba(static_cast<std::uint8_t>(n), 255, 0);
        tris.push_back(again);
    }
    for (const bool with_depth : {false, true}) {
        INFO("depth test: " << with_depth);
        const auto draw = [&](auto&& how) {
            std::vector<Rgba8> colour(width * height, rgba(0, 0, 0));
            std::vector<float> z(width * height, 1.0f);
            how(RenderTarget{colour.data(), with_depth ? z.data() : nullptr, width,
                             height});
            std::vector<std::uint32_t> z_bits; // depths compared bit for bit (+0 vs -0)
            for (const float d : z) {
                z_bits.push_back(std::bit_cast<std::uint32_t>(d));
            }
            return std::pair{colour, z_bits};
        };
        const auto reference =
            draw([&](const RenderTarget& t) { draw_reference(t, tris); });
        int drawn = 0;
        for (const Rgba8 p : reference.first) {
            drawn += p != rgba(0, 0, 0);
        }
        CHECK(drawn > width * height / 2); // the picture is not empty
        for (int threads = 1; threads <= 4; ++threads) {
            INFO(threads << " threads");
            CHECK(draw([&](const RenderTarget& t) { draw_tiled(t, tris, threads); }) ==
                  reference);
        }
        CHECK(draw([&](const RenderTarget& t) {
                  for (const auto& tri : tris) {
                      draw_runs(t, tri);
                  }
              }) == reference);
        CHECK(draw([&](const RenderTarget& t) {
                  for (const auto& tri : tris) {
                      draw_masks(t, tri);
                  }
              }) == reference);
    }
}

TEST_CASE("a depth tie goes to the triangle drawn first, as GL_LESS gives it") {
    // Two overlapping triangles on one depth plane: every pixel both cover is a tie.
    // The depth test here is "less" (plot's !(z < d) refuses a tie), OpenGL's default
    // GL_LESS, which bench_ch10_fast sets for llvmpipe, so the earlier triangle keeps the
    // pixel on every path; chapter 7's DepthBuffer gives a tie to the later one instead
    // (tests/ch07_scenes.cpp). Without a depth buffer the later triangle paints over.
    constexpr int width = 80, height = 60;
    const auto a = ch02::snap3({2.5, 3.25}, {70.75, 8.5}, {20.125, 55.5});
    const auto b = ch02::snap3({10.5, 50.25}, {75.25, 40.5}, {30.75, 1.5});
    const std::array<float, 3> depth = {0.25f, 0.25f, 0.25f};
    const Rgba8 red = rgba(255, 0, 0), blue = rgba(0, 0, 255), ground = rgba(0, 0, 0);
    for (const bool with_depth : {true, false}) {
        for (const bool a_first : {true, false}) {
            INFO("depth test: " << with_depth << ", red first: " << a_first);
            const FlatTriangle first{a_first ? a : b, depth_plane(a_first ? a : b, depth),
                                     a_first ? red : blue};
            const FlatTriangle second{a_first ? b : a,
                                      depth_plane(a_first ? b : a, depth),
                                      a_first ? blue : red};
            const std::vector<FlatTriangle> tris = {first, second};
            const auto draw = [&](auto&& how) {
                std::vector<Rgba8> colour(width * height, ground);
                std::vector<float> z(width * height, 1.0f);
                how(RenderTarget{colour.data(), with_depth ? z.data() : nullptr, width,
                                 height});
                return colour;
            };
            // What each triangle covers alone, to find the pixels both cover.
            const auto alone = [&](const FlatTriangle& t) {
                return draw([&](const RenderTarget& target) {
                    draw_reference(target, std::span(&t, 1));
                });
            };
            const std::vector<Rgba8> only_first = alone(first),
                                     only_second = alone(second);
            const std::vector<Rgba8> reference =
                draw([&](const RenderTarget& t) { draw_reference(t, tris); });
            int shared = 0;
            for (std::size_t i = 0; i < reference.size(); ++i) {
                if (only_first[i] != ground && only_second[i] != ground) {
                    ++shared;
                    CHECK(reference[i] == (with_depth ? first.colour : second.colour));
                }
            }
            CHECK(shared > 300);
            for (int threads = 1; threads <= 2; ++threads) {
                CHECK(draw([&](const RenderTarget& t) {
                          draw_tiled(t, tris, threads);
                      }) == reference);
            }
            CHECK(draw([&](const RenderTarget& t) {
                      draw_runs(t, first);
                      draw_runs(t, second);
                  }) == reference);
            CHECK(draw([&](const RenderTarget& t) {
                      draw_masks(t, first);
                      draw_masks(t, second);
                  }) == reference);
        }
    }
}

TEST_CASE("bad thread counts and vertices are rejected before any pixel is drawn") {
    std::vector<Rgba8> colour(64 * 64, rgba(1, 2, 3));
    const RenderTarget t{colour.data(), nullptr, 64, 64};
    const std::array<FixedPoint2, 3> ok = ch02::snap3({1, 1}, {60, 2}, {30, 50});
    std::vector<FlatTriangle> tris{{ok, {}, rgba(255, 0, 0)}};
    CHECK_THROWS_WITH_AS(draw_tiled(t, tris, 0), "thread count 0 is outside 1 .. 64",
                         Error);
    CHECK_THROWS_AS(draw_tiled(t, tris, max_threads + 1), Error);
    const std::int64_t past = max_fixed_coordinate + 1;
    tris.push_back(
        {{FixedPoint2{0, 0}, FixedPoint2{past, 0}, FixedPoint2{0, 256}}, {}, {}});
    for (int threads : {1, 3}) {
        try {
            draw_tiled(t, tris, threads);
            FAIL("no Error");
        } catch (const Error& e) {
            CHECK(std::string(e.what()).find("triangle 1: vertex 1") == 0);
        }
    }
    CHECK_THROWS_AS(draw_reference(t, tris), Error);
    CHECK(colour == std::vector<Rgba8>(64 * 64, rgba(1, 2, 3))); // nothing drawn
}

namespace {

/// The set as textured triangles: every vertex its own depth w in [1/2, 8] (perspective)
/// and texture coordinates anywhere in [-40, 300] texels (the texture repeats).
std::vector<std::array<TexturedVertex, 3>>
textured(const std::vector<std::array<FixedPoint2, 3>>& set, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> depth(0.5, 8.0), uv(-40.0, 300.0);
    std::vector<std::array<TexturedVertex, 3>> tris;
    for (const auto& v : set) {
        std::array<TexturedVertex, 3> t{};
        for (std::size_t k = 0; k < 3; ++k) {
            t[k] = {to_pixels(v[k]), depth(rng), {uv(rng), uv(rng)}};
        }
        tris.push_back(t);
    }
    return tris;
}

/// A texture whose every texel has its own colour: (i, j) is rgba(i, j, i ^ j).
Texture numbered_texture(int width, int height) {
    std::vector<Rgba8> texels;
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            texels.push_back(rgba(static_cast<std::uint8_t>(i),
                                  static_cast<std::uint8_t>(j),
                                  static_cast<std::uint8_t>(i ^ j)));
        }
    }
    return Texture(width, height, std::move(texels));
}

/// The teaching path's picture of `tris` in order (draw_textured_triangle, `mapper`).
std::vector<Rgba8>
teaching_picture(const std::vector<std::array<TexturedVertex, 3>>& tris, int width,
                 int height, const Texture& texture, Wrap wrap, Mapper mapper = {}) {
    Framebuffer frame(width, height, rgba(0, 0, 0, 0));
    MapperSettings settings;
    settings.mapper = mapper;
    settings.wrap = wrap;
    for (const auto& t : tris) {
        draw_textured_triangle(frame, t, texture, settings);
    }
    return frame.pixels();
}

/// The textured runs' picture of the same.
std::vector<Rgba8> runs_picture(const std::vector<std::array<TexturedVertex, 3>>& tris,
                                int width, int height, const Texture& texture,
                                Wrap wrap) {
    std::vector<Rgba8> pixels(static_cast<std::size_t>(width * height), rgba(0, 0, 0, 0));
    draw_textured_runs(RenderTarget{pixels.data(), nullptr, width, height}, tris, texture,
                       wrap);
    return pixels;
}

int differing(const std::vector<Rgba8>& a, const std::vector<Rgba8>& b) {
    int n = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        n += a[k] != b[k];
    }
    return n;
}

} // namespace

TEST_CASE("textured runs draw the exact mapper's texels under perspective on every set") {
    // Chapter 2's random set (slivers to triangles larger than the frame, ties on the
    // half-pixel grid), a jittered mesh and the fan of 720 slivers, each triangle with
    // its own w at every vertex, drawn in order into one frame: the textured runs give
    // draw_textured_triangle's picture (exact mapper, double, rule 1), pixel for pixel,
    // with a power-of-two texture that repeats (the masked wrap) and with a 20 x 28 one,
    // repeated and clamped (the general wrap).
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> wobble(-3.0, 3.0);
    const auto jittered = [&](int, int) { return Point2{wobble(rng), wobble(rng)}; };
    struct Set {
        const char* name;
        std::vector<std::array<FixedPoint2, 3>> triangles;
        int width, height;
    };
    const Set sets[] = {
        {"random", random_set(100), 130, 90},
        {"mesh", testing::grid_mesh({2.3, 1.7}, 8, 8.0, jittered), 72, 72},
        {"fan", testing::sliver_fan({36.5, 36.5}, 33.0, 720), 72, 72}};
    const Texture square = numbered_texture(64, 64), odd = numbered_texture(20, 28);
    std::uint64_t seed = 101;
    for (const Set& set : sets) {
        INFO(std::string(set.name));
        const auto tris = textured(set.triangles, seed++);
        for (const auto& sampled :
             {std::pair{&square, Wrap::repeat}, std::pair{&odd, Wrap::repeat},
              std::pair{&odd, Wrap::clamp}}) {
            const Texture* texture = sampled.first;
            const Wrap wrap = sampled.second;
            INFO(texture->width() << " x " << texture->height() << " texels, "
                                  << (wrap == Wrap::repeat ? "repeat" : "clamp"));
            const auto reference =
                teaching_picture(tris, set.width, set.height, *texture, wrap);
            CHECK(differing(runs_picture(tris, set.width, set.height, *texture, wrap),
                            reference) == 0);
            // Not vacuous: the frame is mostly drawn, and perspective matters (with
            // the texture repeated, the affine mapper picks other texels at a tenth of
            // the pixels or more; clamped, most of the frame is edge texels either way).
            const std::vector<Rgba8> empty(reference.size(), rgba(0, 0, 0, 0));
            CHECK(differing(reference, empty) > set.width * set.height / 2);
            if (wrap == Wrap::repeat) {
                CHECK(differing(teaching_picture(tris, set.width, set.height, *texture,
                                                 wrap, {MapperKind::affine}),
                                reference) > set.width * set.height / 10);
            }
        }
    }
}

TEST_CASE("textured runs reject a bad triangle before any pixel is drawn") {
    std::vector<Rgba8> pixels(32 * 32, rgba(1, 2, 3));
    const RenderTarget target{pixels.data(), nullptr, 32, 32};
    const Texture texture = numbered_texture(16, 16);
    const std::array<TexturedVertex, 3> good{{{{1.0, 1.0}, 1.0, {0.0, 0.0}},
                                              {{30.0, 2.0}, 2.0, {16.0, 0.0}},
                                              {{5.0, 30.0}, 1.5, {0.0, 16.0}}}};
    const std::vector<std::array<TexturedVertex, 3>> tris{good};
    draw_textured_runs(target, tris, texture, Wrap::repeat);
    CHECK(pixels != std::vector<Rgba8>(32 * 32, rgba(1, 2, 3))); // a good one draws
    std::fill(pixels.begin(), pixels.end(), rgba(1, 2, 3));
    auto zero_w = tris[0];
    zero_w[2].w = 0.0;
    auto far_uv = tris[0];
    far_uv[1].uv = {3e7, 0};
    for (const auto& bad : {zero_w, far_uv}) {
        const std::vector<std::array<TexturedVertex, 3>> set{tris[0], bad};
        try {
            draw_textured_runs(target, set, texture, Wrap::repeat);
            FAIL("no Error");
        } catch (const Error& e) {
            CHECK(std::string(e.what()).find("triangle 1: textured triangle: vertex") ==
                  0);
        }
        CHECK(pixels == std::vector<Rgba8>(32 * 32, rgba(1, 2, 3))); // nothing drawn
    }
}
