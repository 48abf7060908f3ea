// Messages of build/bin/exactpixels: one line each, never a whole huge token.
#include "commands.hpp"

#include "exactpixels/base/error.hpp"
#include "exactpixels/base/printable.hpp"

#include <cstdio>
#include <new>

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

void report_errors(std::string_view command, int& exit_code,
                   const std::function<void()>& body) {
    try {
        body();
    } catch (const Error& error) {
        print_error(command, error.what());
        exit_code = exit_bad_input;
    } catch (const std::bad_alloc&) { // the memory it failed to get is free again
        print_error(command, "out of memory: this input needs more memory than the "
                             "process may have");
        exit_code = exit_bad_input;
    }
}

} // namespace exactpixels::cli
