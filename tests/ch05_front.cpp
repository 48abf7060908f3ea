// Chapter 5 tests: the Pareto front over time, worst error and wrong texels at ties, with
// times compared within the run's noise (lab/pareto_front.hpp).
#include "exactpixels/base/error.hpp"
#include "exactpixels/lab/pareto_front.hpp"
#include "support/printing.hpp"

#include <doctest/doctest.h>

#include <vector>

using namespace exactpixels;

TEST_CASE("times within the noise are tied, and only a time beyond it ranks") {
    CHECK(tied_in_time(3.82, 3.81, 0.01));
    CHECK(tied_in_time(3.81, 3.82, 0.01));
    CHECK_FALSE(tied_in_time(3.82, 3.81, 0.001));
    CHECK_FALSE(tied_in_time(4.0, 3.0, 0.2));
    CHECK(tied_in_time(3.0, 3.0, 0.0));
    // A tied time is "as fast": the exact errors decide.
    const Setting rule{3.82, 0.0, 0}, no_rule{3.81, 0.0, 29952};
    CHECK(beats(rule, no_rule, 0.01));
    CHECK_FALSE(beats(no_rule, rule, 0.01));
    // Without the noise the 0.01 ns decides that neither beats the other.
    CHECK_FALSE(beats(rule, no_rule, 0.0));
    CHECK_FALSE(beats(no_rule, rule, 0.0));
    // Equal on all three: neither beats the other, not even itself.
    CHECK_FALSE(beats(rule, rule, 0.01));
}

TEST_CASE("the front of a hand-made table, with a tie within the noise") {
    // time (ns/px), worst (texels), wrong texels at ties; noise 5 %.
    const std::vector<Setting> table = {
        {1.00, 0.0, 10}, // 0: fastest exact one, but wrong at ties: beaten by 1 and 5
        {1.03, 0.0, 0},  // 1: tied with 0 on time (3 %), better at ties: front
        {1.50, 0.0, 0},  // 2: as accurate as 1 and 5, slower beyond the noise: beaten
        {0.90, 5.0, 0},  // 3: fastest of all: front
        {0.92, 5.0, 0},  // 4: tied with 3 and equal on errors: front too
        {1.04, 0.0, 0},  // 5: tied with 0 (4 %) and with 1: front
        {0.95, 6.0, 3},  // 6: slower than 3 beyond the noise, tied with 4, worse on
                         //    both errors: beaten by both
    };
    const double noise = 0.05;
    CHECK(beaten_by(table, noise) == std::vector<int>{2, 0, 2, 0, 0, 0, 2});
    // Times as measured (no noise): 0 is then fastest among the exact ones, and 3
    // beats 4.
    CHECK(beaten_by(table, 0.0) == std::vector<int>{0, 0, 2, 0, 1, 1, 2});
}

TEST_CASE("the noise of a repeated run is the median spread of its repetitions") {
    // Spreads 0.1, 0.01 and 0.02: the median is 0.02.
    CHECK(repetition_noise({{1.0, 1.1, 1.05}, {2.0, 2.0, 2.02}, {4.0, 4.08, 4.04}}) ==
          doctest::Approx(0.02).epsilon(1e-12));
    // An even count takes the middle two: (0.01 + 0.02) / 2.
    CHECK(repetition_noise({{2.0, 2.02}, {4.0, 4.08}, {1.0, 1.1}, {1.0, 1.0}}) ==
          doctest::Approx(0.015).epsilon(1e-12));
    CHECK_THROWS_AS(repetition_noise({{1.0}}), Error);
    CHECK_THROWS_AS(repetition_noise({}), Error);
    CHECK_THROWS_AS(repetition_noise({{0.0, 1.0}}), Error);
}
