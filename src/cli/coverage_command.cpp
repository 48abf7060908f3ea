// exactpixels coverage: how many triangles cover each pixel centre (chapter 2).
//
// Standard input: a first line "W H" (the frame's size in pixels), then one triangle per
// line, "x0 y0 x1 y1 x2 y2" (pixels, origin top-left, y down, decimal numbers). Blank
// lines are skipped. Output: H lines of W space-separated counts, on standard output or,
// with -o FILE, written all or nothing to FILE. Malformed input or a failed write: a
// message naming the line and the value (or the file) on stderr, exit code 2.
#include "commands.hpp"

#include "exactpixels/atomic_file.hpp"
#include "exactpixels/edge_rasterizer.hpp"
#include "exactpixels/error.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace exactpixels::cli {

namespace {

/// The largest frame the command draws, per side, pixels.
constexpr int max_frame_side = 16384;
/// The most pixels of a frame (2^24, 64 MiB of counts): checked before the count grid
/// and the output text (2 bytes or more per pixel) are allocated.
constexpr long long max_frame_pixels = 1LL << 24;

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

/// The finite decimal number `word` on line `line`, or an Error naming both.
double parse_number(std::string_view word, int line) {
    const std::string_view digits = word.size() > 1 && word[0] == '+'
                                        ? word.substr(1)
                                        : word; // from_chars has no '+'
    double value = 0.0;
    const char* last = digits.data() + digits.size();
    const auto [end, status] = std::from_chars(digits.data(), last, value);
    if (status != std::errc() || end != last) {
        throw Error(fmt::format("line {}: expected a number, found '{}'", line, word));
    }
    if (!std::isfinite(value)) {
        throw Error(fmt::format("line {}: '{}' is not a finite number", line, word));
    }
    return value;
}

/// The frame size from the header line "W H".
Viewport parse_header(std::string_view text, int line) {
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
    if (static_cast<long long>(size[0]) * size[1] > max_frame_pixels) {
        throw Error(
            fmt::format("line {}: a {}x{} frame is more than the {} pixels allowed", line,
                        size[0], size[1], max_frame_pixels));
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

/// Reads the whole of `in`, draws every triangle, returns the counts row by row.
std::vector<int> run_coverage(std::istream& in, RasterizerKind kind,
                              CoveragePrecision precision, Viewport& viewport) {
    std::string text;
    int line = 0;
    bool have_header = false;
    std::vector<int> counts;
    while (std::getline(in, text)) {
        ++line;
        if (words_of(text).empty()) {
            continue;
        }
        if (!have_header) {
            viewport = parse_header(text, line);
            counts.assign(static_cast<std::size_t>(viewport.width) *
                              static_cast<std::size_t>(viewport.height),
                          0);
            have_header = true;
            continue;
        }
        const std::array<Point2, 3> v = parse_triangle(text, line);
        try {
            add_coverage(counts, viewport, v, kind, precision);
        } catch (const Error& error) {
            throw Error(fmt::format("line {}: {}", line, error.what()));
        }
    }
    if (!have_header) {
        throw Error(
            fmt::format("line {}: expected the frame size 'W H', found the end of "
                        "the input",
                        line + 1));
    }
    return counts;
}

} // namespace

void add_coverage_command(CLI::App& app, int& exit_code) {
    struct Options {
        RasterizerKind rasterizer = RasterizerKind::edge8x8;
        CoveragePrecision precision = CoveragePrecision::fixed;
        std::string output; // the file to write (not given: standard output)
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "coverage", "Read 'W H' and then one triangle 'x0 y0 x1 y1 x2 y2' per line from "
                    "standard input; print how many triangles cover each pixel centre");
    const std::map<std::string, RasterizerKind> rasterizers{
        {"scanline", RasterizerKind::scanline},
        {"edge", RasterizerKind::edge},
        {"edge8x8", RasterizerKind::edge8x8}};
    const std::map<std::string, CoveragePrecision> precisions{
        {"fixed", CoveragePrecision::fixed}, {"float", CoveragePrecision::floating}};
    command
        ->add_option("--rasterizer", options->rasterizer,
                     "scanline (chapter 1), edge (bounding box) or edge8x8 (8x8 blocks)")
        ->transform(CLI::CheckedTransformer(rasterizers, CLI::ignore_case))
        ->default_str("edge8x8");
    command
        ->add_option("--precision", options->precision,
                     "fixed (1/256 px, exact) or float (float for edge rasterizers, "
                     "double for scanline)")
        ->transform(CLI::CheckedTransformer(precisions, CLI::ignore_case))
        ->default_str("fixed");
    const CLI::Option* output_option = command->add_option(
        "-o,--output", options->output,
        "Write the counts to this file, all or nothing (default: standard output)");
    command->callback([options, output_option, &exit_code] {
        try {
            if (output_option->count() > 0) {
                check_output(options->output, "coverage"); // before reading the input
            }
            Viewport viewport{0, 0};
            const std::vector<int> counts =
                run_coverage(std::cin, options->rasterizer, options->precision, viewport);
            std::string out;
            for (int y = 0; y < viewport.height; ++y) {
                for (int x = 0; x < viewport.width; ++x) {
                    const auto i = static_cast<std::size_t>(y) *
                                       static_cast<std::size_t>(viewport.width) +
                                   static_cast<std::size_t>(x);
                    if (x > 0) {
                        out += ' ';
                    }
                    out += std::to_string(counts[i]);
                }
                out += '\n';
            }
            if (output_option->count() > 0) {
                write_file_atomically(options->output, "coverage", out);
            } else {
                write_standard_output(out);
            }
        } catch (const Error& error) {
            print_error("coverage", error.what());
            exit_code = exit_bad_input;
        }
    });
}

} // namespace exactpixels::cli
