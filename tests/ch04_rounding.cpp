// Chapter 4 tests: the two rounding rules, the single floor with a modifier
// (@eq:modifier), and the choice of rule from the gradient's signs.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/exact.hpp"
#include "exactpixels/texture/rounding.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <random>

using namespace exactpixels;

namespace {

// The exhaustive identity test runs every N in [-2^20, 2^20] for k = 1..16 (34 million
// pairs): under half a second in Release and a few seconds under the sanitizers, so
// the range is the same in every build.
constexpr std::int64_t exhaustive_limit = std::int64_t{1} << 20;

/// The fill-rule reading of a choice of rule, checked independently of the code's sign
/// test: u(x, y) = u0 + a x + b y with a tie at (0, 0) (u0 an integer: c = u - 1/2 is half
/// way between two texel centres; a and b are the gradient of c as of u). The texel the
/// rule `choose(a, b)` picks must be the one that holds u a small step `side` (+1: right,
/// or below when a = 0; -1: left, or above) from the sample; a constant u takes rule 1.
template <class Choose> void check_tie_goes_to(int side, Choose&& choose) {
    std::mt19937 random(44);
    std::uniform_int_distribution<int> numerator(-8, 8);
    const Rational nudge(side, 1024);
    for (int trial = 0; trial < 2000; ++trial) {
        const Rational a(numerator(random), 4), b(numerator(random), 4);
        const std::int64_t u0 = numerator(random);
        const RoundingRule rule = choose(a, b);
        const std::int64_t picked = rule == RoundingRule::ties_up ? u0 : u0 - 1;
        INFO("dc/dx = " << a << ", dc/dy = " << b << ", u = " << u0);
        if (a != Rational(0)) {
            CHECK(picked == floor_of(Rational(u0) + a * nudge));
        } else if (b != Rational(0)) {
            CHECK(picked == floor_of(Rational(u0) + b * nudge));
        } else {
            CHECK(rule == RoundingRule::ties_up);
        }
    }
}

} // namespace

TEST_CASE("floor_div and ceil_div are exact for every sign") {
    for (std::int64_t a = -50; a <= 50; ++a) {
        for (std::int64_t b = 1; b <= 9; ++b) {
            INFO("a = " << a << ", b = " << b);
            const Rational r(a, b);
            CHECK(floor_div(a, b) == floor_of(r));
            CHECK(ceil_div(a, b) == -floor_of(-r));
        }
    }
}

TEST_CASE("the two rules agree except on ties, where rule 2 is one less") {
    // A tie is c = N/D exactly half way between two texel centres: N + D/2 = 0 mod D.
    for (int k = 1; k <= 8; ++k) {
        const std::int64_t D = std::int64_t{1} << k;
        for (std::int64_t N = -4 * D; N <= 4 * D; ++N) {
            INFO("k = " << k << ", N = " << N);
            const double c = static_cast<double>(N) / static_cast<double>(D); // exact
            CHECK(round_ties_up(N, k) == static_cast<std::int64_t>(std::floor(c + 0.5)));
            CHECK(round_ties_down(N, k) == static_cast<std::int64_t>(std::ceil(c - 0.5)));
            const bool tie = (N + D / 2) % D == 0;
            CHECK(round_ties_up(N, k) - round_ties_down(N, k) == (tie ? 1 : 0));
        }
    }
}

TEST_CASE("both rules are the single floor with their modifier for every N in +-2^20, k = 1..16" *
          doctest::description("points: 5; exercise: ch04-modifier")) {
    // Plain loops and one CHECK per k: 34 million comparisons must stay fast.
    for (int k = 1; k <= 16; ++k) {
        const std::int64_t up = rounding_modifier(RoundingRule::ties_up, k);
        const std::int64_t down = rounding_modifier(RoundingRule::ties_down, k);
        std::int64_t wrong_up = 0, wrong_down = 0, first_wrong = 0;
        for (std::int64_t N = -exhaustive_limit; N <= exhaustive_limit; ++N) {
            const bool up_ok = round_with_modifier(N, up, k) == round_ties_up(N, k);
            const bool down_ok = round_with_modifier(N, down, k) == round_ties_down(N, k);
            if (!up_ok || !down_ok) {
                first_wrong = (wrong_up + wrong_down == 0) ? N : first_wrong;
                wrong_up += !up_ok;
                wrong_down += !down_ok;
            }
        }
        INFO("k = " << k << ", first N that differs: " << first_wrong);
        CHECK(wrong_up == 0);
        CHECK(wrong_down == 0);
    }
}

TEST_CASE("for odd D both rules are floor((N + (D-1)/2)/D) for every N in +-2^16") {
    // For odd D, N/D - 1/2 = (2N - D) / 2D with 2N - D odd: never a whole number, so no
    // tie occurs, the two rules agree, and one integer modifier (D - 1)/2 gives both.
    // Every odd D from 3 to 255 and every N in [-2^16, 2^16], the definitions written
    // with floor_div and ceil_div (no shift: D is not a power of two).
    constexpr std::int64_t limit = std::int64_t{1} << 16;
    for (std::int64_t D = 3; D <= 255; D += 2) {
        const std::int64_t m = (D - 1) / 2;
        std::int64_t wrong = 0, first_wrong = 0, ties = 0;
        for (std::int64_t N = -limit; N <= limit; ++N) {
            const std::int64_t up = floor_div(2 * N + D, 2 * D);  // rule 1
            const std::int64_t down = ceil_div(2 * N - D, 2 * D); // rule 2
            const std::int64_t one_floor = floor_div(N + m, D);
            ties += (2 * N - D) % (2 * D) == 0;
            if (up != one_floor || down != one_floor) {
                first_wrong = wrong == 0 ? N : first_wrong;
                ++wrong;
            }
        }
        INFO("D = " << D << ", first N that differs: " << first_wrong);
        CHECK(ties == 0);
        CHECK(wrong == 0);
    }
    // The even case needs the two modifiers: with D = 4 the tie N = 2 tells them apart.
    CHECK(floor_div(2 + 4 / 2, 4) != floor_div(2 + 4 / 2 - 1, 4));
}

TEST_CASE("the single floor holds at the ends of the documented range" *
          doctest::description("points: 3; exercise: ch04-modifier")) {
    // |C| <= 2^61 and k <= 30: 2C + D and C + m must not overflow.
    std::mt19937_64 random(4);
    const std::int64_t limit = std::int64_t{1} << 61;
    std::uniform_int_distribution<std::int64_t> any(-limit, limit);
    for (int k : {1, 8, 16, 24, 30}) {
        const std::int64_t D = std::int64_t{1} << k;
        for (std::int64_t C : {-limit, limit, -limit + D / 2, limit - D / 2, any(random),
                               any(random), any(random), any(random)}) {
            INFO("k = " << k << ", C = " << C);
            for (RoundingRule rule : {RoundingRule::ties_up, RoundingRule::ties_down}) {
                const std::int64_t by_definition = rule == RoundingRule::ties_up
                                                       ? round_ties_up(C, k)
                                                       : round_ties_down(C, k);
                CHECK(round_with_modifier(C, rounding_modifier(rule, k), k) ==
                      by_definition);
            }
        }
    }
}

TEST_CASE("a modifier for an unusable fraction width is an Error naming k") {
    CHECK_THROWS_WITH_AS(rounding_modifier(RoundingRule::ties_up, 0),
                         doctest::Contains("k = 0"), Error);
    CHECK_THROWS_WITH_AS(rounding_modifier(RoundingRule::ties_down, 31),
                         doctest::Contains("k = 31"), Error);
}

TEST_CASE("chapter 3's 16.16 loops take the modifiers as they are" *
          doctest::description("points: 2; exercise: ch04-modifier")) {
    // Chapter 3 indexes with floor((U + modifier - D/2) / D), U = u * D = C + D/2: the
    // modifier is the modifier, so rule 1 gives floor(u) and rule 2 gives ceil(u) - 1.
    CHECK(texel_modifier(RoundingRule::ties_up) == texel_scale / 2);
    CHECK(texel_modifier(RoundingRule::ties_down) == texel_scale / 2 - 1);
    CHECK(TexelRounding{}.u_modifier == texel_modifier(RoundingRule::ties_up));
    for (std::int32_t U = -3 * texel_scale; U <= 3 * texel_scale; U += texel_scale / 8) {
        INFO("U = " << U);
        const double u = static_cast<double>(U) / texel_scale; // exact
        CHECK(fixed_texel_index(U, texel_modifier(RoundingRule::ties_up)) ==
              std::floor(u));
        CHECK(fixed_texel_index(U, texel_modifier(RoundingRule::ties_down)) ==
              std::ceil(u) - 1);
    }
}

TEST_CASE("the rule follows the sign of dc/dx, and of dc/dy when dc/dx is zero" *
          doctest::description("points: 3; exercise: ch04-choose-rule")) {
    using enum RoundingRule;
    CHECK(choose_rule(1.0, -5.0) == ties_up);
    CHECK(choose_rule(0.25, 0.0) == ties_up);
    CHECK(choose_rule(-1.0, 5.0) == ties_down);
    CHECK(choose_rule(-1e-30, 0.0) == ties_down);
    CHECK(choose_rule(0.0, 2.0) == ties_up);
    CHECK(choose_rule(0.0, -2.0) == ties_down);
    CHECK(choose_rule(-0.0, -2.0) == ties_down); // -0 is zero: the y gradient decides
    CHECK(choose_rule(0.0, 0.0) == ties_up);     // constant c: rule 1 by convention
    CHECK(choose_rule(Rational(-1, 3), Rational(7)) == ties_down);
}

TEST_CASE("a sample on a texel edge goes to the texel on its right, or below it" *
          doctest::description("points: 2; exercise: ch04-choose-rule")) {
    check_tie_goes_to(+1, [](Rational a, Rational b) { return choose_rule(a, b); });
}

TEST_CASE("a sample on a texel edge goes to the texel on its left, or above it" *
          doctest::description("points: 20; exercise: ch04-choose-rule-left-up")) {
    // The course's variant of the exercise (the opposite convention), checked the same
    // way, and on the edge cases of its table.
    check_tie_goes_to(-1, [](Rational a, Rational b) { return choose_rule_left_up(a, b); });
    using enum RoundingRule;
    CHECK(choose_rule_left_up(1.0, -5.0) == ties_down);
    CHECK(choose_rule_left_up(-1e-30, 0.0) == ties_up);
    CHECK(choose_rule_left_up(-0.0, 2.0) == ties_down); // -0 is zero: dc/dy decides
    CHECK(choose_rule_left_up(0.0, -2.0) == ties_up);
    CHECK(choose_rule_left_up(0.0, 0.0) == ties_up); // constant c: rule 1 by convention
}

TEST_CASE("with the chosen rule a span samples only the texels between its ends" *
          doctest::description("points: 3; exercise: ch04-choose-rule")) {
    // One row: the span covers pixel centres in [x0, x1) (the left end is in, the right
    // end out, as the top-left rule has it), and u runs linearly from the integer a at
    // x0 to the integer b at x1. Texels a .. b-1 (or b .. a-1) are the ones the span
    // owns; the neighbours' texels must never show, whichever way u runs. Exact
    // arithmetic: x0, x1 on the 1/256 px grid, u at each centre as a Rational.
    std::mt19937 random(4004);
    std::uniform_int_distribution<int> position(0, 40 * 256), texel(-20, 20);
    int samples = 0, ties = 0, stray_with_rule1 = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        // Half of the spans start and end on pixel centres or pixel edges (multiples of
        // 1/2 px), where whole-number slopes make ties common; the rest anywhere.
        const int snap = trial % 2 == 0 ? 128 : 1;
        const int s0 = position(random) / snap * snap,
                  s1 = position(random) / snap * snap;
        const std::int64_t a = texel(random), b = texel(random);
        if (s0 == s1 || a == b) {
            continue;
        }
        const Rational x0(std::min(s0, s1), 256), x1(std::max(s0, s1), 256);
        const Rational slope = Rational(b - a) / (x1 - x0); // du/dx = dc/dx
        const RoundingRule rule = choose_rule(slope, Rational(0));
        const std::int64_t lo = std::min(a, b), hi = std::max(a, b);
        const auto first = static_cast<std::int64_t>(floor_of(x0)) - 1;
        const auto last = static_cast<std::int64_t>(floor_of(x1)) + 1;
        for (std::int64_t x = first; x <= last; ++x) {
            const Rational centre = Rational(x) + Rational(1, 2);
            if (centre < x0 || centre >= x1) {
                continue; // not covered
            }
            const Rational u = Rational(a) + slope * (centre - x0);
            const auto rule1 = static_cast<std::int64_t>(floor_of(u));
            const bool tie = Rational(rule1) == u;
            const std::int64_t picked =
                (rule == RoundingRule::ties_down && tie) ? rule1 - 1 : rule1;
            INFO("span [" << x0 << ", " << x1 << "), u from " << a << " to " << b
                          << ", centre " << centre << ", u = " << u);
            CHECK(picked >= lo);
            CHECK(picked < hi);
            ++samples;
            ties += tie;
            stray_with_rule1 += rule1 < lo || rule1 >= hi;
        }
    }
    MESSAGE(samples << " samples, " << ties
                    << " ties; always using rule 1 would have put " << stray_with_rule1
                    << " of them on a neighbour's texel");
    CHECK(ties > 100);           // the random spans do exercise the tie
    CHECK(stray_with_rule1 > 0); // and the bug the rule exists for does happen
}
