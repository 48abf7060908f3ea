#include "exactpixels/base/decimal_from_chars.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>
#include <system_error>

namespace exactpixels {

#if defined(__cpp_lib_to_chars)

std::from_chars_result decimal_from_chars(const char* first, const char* last,
                                          double& value) {
    return std::from_chars(first, last, value);
}

#else

namespace {

bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

/// `text` starts with `word`, letters compared without case.
bool starts_with_word(std::string_view text, std::string_view word) {
    if (text.size() < word.size()) {
        return false;
    }
    for (std::size_t i = 0; i < word.size(); ++i) {
        const char c = text[i] >= 'A' && text[i] <= 'Z' ? static_cast<char>(text[i] + 32)
                                                        : text[i];
        if (c != word[i]) {
            return false;
        }
    }
    return true;
}

/// The length of the longest prefix of `text` that from_chars reads (after a '-'), and
/// whether it has a nonzero digit; 0 when there is none.
std::size_t number_length(std::string_view text, bool& nonzero) {
    nonzero = false;
    if (starts_with_word(text, "infinity")) {
        return 8;
    }
    if (starts_with_word(text, "inf") || starts_with_word(text, "nan")) {
        return 3; // a "nan(...)" payload is not read: never in this project's inputs
    }
    std::size_t i = 0, digits = 0;
    for (; i < text.size() && is_digit(text[i]); ++i, ++digits) {
        nonzero = nonzero || text[i] != '0';
    }
    if (i < text.size() && text[i] == '.') {
        ++i;
        for (; i < text.size() && is_digit(text[i]); ++i, ++digits) {
            nonzero = nonzero || text[i] != '0';
        }
    }
    if (digits == 0) {
        return 0;
    }
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        std::size_t j = i + 1;
        if (j < text.size() && (text[j] == '+' || text[j] == '-')) {
            ++j;
        }
        if (j < text.size() && is_digit(text[j])) {
            while (j < text.size() && is_digit(text[j])) {
                ++j;
            }
            i = j;
        }
    }
    return i;
}

} // namespace

std::from_chars_result decimal_from_chars(const char* first, const char* last,
                                          double& value) {
    const std::string_view text(first, static_cast<std::size_t>(last - first));
    const std::size_t sign = !text.empty() && text[0] == '-' ? 1 : 0;
    bool nonzero = false;
    const std::size_t length = number_length(text.substr(sign), nonzero);
    if (length == 0) {
        return {first, std::errc::invalid_argument};
    }
    const std::string number(text.substr(0, sign + length));
    errno = 0;
    const double read = std::strtod(number.c_str(), nullptr);
    const char* end = first + number.size();
    const bool letters = !is_digit(number[sign]) && number[sign] != '.';
    if (!letters && (std::isinf(read) || (read == 0.0 && nonzero))) {
        return {end, std::errc::result_out_of_range}; // value is left as it was
    }
    value = read;
    return {end, std::errc{}};
}

#endif

} // namespace exactpixels
