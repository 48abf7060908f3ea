// printable.hpp: input text made safe to quote in a message.
//
// Usage:
//   printable("a\x1b[31mb\tc")  // "a\x1b[31mb\tc" with the ESC and the tab written out:
//                               // a\x1b[31mb\tc
//
// A message quotes what the input said (a key, a word, a file name), and the input may
// hold any byte. Written to a terminal raw, ESC and BEL act instead of showing, a NUL
// ends a C string and a line break splits the message. printable() writes every control
// character as an escape, so a message is always one line of visible text: \0, \t, \n,
// \r, and \xNN for the other C0 controls and DEL (0x00-0x1f, 0x7f); \u0080 to \u009f for
// the C1 controls of UTF-8; and \xNN for each byte that is not part of valid UTF-8. All
// other text, UTF-8 letters included, is kept. A backslash is kept as it is, so the
// result is unchanged by a second printable(): Error applies it to every message.
// unsigned_nan(v) is v with a NaN's sign cleared, for a number a message prints.
#pragma once

#include <cmath>
#include <string>
#include <string_view>

namespace exactpixels {

/// `text` with every control character and every byte of invalid UTF-8 escaped.
std::string printable(std::string_view text);

/// v, or, if v is a NaN, that NaN without its sign, which a message then prints as "nan".
/// IEEE 754 leaves the sign of an operation's NaN open (x86 passes on one operand's, and
/// a compiler may swap a sum's operands), so two exact paths may differ in it alone.
inline double unsigned_nan(double v) {
    return std::isnan(v) ? std::fabs(v) : v;
}

} // namespace exactpixels
