// decimal_from_chars.hpp: std::from_chars for a double, on every standard library.
//
// Usage:
//   double value = 0.0;
//   const auto [end, status] = decimal_from_chars(first, last, value);
//
// The same contract as std::from_chars(first, last, value) in its general format: an
// optional '-', digits with an optional point, an optional exponent (or inf, infinity,
// nan), the longest such prefix read and rounded to the nearest double; no '+', no
// leading space, no hexadecimal. Where the library has it (GCC's libstdc++ from version
// 11, which defines __cpp_lib_to_chars) this is std::from_chars itself; LLVM's libc++ 14
// has from_chars for integers only, and there the prefix is found here and converted by
// std::strtod, which is correctly rounded in glibc and in macOS's C library.
// result_out_of_range: beyond the largest double, or a nonzero number that reads as 0.
#pragma once

#include <charconv>

namespace exactpixels {

/// std::from_chars for a double (general format), also where the library lacks it.
std::from_chars_result decimal_from_chars(const char* first, const char* last,
                                          double& value);

} // namespace exactpixels
