// error.hpp: the one exception type for bad input and failed I/O.
//
// Input and I/O fail with an Error whose message names the file (and line, and value,
// where there is one). A broken internal invariant is an assert, never an Error.
#pragma once

#include <stdexcept>
#include <string>

namespace exactpixels {

/// Bad input or failed I/O. what() names the file, line and offending value.
class Error : public std::runtime_error {
  public:
    /// Makes an error whose message is shown to the user as it is.
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

} // namespace exactpixels
