// Chapter 5 tests: the error measure of the benchmark, its scenes, and its agreement
// with chapter 3's closed-form bound for the affine mapper.
#include "exactpixels/base/floor_to_int.hpp"
#include "exactpixels/base/split_mix.hpp"
#include "exactpixels/lab/accuracy_scenes.hpp"
#include "exactpixels/texture/perspective_error.hpp"
#include "exactpixels/texture/texel_error.hpp"
#include "exactpixels/texture/texture.hpp"
#include "support/measured_facts.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace exactpixels;
using exactpixels::testing::record_fact;

namespace {
MapperConfig find(const std::string& name) {
    for (const MapperConfig& m : accuracy_mappers()) {
        if (m.name == name) {
            return m;
        }
    }
    FAIL("no mapper " << name);
    return {};
}
} // namespace

TEST_CASE("the texel error and its three summaries on a hand-made pair of maps" *
          doctest::description("points: 7; exercise: ch05-texel-error")) {
    CHECK(texel_error(3.25, 7.0, 3.0, 7.5) == 0.5);
    CHECK(texel_error(-1.0, 2.0, 1.0, 2.25) == 2.0);
    CHECK(texel_error(4.0, 4.0, 4.0, 4.0) == 0.0);
    // Through a whole comparison: one pixel off by (0.75, -0.25) texels.
    TexelMap a(2, 1), b(2, 1);
    for (TexelMap* m : {&a, &b}) {
        m->covered = {true, true};
        m->u = {0.5, 1.5};
        m->v = {0.5, 0.5};
        m->i = {0, 1};
        m->j = {0, 0};
    }
    b.u[1] = 2.25;
    b.v[1] = 0.25;
    b.i[1] = 2;
    const TexelError e = compare_texel_maps(a, b);
    CHECK(e.pixels == 2);
    CHECK(e.worst == 0.75);
    CHECK(e.mean == 0.375);
    CHECK(e.differing_share == 0.5);
}

TEST_CASE("every mapper covers the same pixels as the reference on every scene") {
    for (const AccuracyScene& scene : accuracy_scenes()) {
        for (const MapperConfig& m : accuracy_mappers()) {
            INFO(benchmark_name(scene, m));
            const TexelError e = measure_mapper_error(scene, m);
            CHECK(e.coverage_mismatches == 0);
            CHECK(e.pixels > 0);
        }
    }
}

TEST_CASE("on the facing wall only the rounding rule decides, at exactly the ties") {
    // w is the same at every corner, so every mapper is exact; u = (304.5 - x) / 2 is a
    // whole number at every other pixel centre, and u falls to the right, so chapter
    // 4's rule picks ceil(u) - 1 there while rule 1 picks floor(u): half the pixels.
    const AccuracyScene wall = wall_facing_scene();
    for (const char* name : {"affine fixed", "quadratic fixed", "exact double"}) {
        const TexelError e = measure_mapper_error(wall, find(name));
        INFO(name);
        CHECK(e.worst == 0.0);
        CHECK(e.differing_share == 0.5);
    }
    for (const char* name : {"affine fixed +rule", "exact fixed +rule"}) {
        const TexelError e = measure_mapper_error(wall, find(name));
        CHECK(e.worst == 0.0);
        CHECK(e.differing_share == 0.0);
    }
}

TEST_CASE("a wrong texel at a tie is a differing texel where the exact u or v is whole") {
    // Four pixels, the reference's (u, v) and the candidate's texel at each:
    //   0: u whole (a tie), the candidate's i differs        -> wrong at a tie
    //   1: v whole (a tie), the candidate agrees              -> a tie, not wrong
    //   2: no tie, the candidate's i differs                  -> differs, not at a tie
    //   3: u and v whole, the candidate's j only differs      -> wrong at a tie
    TexelMap reference(4, 1), candidate(4, 1);
    reference.covered = {true, true, true, true};
    reference.u = {3.0, 0.25, 5.5, -2.0};
    reference.v = {0.5, 7.0, 1.75, 4.0};
    reference.i = {2, 0, 5, -3};
    reference.j = {0, 7, 1, 4};
    candidate = reference;
    candidate.i[0] = 3;
    candidate.u[2] = 6.0;
    candidate.i[2] = 6;
    candidate.j[3] = 3;
    const TexelError e = compare_texel_maps(reference, candidate);
    CHECK(e.pixels == 4);
    CHECK(e.ties == 3);
    CHECK(e.wrong_at_ties == 2);
    CHECK(e.differing_share == 0.75);
}

TEST_CASE("the exact mapper errs at no tie with the rule and at half the wall without") {
    // With chapter 4's rule the exact mappers agree with the reference at every tie of
    // every scene (exact fixed rounds its quotient to 16.16 first, and a whole u stays
    // whole). Without it, rule 1 sends the wall's ties in u, which falls to the right,
    // to the other texel: every pixel of every second column. The floor and the field
    // have no ties at all: there the rule can change no texel the reference picks.
    const std::vector<AccuracyScene> scenes = accuracy_scenes();
    for (const AccuracyScene& scene : scenes) {
        for (const char* name : {"exact double +rule", "exact fixed +rule"}) {
            INFO(scene.name << " " << name);
            CHECK(measure_mapper_error(scene, find(name)).wrong_at_ties == 0);
        }
    }
    const AccuracyScene& wall = scenes[0];
    const TexelError with = measure_mapper_error(wall, find("exact double +rule"));
    const TexelError without = measure_mapper_error(wall, find("exact double"));
    const TexelError affine = measure_mapper_error(wall, find("affine fixed"));
    CHECK(with.ties == without.ties);
    CHECK(4 * with.ties == 3 * with.pixels); // every second column or row
    CHECK(without.wrong_at_ties > 0);
    CHECK(2 * without.wrong_at_ties == without.pixels); // every second column
    CHECK(affine.wrong_at_ties == without.wrong_at_ties);
    record_fact("ch05_wall_pixels", double(without.pixels));
    record_fact("ch05_wall_ties", double(without.ties));
    record_fact("ch05_wall_wrong_at_ties_rule_1", double(without.wrong_at_ties));
    for (const AccuracyScene* scene : {&scenes[1], &scenes[2]}) {
        INFO(scene->name);
        const TexelError e = measure_mapper_error(*scene, find("exact double"));
        CHECK(e.ties == 0);
        record_fact("ch05_" + scene->name + "_ties", double(e.ties));
    }
}

TEST_CASE("the grazing floor spans depth ratios from 1.1 to 20") {
    const auto r = span_depth_ratios(grazing_floor_scene());
    record_fact("ch05_floor_ratio_low", r[0]);
    record_fact("ch05_floor_ratio_high", r[1]);
    CHECK(r[0] >= 1.1);
    CHECK(r[0] <= 1.2);
    CHECK(r[1] >= 20.0);
    CHECK(r[1] <= 21.0);
}

TEST_CASE("the floor's picks follow how far a span reaches, not its depth ratio") {
    // The picks table (figures/ch05_table.cpp) splits the floor by the depth ratio of
    // each pixel's span and picks, per band, the cheapest mapper under half a texel. A
    // short piece's error is its texel extent times a function of its own depth ratio
    // (eq. affine-bound, eq. piece-ratio), and both are largest at the far end of a span,
    // where one pixel covers the most texels: what decides whether short pieces hold is
    // how far the span reaches, which the bands do not sort by. Bands 1-2, 2-5 and 10-30
    // hold spans that reach the floor's far edge (depth 28); band 5-10 only spans that
    // stop before depth 15. So pieces of 4 (affine) and 16 (quadratic) stay under half a
    // texel in band 5-10 and not in 2-5 or 10-30, and in band 10-30 they do hold on the
    // spans that stop before depth 15. Pieces of 8 (quadratic) hold everywhere.
    const AccuracyScene floor = grazing_floor_scene();
    const std::vector<double> ratio = span_ratio_map(floor);
    const std::vector<double> far = span_far_depth_map(floor);
    TexelMap reference(floor.width, floor.height);
    map_with(reference, floor, reference_mapper());
    const auto map_of = [&](const char* name) {
        TexelMap map(floor.width, floor.height);
        map_with(map, floor, find(name));
        return map;
    };
    const TexelMap sub4 = map_of("subdivided:4 fixed"),
                   quad16 = map_of("quadratic:16 fixed"),
                   quad8 = map_of("quadratic:8 fixed");
    // The worst error of `map` over the pixels of band [lo, hi) whose far depth passes:
    // eq. texel-error written out here rather than through texel_error, which is the
    // chapter's exercise (a fresh kit's stub must not fail this test).
    const auto worst = [&](const TexelMap& map, double lo, double hi, auto&& far_ok) {
        double w = 0;
        int pixels = 0;
        for (std::size_t k = 0; k < ratio.size(); ++k) {
            if (ratio[k] >= lo && ratio[k] < hi && far_ok(far[k]) && map.covered[k] &&
                reference.covered[k]) {
                ++pixels;
                w = std::max({w, std::abs(map.u[k] - reference.u[k]),
                              std::abs(map.v[k] - reference.v[k])});
            }
        }
        REQUIRE(pixels > 0);
        return w;
    };
    const auto any = [](double) { return true; };
    for (const auto& [lo, hi] : picks_ratio_bands) {
        const std::string band =
            "ch05_band_" + std::to_string(int(lo)) + "_" + std::to_string(int(hi));
        double reach = 0;
        for (std::size_t k = 0; k < ratio.size(); ++k) {
            if (ratio[k] >= lo && ratio[k] < hi) {
                reach = std::max(reach, far[k]);
            }
        }
        const double s4 = worst(sub4, lo, hi, any), q16 = worst(quad16, lo, hi, any),
                     q8 = worst(quad8, lo, hi, any);
        INFO(band << ": reaches depth " << reach << ", subdivided:4 " << s4
                  << ", quadratic:16 " << q16 << ", quadratic:8 " << q8);
        record_fact(band + "_far", reach);
        record_fact(band + "_subdivided4", s4);
        record_fact(band + "_quadratic16", q16);
        record_fact(band + "_quadratic8", q8);
        CHECK(q8 < 0.5);
        if (lo == 5.0) {
            CHECK(reach < 15.0);
            CHECK(s4 < 0.5);
            CHECK(q16 < 0.5);
        } else {
            CHECK(reach > 25.0);
        }
        if (lo == 2.0 || lo == 10.0) {
            CHECK(s4 > 0.5);
            CHECK(q16 > 0.5);
        }
    }
    // Within band 10-30 alone, the spans that stop before depth 15 against the rest.
    const auto near = [](double w) { return w < 15.0; };
    const auto beyond = [](double w) { return w >= 15.0; };
    const double s4_near = worst(sub4, 10.0, 30.0, near);
    const double q16_near = worst(quad16, 10.0, 30.0, near);
    record_fact("ch05_band_10_30_near15_subdivided4", s4_near);
    record_fact("ch05_band_10_30_near15_quadratic16", q16_near);
    CHECK(s4_near < 0.5);
    CHECK(q16_near < 0.5);
    CHECK(worst(sub4, 10.0, 30.0, beyond) > 0.5);
    CHECK(worst(quad16, 10.0, 30.0, beyond) > 0.5);
}

TEST_CASE("the measured affine error meets chapter 3's bound on a single receding quad" *
          doctest::description("points: 3; exercise: ch05-texel-error")) {
    // A quad whose depth grows from 1 to r along x only: every row is one span with
    // depth ratio close to r and u running over 100 texels, so the worst affine error
    // is affine_error_bound(r) * 100 texels (eq. affine-bound), up to the sampling of
    // the span at pixel centres: within 1 % of it.
    const double r = 9.0;
    AccuracyScene quad{"quad", 320, 40, {}, checkerboard_texture(8, 8, 1)};
    const TexturedVertex a{{0.0, 0.0}, 1.0, {0.0, 0.0}}, b{{320.0, 0.0}, r, {100.0, 0.0}},
        c{{320.0, 40.0}, r, {100.0, 10.0}}, d{{0.0, 40.0}, 1.0, {0.0, 10.0}};
    quad.triangles = {{a, b, c}, {a, c, d}};
    const TexelError e = measure_mapper_error(quad, find("affine double"));
    const double bound = affine_error_bound(r) * 100.0; // 50 texels for r = 9
    MESSAGE("affine worst " << e.worst << " texels, chapter 3's bound " << bound);
    record_fact("ch05_quad_affine_worst", e.worst);
    record_fact("ch05_quad_affine_bound", bound);
    CHECK(e.worst <= bound);
    CHECK(e.worst >= 0.99 * bound);
}

TEST_CASE("the masked wrap equals wrap_index on every power-of-two size") {
    // Exhaustive over a window of indices around zero and at both ends of int, for every
    // power of two a texture side can be.
    long long differ = 0, compared = 0;
    for (int size = 1; size <= (1 << 16); size *= 2) {
        for (const int start : {-70000, std::numeric_limits<int>::min(),
                                std::numeric_limits<int>::max() - 140000}) {
            for (int k = 0; k <= 140000; ++k) {
                const int i = start + k;
                differ += wrap_index_masked(i, size) != wrap_index(i, size, Wrap::repeat);
                ++compared;
            }
        }
    }
    CHECK(compared == 17LL * 3 * 140001);
    CHECK(differ == 0);
}

namespace {

/// real_texel_index as chapter 4 states it, with the maths library's floor and ceil.
int texel_index_by_library(double u, std::int32_t modifier) {
    const std::int32_t offset = modifier - texel_scale / 2;
    return offset >= 0
               ? static_cast<int>(std::floor(u + double(offset) / texel_scale))
               : static_cast<int>(std::ceil(u + double(offset + 1) / texel_scale)) - 1;
}

} // namespace

TEST_CASE("floor_to_int, ceil_to_int, round_to_int and the texel index equal libm's") {
    // Edge cases: integers, halves, the doubles next to them, both signs, the range's
    // ends.
    std::vector<double> xs{0.0,
                           -0.0,
                           0.5,
                           -0.5,
                           1.0,
                           -1.0,
                           2.5,
                           -2.5,
                           max_floor_to_int_magnitude,
                           -max_floor_to_int_magnitude,
                           0x1p30 - 0.5,
                           -0x1p30 + 0.5,
                           1e-300,
                           -1e-300,
                           0.49999999999999994, // floor(x + 0.5) gets this one wrong
                           -0.49999999999999994};
    for (const double x : std::vector<double>(xs)) {
        xs.push_back(std::nextafter(x, 1e300));
        xs.push_back(std::nextafter(x, -1e300));
    }
    SplitMix random(5);
    for (int k = 0; k < 200000; ++k) { // random magnitudes from 2^-20 to 2^30
        const double x =
            std::ldexp(random.uniform(-1.0, 1.0), int(random.uniform(-20, 31)));
        xs.push_back(x);
        xs.push_back(std::round(x));       // whole numbers, where floor and ceil meet
        xs.push_back(std::round(x) + 0.5); // halves, where rounding breaks a tie
    }
    long long floor_differs = 0, ceil_differs = 0, round_differs = 0, index_differs = 0,
              indices = 0;
    for (const double x : xs) {
        if (std::abs(x) <= max_floor_to_int_magnitude) {
            floor_differs += floor_to_int(x) != static_cast<int>(std::floor(x));
            ceil_differs += ceil_to_int(x) != static_cast<int>(std::ceil(x));
            round_differs += round_to_int(x) != static_cast<int>(std::lround(x));
        }
        if (std::abs(x) < 0x1p31 - 2) { // the index fits in an int
            for (const std::int32_t modifier : {texel_scale / 2, texel_scale / 2 - 1}) {
                index_differs +=
                    real_texel_index(x, modifier) != texel_index_by_library(x, modifier);
                ++indices;
            }
        }
    }
    CHECK(xs.size() > 400000);
    CHECK(indices == 2 * static_cast<long long>(xs.size()) - 8); // all but +-max, outward
    CHECK(floor_differs == 0);
    CHECK(ceil_differs == 0);
    CHECK(round_differs == 0);
    CHECK(index_differs == 0);
}

TEST_CASE("a texel index past int's range is held to it, the same on every CPU") {
    // |u| up to texture_coordinate_limit (1e30 in double) passes the mappers' checks,
    // but an index past 2^31 is no int: both rules hold it to int's range (a plain
    // conversion is undefined there), and NaN gives the lowest.
    constexpr int lowest = std::numeric_limits<int>::min();
    constexpr int highest = std::numeric_limits<int>::max();
    for (const std::int32_t modifier : {texel_scale / 2, texel_scale / 2 - 1}) {
        INFO("modifier " << modifier);
        for (const double u : {0x1p31, 3e9, 1e30}) {
            CHECK(real_texel_index(u, modifier) == highest);
            CHECK(real_texel_index(-u - 1.0, modifier) == lowest);
        }
        CHECK(real_texel_index(std::nan(""), modifier) == lowest);
        // Just inside the range, the index is the library's, exactly.
        CHECK(real_texel_index(0x1p31 - 2.0, modifier) ==
              texel_index_by_library(0x1p31 - 2.0, modifier));
        CHECK(real_texel_index(-0x1p31 + 2.0, modifier) ==
              texel_index_by_library(-0x1p31 + 2.0, modifier));
    }
    CHECK(saturated_int(-0x1p31) == lowest);
    CHECK(saturated_int(0x1p31 - 1.0) == highest);
    CHECK(saturated_int(-5.0) == -5);
}
