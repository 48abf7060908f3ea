// scene_toml_text.cpp: the scene's text before and around toml++: a dotted key too deep
// for the parser is refused on the raw text, the numbers below the least normal double
// are read by the loader itself (libc++'s streams refuse them), and toml++'s messages
// name a redefined key as the scene wrote it.
#include "exactpixels/base/decimal_from_chars.hpp"
#include "exactpixels/scene/scene_toml.hpp"

#include <limits>
#include <optional>
#include <set>

namespace exactpixels::scene_format {

namespace {

bool is_bare_char(char ch) { // of a bare key, a number, a date, true or false, inf, nan
    return (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'z') ||
           (ch >= 'A' && ch <= 'Z') || ch == '_' || ch == '-' || ch == '+' || ch == '.' ||
           ch == ':';
}

/// The run of characters of a bare key, number or date that starts at text[i].
std::string_view bare_run(std::string_view text, std::size_t i) {
    std::size_t end = i;
    while (end < text.size() && is_bare_char(text[end])) {
        ++end;
    }
    return text.substr(i, end - i);
}

/// Whether `token` is a TOML decimal float with a finite value (an optional sign; an
/// integer part with no leading zero; a fraction, an exponent or both; '_' only between
/// digits).
bool is_decimal_float(std::string_view token) {
    std::size_t i = !token.empty() && (token[0] == '+' || token[0] == '-') ? 1 : 0;
    const auto digits = [&] { // one or more digits, '_' between two of them
        const std::size_t first = i;
        while (i < token.size() &&
               ((token[i] >= '0' && token[i] <= '9') ||
                (token[i] == '_' && i > first && i + 1 < token.size() &&
                 token[i + 1] >= '0' && token[i + 1] <= '9'))) {
            ++i;
        }
        return i > first;
    };
    const std::size_t integer = i;
    if (!digits() || (token[integer] == '0' && i > integer + 1)) {
        return false;
    }
    const std::size_t whole = i;
    if (i < token.size() && token[i] == '.' && !(++i, digits())) {
        return false;
    }
    if (i < token.size() && (token[i] == 'e' || token[i] == 'E')) {
        ++i;
        i += i < token.size() && (token[i] == '+' || token[i] == '-') ? 1 : 0;
        if (!digits()) {
            return false;
        }
    }
    return i == token.size() && i > whole;
}

/// The value of a TOML decimal float (is_decimal_float), rounded to the nearest double by
/// the project's own reader (decimal_from_chars), the same on every standard library. A
/// number beyond the doubles is std::nullopt; a nonzero number nearer 0 than the smallest
/// double reads as 0 with its sign, as toml++ reads it through GCC's library.
std::optional<double> read_decimal_float(std::string_view token) {
    const bool negative = token[0] == '-';
    std::string number; // without the sign and the underscores
    for (const char ch : token.substr(token[0] == '-' || token[0] == '+' ? 1 : 0)) {
        if (ch != '_') {
            number += ch;
        }
    }
    double value = 0.0;
    const auto [end, status] =
        decimal_from_chars(number.data(), number.data() + number.size(), value);
    assert(end == number.data() + number.size());
    if (status == std::errc::result_out_of_range) {
        // Beyond the largest double (1.8e308), or nearer 0 than the smallest (4.9e-324):
        // which one the place of the first nonzero digit says.
        const std::size_t e = std::min(number.find_first_of("eE"), number.size());
        const std::size_t point = std::min(number.find('.'), e);
        const std::size_t first = number.find_first_of("123456789");
        const long long place = static_cast<long long>(point) -
                                static_cast<long long>(first) - (first < point ? 1 : 0);
        long long exponent = 0; // saturated: only its sign beside `place` matters
        for (std::size_t k = e + 1; k < number.size(); ++k) {
            if (number[k] >= '0' && number[k] <= '9') {
                exponent = std::min(exponent * 10 + (number[k] - '0'), 1'000'000'000LL);
            }
        }
        exponent = e + 1 < number.size() && number[e + 1] == '-' ? -exponent : exponent;
        if (place + exponent >= 0) {
            return std::nullopt;
        }
        value = 0.0;
    }
    return negative ? -value : value;
}

/// The index just past the TOML string that opens at text[i] (a '"' or a '\''), one line
/// or three-quoted; for a string never closed, the line break or the end that cuts it.
std::size_t past_string(std::string_view text, std::size_t i) {
    const char quote = text[i];
    const bool triple = text.substr(i, 3) == std::string(3, quote);
    const std::string close = triple ? std::string(3, quote) : std::string(1, quote);
    std::size_t j = i + close.size();
    while (j < text.size() && text.compare(j, close.size(), close) != 0 &&
           (triple || text[j] != '\n')) {
        j += quote == '"' && text[j] == '\\' ? 2 : 1; // an escape in a basic string
    }
    return j < text.size() && text.compare(j, close.size(), close) == 0
               ? j + close.size()
               : std::min(j, text.size());
}

/// Where in `text` the numbers are that toml++ may not read but the project does: the
/// TOML decimal floats in a value's place whose magnitude is nonzero and below the
/// smallest normal double, 2^-1022. toml++ reads a float through the standard library's
/// streams, and LLVM's libc++ refuses such a number there (its strtod reports ERANGE).
/// A value's place: after '=', or after '[' or ',' inside an array or inline table, and
/// not before '=' (a key); headers and comments and strings are skipped.
std::vector<std::size_t> tiny_numbers(std::string_view text) {
    std::vector<std::size_t> found;
    int depth = 0;       // of the arrays and inline tables open in a value
    bool header = false; // between a table header's brackets
    char last = '\n';    // the last character that counts (not blank, not in a comment)
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '"' || ch == '\'') {
            i = past_string(text, i) - 1;
            last = '"';
        } else if (ch == '#') {
            i = std::min(text.find('\n', i), text.size()) - 1;
        } else if (ch == '\n') {
            header = depth == 0 ? false : header;
            last = depth == 0 ? '\n' : last;
        } else if (ch == '[' && depth == 0 && (last == '\n' || header)) {
            header = true;
            last = ch;
        } else if (ch == '[' || ch == '{') {
            depth += header ? 0 : 1;
            last = ch;
        } else if (ch == ']' || ch == '}') {
            depth -= depth > 0 && !header ? 1 : 0;
            last = ch;
        } else if (is_bare_char(ch)) {
            const std::string_view token = bare_run(text, i);
            const std::size_t next = text.find_first_not_of(" \t", i + token.size());
            const bool value =
                !header && (last == '=' || (depth > 0 && (last == '[' || last == ','))) &&
                (next == std::string_view::npos || text[next] != '=');
            if (value && is_decimal_float(token)) {
                const std::optional<double> number = read_decimal_float(token);
                const bool nonzero = // a digit 1 to 9 before the exponent
                    token.find_first_of("123456789") < token.find_first_of("eE");
                if (number && std::abs(*number) < std::numeric_limits<double>::min() &&
                    nonzero) {
                    found.push_back(i);
                }
            }
            i += token.size() - 1;
            last = 'a';
        } else if (ch != ' ' && ch != '\t' && ch != '\r') {
            last = ch;
        }
    }
    return found;
}

/// Where in the scene's text toml++ read a float.
void float_places(const toml::node& node, std::set<TextPlace>& out) {
    if (const toml::table* table = node.as_table()) {
        for (auto&& [key, child] : *table) {
            float_places(child, out);
        }
    } else if (const toml::array* array = node.as_array()) {
        for (const toml::node& child : *array) {
            float_places(child, out);
        }
    } else if (node.is_floating_point()) {
        out.insert({node.source().begin.line, node.source().begin.column});
    }
}

/// The key as written on `line` (one line of a scene) that a toml++ error at `column`
/// (from 1) is about: the last key before the column that ends at an unquoted '=' (a
/// key-value pair) or ']' (a table header), or the first one when the error points
/// before it (at a header's '['). Empty when the line has none.
std::string key_written_on(std::string_view line, std::size_t column) {
    std::string key;
    std::size_t start = 0; // where the key being scanned begins
    for (std::size_t i = 0; i < line.size() && line[i] != '#'; ++i) {
        const char ch = line[i];
        if (ch == '"' || ch == '\'') {
            i = past_string(line, i) - 1;
        } else if (ch == '[' || ch == '{' || ch == ',') {
            start = i + 1;
        } else if (ch == '=' || ch == ']') {
            const std::size_t first = line.find_first_not_of(" \t", start);
            const std::size_t last = line.find_last_not_of(" \t", i - 1);
            const bool before = i + 1 < column;
            if (first < i && (before || key.empty())) {
                key = line.substr(first, last + 1 - first);
            }
            if (!before && !key.empty()) {
                break;
            }
            start = i + 1;
        }
    }
    return key;
}

/// toml++'s description of a parse error, with the key of a redefinition named as the
/// scene wrote it. toml++ 3.3 quotes that key ("cannot redefine existing array '...' as
/// table", "cannot insert '...' into existing inline table") from a record of the text
/// that holds a quoted key's first characters twice: ["mesh"] after [[mesh]] is named
/// '"memesh"'. The key between its first and last quote is replaced by the key read
/// from the line the error points at.
std::string toml_message(const toml::parse_error& error, std::string_view text) {
    std::string message(error.description());
    const std::size_t open = message.find('\'');
    const std::size_t close = message.rfind('\'');
    if (message.find("cannot redefine existing") == std::string::npos &&
        message.find("cannot insert") == std::string::npos) {
        return message;
    }
    if (open == std::string::npos || open == close) {
        return message;
    }
    std::size_t begin = 0; // of the error's line in text
    for (auto n = error.source().begin.line; n > 1 && begin != std::string_view::npos;
         --n) {
        begin = text.find('\n', begin);
        begin = begin == std::string_view::npos ? begin : begin + 1;
    }
    if (begin == std::string_view::npos) {
        return message;
    }
    const std::string_view line = text.substr(begin, text.find('\n', begin) - begin);
    const std::string key = key_written_on(line, error.source().begin.column);
    return key.empty() ? message : message.replace(open + 1, close - open - 1, key);
}

} // namespace

/// Rejects a dotted key of more than max_key_parts parts anywhere in `text`, before the
/// parser (which recurses once per part) sees it. Outside strings and comments, a dot
/// joins two parts of one key or the two halves of a float; a run of dots is broken only
/// by punctuation ('=', ',', brackets, braces) or a line break.
void check_key_depth(const Context& c, std::string_view text) {
    int line = 1, dots = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '"' || ch == '\'') { // skip a string, one line or three-quoted
            const std::size_t end = past_string(text, i);
            line +=
                static_cast<int>(std::count(text.begin() + i, text.begin() + end, '\n'));
            i = end - 1;
        } else if (ch == '#') {
            while (i + 1 < text.size() && text[i + 1] != '\n') {
                ++i;
            }
        } else if (ch == '.') {
            if (++dots >= max_key_parts) {
                throw Error(fmt::format("{}:{}: a dotted key has more than {} parts",
                                        c.file, line, max_key_parts));
            }
        } else if (ch == '\n' || ch == '=' || ch == ',' || ch == '[' || ch == ']' ||
                   ch == '{' || ch == '}') {
            line += ch == '\n';
            dots = 0;
        }
    }
}

/// The scene's TOML document, as toml++ reads it with a 0 of the same length in place of
/// each number below 2^-1022 (tiny_numbers), whose value the loader reads itself into
/// c.own_numbers: every column stays where it was, and toml++ reads the same on every
/// standard library. Where a 0 stood anywhere but in a float's place, the text is read as
/// written, and so is a text with an error (the error is the text's as written, unless
/// that is toml++ refusing a tiny number).
toml::table parse_toml(Context& c) {
    const std::vector<std::size_t> tiny = tiny_numbers(c.text);
    std::string zeroed(c.text);
    std::set<TextPlace> tiny_ends; // where toml++ reports refusing one
    // The place of each, counted from the one before.
    std::size_t i = c.text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
    TextPlace place{1, 1};
    for (const std::size_t at : tiny) {
        for (; i < at; ++i) {
            const bool continuation =
                (static_cast<unsigned char>(c.text[i]) & 0xC0) == 0x80;
            place = c.text[i] == '\n'
                        ? TextPlace{place.first + 1, 1}
                        : TextPlace{place.first, place.second + !continuation};
        }
        const std::string_view token = bare_run(c.text, at);
        c.own_numbers[place] = *read_decimal_float(token);
        tiny_ends.insert({place.first, place.second + token.size()});
        const std::size_t digits = token[0] == '-' || token[0] == '+' ? 1 : 0;
        zeroed.replace(at + digits, token.size() - digits,
                       "0." + std::string(token.size() - digits - 2, '0'));
    }
    std::optional<toml::parse_error> zeroed_error;
    try {
        toml::table root = toml::parse(zeroed, c.file);
        std::set<TextPlace> floats;
        float_places(root, floats);
        if (std::all_of(c.own_numbers.begin(), c.own_numbers.end(),
                        [&](const auto& own) { return floats.count(own.first) != 0; })) {
            return root;
        }
    } catch (const toml::parse_error& error) {
        zeroed_error = error;
    }
    c.own_numbers.clear();
    try {
        return toml::parse(c.text, c.file);
    } catch (const toml::parse_error& error) {
        const bool refused = tiny_ends.count({error.source().begin.line,
                                              error.source().begin.column}) != 0;
        const toml::parse_error& shown = refused && zeroed_error ? *zeroed_error : error;
        c.fail(shown.source(), "(syntax)", toml_message(shown, c.text));
    }
}

} // namespace exactpixels::scene_format
