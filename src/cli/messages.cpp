// Messages of build/bin/exactpixels: one line each, never a whole huge token.
#include "commands.hpp"

#include "exactpixels/base/printable.hpp"

#include <cstdio>

namespace exactpixels::cli {

std::string one_line(std::string_view message) {
    std::string out;
    std::size_t word = 0; // characters of the current word so far
    for (const char c : message) {
        const bool space = c == ' ' || c == '\n' || c == '\r' || c == '\t';
        if (space) {
            out += ' ';
            word = 0;
            continue;
        }
        if (word < max_word_chars) {
            out += c;
        } else if (word == max_word_chars) {
            out += "...";
        }
        ++word;
    }
    while (!out.empty() && out.back() == ' ') {
        out.pop_back();
    }
    return out;
}

void print_error(std::string_view command, std::string_view message) {
    std::string text = "exactpixels";
    if (!command.empty()) {
        text += ' ';
        text += command;
    }
    // An Error's message is printable already; CLI11's quotes the command line raw.
    text += ": " + printable(one_line(message)) + "\n";
    std::fputs(text.c_str(), stderr);
}

} // namespace exactpixels::cli
