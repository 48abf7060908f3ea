// reference_reading.hpp: a second reading of OBJ and MTL text for the differential fuzz
// targets fuzz_obj_numbers and fuzz_mtl_numbers, sharing no code with the loader's
// (obj_model.cpp): lines end at "\n", "\r\n" or a lone "\r", as tinyobjloader ends them;
// words are split at spaces and tabs; a number is read by the C library's strtod
// (correctly rounded, in the "C" locale the fuzzer runs in), and must be the whole word.
// A target calls abort() on any difference from the loader's model, so that libFuzzer
// reports the input.
#pragma once

#include "exactpixels/base/error.hpp"
#include "exactpixels/scene/obj_model.hpp"

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fuzz {

/// The model the loader makes of the OBJ text `obj` (its files looked up in the fixtures
/// folder), or none when the loader refuses it: then nothing is drawn, nothing compared.
inline std::optional<exactpixels::Model> accepted(std::string_view obj) {
    try {
        long long texture_bytes = 0;
        return exactpixels::parse_obj_model(obj, "fuzz.obj", EXACTPIXELS_MODEL_FIXTURES,
                                            texture_bytes);
    } catch (const exactpixels::Error&) {
        return std::nullopt;
    }
}

/// Stops the fuzzer with a message: the loader and the reference differ.
[[noreturn]] inline void differ(const std::string& what) {
    std::fprintf(stderr, "the loader and the reference reading differ: %s\n",
                 what.c_str());
    std::abort();
}

/// The text without a UTF-8 byte-order mark at its start.
inline std::string_view skip_bom(std::string_view text) {
    return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}

/// The blank-separated words of each line of `text` (blank lines give none).
inline std::vector<std::vector<std::string>> lines_of_words(std::string_view text) {
    std::vector<std::vector<std::string>> lines;
    std::vector<std::string> words;
    std::string word;
    const auto end_word = [&] {
        if (!word.empty()) {
            words.push_back(word);
            word.clear();
        }
    };
    for (std::size_t i = 0; i <= text.size(); ++i) {
        const char ch = i < text.size() ? text[i] : '\n';
        if (ch == '\n' || ch == '\r') {
            end_word();
            lines.push_back(words);
            words.clear();
            if (ch == '\r' && i + 1 < text.size() && text[i + 1] == '\n') {
                ++i;
            }
        } else if (ch == ' ' || ch == '\t') {
            end_word();
        } else {
            word += ch;
        }
    }
    return lines;
}

/// The word read by strtod, which must read all of it (else the two readings differ
/// about what a number is: the loader accepted a word strtod does not). errno is not
/// looked at: glibc sets ERANGE for a denormal result, which is still the right value.
inline double number(const std::string& word) {
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size()) {
        differ("the loader accepted '" + word + "', which strtod does not read whole");
    }
    return value;
}

} // namespace fuzz
