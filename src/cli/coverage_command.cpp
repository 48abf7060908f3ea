// exactpixels coverage: how many triangles cover each pixel centre (chapter 2).
//
// Standard input: a first line "W H" (the frame's size in pixels), then one triangle per
// line, "x0 y0 x1 y1 x2 y2" (pixels, origin top-left, y down, decimal numbers). Blank
// lines are skipped. Standard output: H lines of W space-separated counts. Malformed
// input: a message naming the line and the value on stderr, exit code 2. Chapter 9
// adds the fast traversals `runs` and `masks`, exact and therefore fixed point only.
#include "commands.hpp"

#include "exactpixels/block_masks.hpp"
#include "exactpixels/edge_rasterizer.hpp"
#include "exactpixels/error.hpp"
#include "exactpixels/row_runs.hpp"

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

/// The largest frame the command draws, per side (keeps the count grid modest).
constexpr int max_frame_side = 16384;

/// Every rasterizer the command offers: chapters 1 and 2's, and chapter 9's two fast
/// traversals (covered runs per row, 8 x 8 masks).
enum class CoverageRasterizer { scanline, edge, edge8x8, runs, masks };

/// Adds 1 to counts[y * width + x] for every pixel the triangle v (pixels) covers, drawn
/// by chapter 9's runs or masks (fixed point). Throws Error naming a vertex out of range.
void add_fast_coverage(std::vector<int>& counts, Viewport viewport,
                       const std::array<Point2, 3>& v, CoverageRasterizer kind) {
    std::array<FixedPoint2, 3> f;
    for (int i = 0; i < 3; ++i) {
        try {
            f[i] = snap_in_range(v[i]);
        } catch (const Error& error) {
            throw Error(fmt::format("vertex {}: {}", i, error.what()));
        }
    }
    const EdgeSetup<FixedEdge> s = setup_edges(f);
    if (s.empty) {
        return;
    }
    const auto count = [&](int x, int y) {
        ++counts[static_cast<std::size_t>(y) * static_cast<std::size_t>(viewport.width) +
                 static_cast<std::size_t>(x)];
    };
    const PixelRect r = pixel_bounds(f, viewport);
    if (kind == CoverageRasterizer::runs) {
        traverse_runs_fast(s, r, [&](Span run) {
            for (int x = run.x_begin; x < run.x_end; ++x) {
                count(x, run.y);
            }
        });
    } else {
        traverse_block_masks(s, r, [&](BlockMask m) { for_each_pixel(m, count); });
    }
}

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
std::vector<int> run_coverage(std::istream& in, CoverageRasterizer kind,
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
            switch (kind) {
            case CoverageRasterizer::scanline:
                add_coverage(counts, viewport, v, RasterizerKind::scanline, precision);
                break;
            case CoverageRasterizer::edge:
                add_coverage(counts, viewport, v, RasterizerKind::edge, precision);
                break;
            case CoverageRasterizer::edge8x8:
                add_coverage(counts, viewport, v, RasterizerKind::edge8x8, precision);
                break;
            case CoverageRasterizer::runs:
            case CoverageRasterizer::masks:
                add_fast_coverage(counts, viewport, v, kind);
                break;
            }
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
        CoverageRasterizer rasterizer = CoverageRasterizer::edge8x8;
        CoveragePrecision precision = CoveragePrecision::fixed;
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "coverage", "Read 'W H' and then one triangle 'x0 y0 x1 y1 x2 y2' per line from "
                    "standard input; print how many triangles cover each pixel centre");
    const std::map<std::string, CoverageRasterizer> rasterizers{
        {"scanline", CoverageRasterizer::scanline},
        {"edge", CoverageRasterizer::edge},
        {"edge8x8", CoverageRasterizer::edge8x8},
        {"runs", CoverageRasterizer::runs},
        {"masks", CoverageRasterizer::masks}};
    const std::map<std::string, CoveragePrecision> precisions{
        {"fixed", CoveragePrecision::fixed}, {"float", CoveragePrecision::floating}};
    command
        ->add_option("--rasterizer", options->rasterizer,
                     "scanline (chapter 1), edge (bounding box), edge8x8 (8x8 blocks), "
                     "runs or masks (chapter 9: covered runs, 8x8 masks; fixed only)")
        ->transform(CLI::CheckedTransformer(rasterizers, CLI::ignore_case))
        ->default_str("edge8x8");
    command
        ->add_option("--precision", options->precision,
                     "fixed (1/256 px, exact) or float (float for edge rasterizers, "
                     "double for scanline)")
        ->transform(CLI::CheckedTransformer(precisions, CLI::ignore_case))
        ->default_str("fixed");
    command->callback([options, &exit_code] {
        try {
            const bool fast = options->rasterizer == CoverageRasterizer::runs ||
                              options->rasterizer == CoverageRasterizer::masks;
            if (fast && options->precision != CoveragePrecision::fixed) {
                throw Error("--rasterizer runs and masks are exact: they work in fixed "
                            "point only (--precision fixed)");
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
            std::fwrite(out.data(), 1, out.size(), stdout);
        } catch (const Error& error) {
            fmt::print(stderr, "exactpixels coverage: {}\n", error.what());
            exit_code = exit_bad_input;
        }
    });
}

} // namespace exactpixels::cli
