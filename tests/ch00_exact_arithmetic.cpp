// Chapter 0 tests: what every exact result of the book relies on. The build never fuses
// a multiply and an add (-ffp-contract=off), and the exact types the references use
// (exactpixels/base/exact.hpp) take a double's value exactly and round back once, to
// the nearest double.
#include "exactpixels/base/contraction.hpp"
#include "exactpixels/base/exact.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

using namespace exactpixels;

namespace {

/// a * b + c rounded twice (the product, then the sum), from exact values.
double unfused(double a, double b, double c) {
    return to_double(exact(to_double(exact(a) * exact(b))) + exact(c));
}

/// a * b + c rounded once, as a fused multiply-add gives it, from exact values.
double fused(double a, double b, double c) {
    return to_double(exact(a) * exact(b) + exact(c));
}

/// The exact value of a finite double, from its bits: sign, 53-bit integer, power of 2.
Rational value_from_bits(double d) {
    int e = 0;
    const double m = std::frexp(d, &e); // d = m 2^e, 1/2 <= |m| < 1
    const auto integer = static_cast<std::int64_t>(std::ldexp(m, 53)); // exact
    const int shift = e - 53;
    return shift >= 0 ? Rational(Integer(integer) << shift)
                      : Rational(Integer(integer), Integer(1) << -shift);
}

} // namespace

TEST_CASE(
    "a*b + c rounds twice: the build never contracts it into a fused multiply-add") {
    // multiply_add_as_written is compiled like the library, on x86-64 for CPUs with FMA
    // so that the compiler could fuse it: only -ffp-contract=off stops it. Each set of
    // operands is chosen so that the fused and the unfused results differ, checked
    // exactly; the function must give the unfused one, every time.
    if (!multiply_add_runs_here()) {
        MESSAGE("skipped: this CPU has no FMA instructions, so no compiler can fuse here "
                "(run it on a CPU with FMA, any x86-64 since 2013 or any ARM64)");
        return;
    }
    // 1 + 2^-30 times 1 - 2^-30 is 1 - 2^-60, which rounds to 1: unfused 0, fused -2^-60.
    const double a = 1 + 0x1p-30, b = 1 - 0x1p-30;
    REQUIRE(unfused(a, b, -1.0) == 0.0);
    REQUIRE(fused(a, b, -1.0) == -0x1p-60);
    CHECK(multiply_add_as_written(a, b, -1.0) == 0.0);
    // Random products minus their rounded value: the fused result is the product's
    // rounding error, the unfused one 0; and random sums where the two differ in the
    // last bit.
    std::mt19937_64 random(32);
    std::uniform_real_distribution<double> any(-1000.0, 1000.0);
    int differing = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const double x = any(random), y = any(random);
        const double c = trial % 2 == 0 ? -(x * y) : any(random);
        if (fused(x, y, c) == unfused(x, y, c)) {
            continue;
        }
        ++differing;
        INFO("a = " << x << ", b = " << y << ", c = " << c);
        REQUIRE(multiply_add_as_written(x, y, c) == unfused(x, y, c));
    }
    CHECK(differing > 1000);
}

TEST_CASE("exact takes a double's value exactly, to_double rounds once to the nearest") {
    std::mt19937_64 random(33);
    std::uniform_int_distribution<std::int64_t> numerator(-(std::int64_t{1} << 62),
                                                          std::int64_t{1} << 62);
    std::uniform_int_distribution<int> scale(-300, 300);
    for (int trial = 0; trial < 3000; ++trial) {
        // A random double of any size: exact() is the value its bits say.
        const double d =
            std::ldexp(static_cast<double>(numerator(random)), scale(random));
        REQUIRE(exact(d) == value_from_bits(d));
        REQUIRE(to_double(exact(d)) == d);
        // A random fraction: its double is no farther than either neighbour, and on a
        // tie (the midpoint of two doubles) it is the even one.
        const int k = scale(random) % 40;
        const Rational power =
            k >= 0 ? Rational(Integer(1) << k) : Rational(Integer(1), Integer(1) << -k);
        const std::int64_t p = numerator(random), q = std::abs(numerator(random)) | 1;
        const Rational r = Rational(p, q) * power;
        const double nearest = to_double(r);
        const double below = std::nextafter(nearest, -1e308);
        const double above = std::nextafter(nearest, 1e308);
        const Rational error = abs(exact(nearest) - r);
        REQUIRE(error <= abs(exact(below) - r));
        REQUIRE(error <= abs(exact(above) - r));
        // The midpoint of two neighbouring doubles rounds to the one with an even last
        // bit.
        const Rational midpoint = (exact(nearest) + exact(above)) / 2;
        const double tie = to_double(midpoint);
        REQUIRE((tie == nearest || tie == above));
        const auto last_bit = [](double v) {
            int e = 0;
            return static_cast<std::int64_t>(std::ldexp(std::frexp(v, &e), 53)) & 1;
        };
        CHECK(last_bit(tie) == 0);
    }
    // 1/3 is 0x1.5555555555555p-2 in double: rounded down, once; the quotient of two
    // integers rounds the same, whatever their common factors and signs.
    CHECK(to_double(Rational(1, 3)) == 1.0 / 3.0);
    CHECK(to_double(Rational(2, 3)) == 2.0 / 3.0);
    CHECK(quotient_to_double(Integer(14), Integer(42)) == 1.0 / 3.0);
    CHECK(quotient_to_double(Integer(14), Integer(-42)) == -1.0 / 3.0);
    CHECK(quotient_to_double(Integer(-14) << 200, Integer(-42) << 200) == 1.0 / 3.0);
    // 2^53 + 1 is a tie between 2^53 and 2^53 + 2: even, down; 2^53 + 3 ties up.
    CHECK(quotient_to_double((Integer(1) << 53) + 1, Integer(1)) == 0x1p53);
    CHECK(quotient_to_double((Integer(1) << 53) + 3, Integer(1)) == 0x1p53 + 4);
}
