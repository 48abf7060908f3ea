// floor_to_int.hpp: floor(x), ceil(x) and round(x) of a double as an int, without a
// library call.
//
// Usage:
//   floor_to_int(-2.5) == -3;  floor_to_int(2.0) == 2;  ceil_to_int(-2.5) == -2
//   round_to_int(-2.5) == -3;  round_to_int(2.5) == 3   // halves away from zero
//
// std::floor and std::ceil are one instruction (roundsd) only with SSE4.1, which the
// x86-64 baseline this book builds for does not assume: there each is a call into the
// maths library, paid per pixel by every mapper that turns a real coordinate into a
// texel index. Converting to int truncates towards zero, exactly, in one instruction;
// where the truncation went the wrong way (up for a negative non-integer x when flooring)
// one comparison, exact too, steps it back. So both functions equal the library's for
// every x with |x| < 2^31 - 1, which is the precondition (the caller checks the range:
// beyond it the int conversion is undefined). round_to_int is std::lround's rounding
// (halves away from zero) the same way: x - trunc(x) is exact in double, so comparing it
// with 1/2 decides the step. tests/ch05_accuracy.cpp compares all three with the
// library at the edge cases and on random values.
#pragma once

namespace exactpixels {

/// The largest |x| floor_to_int and ceil_to_int accept (their result fits in an int).
inline constexpr double max_floor_to_int_magnitude = 2147483646.0;

//> floor-to-int
/// floor(x) as an int, for |x| <= max_floor_to_int_magnitude.
inline int floor_to_int(double x) {
    const int t = static_cast<int>(x); // towards zero: floor(x) or floor(x) + 1
    return t - (x < double(t));
}

/// ceil(x) as an int, for |x| <= max_floor_to_int_magnitude.
inline int ceil_to_int(double x) {
    const int t = static_cast<int>(x); // towards zero: ceil(x) or ceil(x) - 1
    return t + (x > double(t));
}

/// x rounded to the nearest int, halves away from zero (std::lround's rule), for
/// |x| <= max_floor_to_int_magnitude.
inline int round_to_int(double x) {
    const int t = static_cast<int>(x);     // towards zero
    const double fraction = x - double(t); // exact: in (-1, 1), with x's sign
    return t + (fraction >= 0.5) - (fraction <= -0.5);
}
//< floor-to-int

/// An integral double (a floor or ceil) as an int, held to int's range: INT_MIN below it
/// and for NaN, INT_MAX above. A plain conversion of a value beyond the range is
/// undefined (x86-64 gives INT_MIN either way, ARM64 saturates), so a texel index of a
/// coordinate past 2^31 texels would differ from CPU to CPU.
inline int saturated_int(double integral) {
    if (!(integral >= -2147483648.0)) { // false for NaN too
        return -2147483647 - 1;
    }
    return integral > 2147483647.0 ? 2147483647 : static_cast<int>(integral);
}

} // namespace exactpixels
