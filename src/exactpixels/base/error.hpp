// error.hpp: the one exception type for bad input and failed I/O.
//
// Input and I/O fail with an Error whose message names the file (and line, and value,
// where there is one). A broken internal invariant is an assert, never an Error.
// A message quotes input, which may hold any byte; the constructor escapes every control
// character (printable.hpp), so what() is one line of visible text, never cut at a NUL
// and never an escape sequence for the terminal, whichever reader made it.
#pragma once

#include "exactpixels/base/printable.hpp"

#include <stdexcept>
#include <string>

namespace exactpixels {

/// Bad input or failed I/O. what() names the file, line and offending value.
class Error : public std::runtime_error {
  public:
    /// Makes an error whose message is shown to the user, control characters escaped.
    explicit Error(std::string_view message) : std::runtime_error(printable(message)) {}
};

} // namespace exactpixels
