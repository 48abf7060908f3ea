// text_lines.hpp: a text split into its lines, for tests that read files and output.
//
// Usage:
//   for (const std::string& line : lines_of(read_file(path))) { ... }
//
// Lines are split at '\n' and keep any '\r'; a final line without '\n' counts, an empty
// text has no lines.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace exactpixels::testing {

/// The lines of `text`, without their '\n'.
inline std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
    }
    return lines;
}

} // namespace exactpixels::testing
