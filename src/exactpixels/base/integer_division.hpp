// integer_division.hpp: floor and ceiling of an integer quotient, exact for every sign.
//
// Usage:
//   floor_div(-7, 2) == -4;  ceil_div(-7, 2) == -3;  ceil_div(7, 2) == 4
//
// C++'s / truncates towards zero, which is neither floor nor ceiling for negative
// quotients. The fixed-point scanline (chapter 1) and the rounding rules (chapter 4)
// both need the real floor and ceiling; the divisor must be positive.
#pragma once

#include <cstdint>

namespace exactpixels {

/// floor(a / b) for b > 0, exact for every a.
constexpr std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    const std::int64_t q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

/// ceil(a / b) for b > 0, exact for every a.
constexpr std::int64_t ceil_div(std::int64_t a, std::int64_t b) {
    const std::int64_t q = a / b;
    return (a % b != 0 && a > 0) ? q + 1 : q;
}

} // namespace exactpixels
