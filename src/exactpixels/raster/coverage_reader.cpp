#include "exactpixels/raster/coverage_reader.hpp"

#include "exactpixels/base/decimal_from_chars.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/fill_work.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace exactpixels {

namespace {

/// The whitespace-separated words of a line.
std::vector<std::string_view> words_of(std::string_view line) {
    std::vector<std::string_view> words;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() &&
               (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) {
            ++i;
        }
        const std::size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') {
            ++i;
        }
        if (i > start) {
            words.push_back(line.substr(start, i - start));
        }
    }
    return words;
}

/// The finite decimal number `word` on line `line`, or an Error naming both. The form is
/// the one coverage_reader.hpp states: one optional sign, then digits with an optional
/// point and exponent, as from_chars reads them. from_chars takes no '+' and a '-' of its
/// own, so the sign is taken here, once: "+-0.5" and "-+1" have two and are refused.
double parse_number(std::string_view word, int line) {
    const bool has_sign = !word.empty() && (word[0] == '+' || word[0] == '-');
    const std::string_view digits = has_sign ? word.substr(1) : word;
    double value = 0.0;
    const char* last = digits.data() + digits.size();
    const auto [end, status] = decimal_from_chars(digits.data(), last, value);
    if (digits.empty() || digits[0] == '-' || status == std::errc::invalid_argument ||
        end != last) {
        throw Error(fmt::format("line {}: expected a number, found '{}'", line, word));
    }
    if (status == std::errc::result_out_of_range) {
        throw Error(fmt::format("line {}: '{}' is too large or too small for a double",
                                line, word));
    }
    if (!std::isfinite(value)) {
        throw Error(fmt::format("line {}: '{}' is not a finite number", line, word));
    }
    return word[0] == '-' ? -value : value;
}

/// The frame size from the header line "W H", at most `max_pixels` pixels.
Viewport parse_header(std::string_view text, int line, long long max_pixels) {
    const auto words = words_of(text);
    if (words.size() != 2) {
        throw Error(
            fmt::format("line {}: expected the frame size 'W H', found {} value(s)", line,
                        words.size()));
    }
    int size[2] = {0, 0};
    for (int i = 0; i < 2; ++i) {
        const double value = parse_number(words[i], line);
        if (value != std::floor(value) || value < 1 || value > max_frame_side) {
            throw Error(
                fmt::format("line {}: frame size '{}' is not a whole number from 1 "
                            "to {}",
                            line, words[i], max_frame_side));
        }
        size[i] = static_cast<int>(value);
    }
    if (static_cast<long long>(size[0]) * size[1] >
        std::min(max_pixels, max_frame_pixels)) {
        throw Error(
            fmt::format("line {}: a {}x{} frame is more than the {} pixels allowed", line,
                        size[0], size[1], std::min(max_pixels, max_frame_pixels)));
    }
    return {size[0], size[1]};
}

/// The triangle "x0 y0 x1 y1 x2 y2" of one line.
std::array<Point2, 3> parse_triangle(std::string_view text, int line) {
    const auto words = words_of(text);
    if (words.size() != 6) {
        throw Error(
            fmt::format("line {}: expected 6 numbers 'x0 y0 x1 y1 x2 y2', found {}", line,
                        words.size()));
    }
    std::array<Point2, 3> v;
    for (int i = 0; i < 3; ++i) {
        v[i] = {parse_number(words[2 * i], line), parse_number(words[2 * i + 1], line)};
    }
    return v;
}

/// Reads the next line of `in` (number `line`) into `text`, without its '\n'; false at
/// the end of the input. An Error when the line is longer than max_line_bytes, so an
/// endless line (/dev/zero) costs no more than that.
bool read_line(std::istream& in, std::string& text, int line) {
    text.clear();
    std::istream::int_type c = in.get();
    if (c == std::istream::traits_type::eof()) {
        return false;
    }
    while (c != std::istream::traits_type::eof() && c != '\n') {
        if (text.size() == max_line_bytes) {
            throw Error(fmt::format("line {}: longer than the {} bytes allowed", line,
                                    max_line_bytes));
        }
        text += static_cast<char>(c);
        c = in.get();
    }
    if (in.bad()) {
        throw Error(fmt::format("line {}: cannot read the input", line));
    }
    return true;
}

} // namespace

std::vector<int> count_coverage(std::istream& in, RasterizerKind kind,
                                CoveragePrecision precision, Viewport& viewport,
                                long long max_pixels) {
    return count_coverage(
        in,
        [&](std::vector<int>& counts, Viewport frame, const std::array<Point2, 3>& v) {
            add_coverage(counts, frame, v, kind, precision);
        },
        viewport, max_pixels);
}

namespace {

/// A triangle of the input (pixels) and the line it was read from.
struct InputTriangle {
    std::array<Point2, 3> corners;
    int line = 0;
};

/// The whole input: the frame and every triangle, their fill work within the limit.
struct CoverageInput {
    Viewport viewport{0, 0};
    std::vector<InputTriangle> triangles;
};

/// Reads all of `in`, refusing more than max_coverage_triangles triangles and a sum of
/// fill work (fill_work.hpp) beyond max_fill_work at the line that passes it, so that
/// an input over the limits is refused before anything is drawn.
CoverageInput read_coverage_input(std::istream& in, long long max_pixels) {
    CoverageInput input;
    std::string text;
    int line = 0;
    bool have_header = false;
    long long work = 0;
    while (read_line(in, text, line + 1)) {
        ++line;
        if (words_of(text).empty()) {
            continue;
        }
        if (!have_header) {
            input.viewport = parse_header(text, line, max_pixels);
            have_header = true;
            continue;
        }
        const std::array<Point2, 3> v = parse_triangle(text, line);
        if (input.triangles.size() == static_cast<std::size_t>(max_coverage_triangles)) {
            throw Error(fmt::format("line {}: more than the {} triangles allowed", line,
                                    max_coverage_triangles));
        }
        work += fill_work(v, input.viewport);
        if (work > max_fill_work) {
            throw Error(fmt::format("line {}: the triangles up to this line ask for {} "
                                    "pixels of drawing (their bounding boxes in the "
                                    "frame), more than the {} allowed",
                                    line, work, max_fill_work));
        }
        input.triangles.push_back({v, line});
    }
    if (!have_header) {
        throw Error(
            fmt::format("line {}: expected the frame size 'W H', found the end of "
                        "the input",
                        line + 1));
    }
    return input;
}

} // namespace

std::vector<int> count_coverage(std::istream& in, const CoverageDraw& draw,
                                Viewport& viewport, long long max_pixels) {
    const CoverageInput input = read_coverage_input(in, max_pixels);
    viewport = input.viewport;
    std::vector<int> counts(static_cast<std::size_t>(viewport.width) *
                                static_cast<std::size_t>(viewport.height),
                            0);
    for (const InputTriangle& t : input.triangles) {
        try {
            draw(counts, viewport, t.corners);
        } catch (const Error& error) {
            throw Error(fmt::format("line {}: {}", t.line, error.what()));
        }
    }
    return counts;
}

std::string format_counts(const std::vector<int>& counts, Viewport viewport) {
    std::string out;
    for (int y = 0; y < viewport.height; ++y) {
        for (int x = 0; x < viewport.width; ++x) {
            const auto i =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(viewport.width) +
                static_cast<std::size_t>(x);
            if (x > 0) {
                out += ' ';
            }
            out += std::to_string(counts[i]);
        }
        out += '\n';
    }
    return out;
}

} // namespace exactpixels
