// exactpixels coverage: how many triangles cover each pixel centre (chapter 2).
//
// Standard input: a first line "W H" (the frame's size in pixels), then one triangle per
// line, "x0 y0 x1 y1 x2 y2" (pixels, origin top-left, y down, decimal numbers). Blank
// lines are skipped. Output: H lines of W space-separated counts, on standard output or,
// with -o FILE, written all or nothing to FILE. Malformed input or a failed write: a
// message naming the line and the value (or the file) on stderr, exit code 2. Chapter 10
// adds the fast traversals `runs` and `masks`, exact and therefore fixed point only.
#include "commands.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/coverage_reader.hpp"
#include "exactpixels/raster/edge_rasterizer.hpp"
#ifdef EXACTPIXELS_HAS_FAST // chapter 10's layer (a chapter 2 kit has not got it)
#include "exactpixels/fast/block_masks.hpp"
#include "exactpixels/fast/row_runs.hpp"
#endif

#include <fmt/format.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <string>

namespace exactpixels::cli {

namespace {

/// Every rasterizer the command offers: chapters 1 and 2's, and chapter 10's two fast
/// traversals (covered runs per row, 8 x 8 masks).
enum class CoverageRasterizer { scanline, edge, edge8x8, runs, masks };

#ifdef EXACTPIXELS_HAS_FAST
/// Adds 1 to counts[y * width + x] for every pixel the triangle v (pixels) covers, drawn
/// by chapter 10's runs or masks (fixed point). Throws Error naming a vertex out of range.
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
#endif

/// Chapters 1 and 2's rasterizer for one of theirs (runs and masks are chapter 10's).
RasterizerKind chapter2_kind(CoverageRasterizer kind) {
    return kind == CoverageRasterizer::scanline ? RasterizerKind::scanline
           : kind == CoverageRasterizer::edge   ? RasterizerKind::edge
                                                : RasterizerKind::edge8x8;
}

/// Reads the frame and the triangles from standard input and counts the coverage with
/// `kind` in `precision`; sets `viewport` to the frame read.
std::vector<int> count_input(CoverageRasterizer kind, CoveragePrecision precision,
                             Viewport& viewport) {
#ifdef EXACTPIXELS_HAS_FAST
    if (kind == CoverageRasterizer::runs || kind == CoverageRasterizer::masks) {
        return count_coverage(
            std::cin,
            [kind](std::vector<int>& c, Viewport frame, const std::array<Point2, 3>& v) {
                add_fast_coverage(c, frame, v, kind);
            },
            viewport);
    }
#endif
    return count_coverage(std::cin, chapter2_kind(kind), precision, viewport);
}

} // namespace

void add_coverage_command(CLI::App& app, int& exit_code) {
    struct Options {
        CoverageRasterizer rasterizer = CoverageRasterizer::edge8x8;
        CoveragePrecision precision = CoveragePrecision::fixed;
        std::string output; // the file to write (not given: standard output)
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand(
        "coverage", "Read 'W H' and then one triangle 'x0 y0 x1 y1 x2 y2' per line from "
                    "standard input; print how many triangles cover each pixel centre");
    const std::map<std::string, CoverageRasterizer> rasterizers{
        {"scanline", CoverageRasterizer::scanline},
        {"edge", CoverageRasterizer::edge},
        {"edge8x8", CoverageRasterizer::edge8x8},
#ifdef EXACTPIXELS_HAS_FAST
        {"runs", CoverageRasterizer::runs},
        {"masks", CoverageRasterizer::masks},
#endif
    };
    const std::map<std::string, CoveragePrecision> precisions{
        {"fixed", CoveragePrecision::fixed}, {"float", CoveragePrecision::floating}};
    command
        ->add_option("--rasterizer", options->rasterizer,
                     "scanline (chapter 1), edge (bounding box), edge8x8 (8x8 blocks), "
                     "runs or masks (chapter 10: covered runs, 8x8 masks; fixed only)")
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
        report_errors("coverage", exit_code, [&] {
            const bool fast = options->rasterizer == CoverageRasterizer::runs ||
                              options->rasterizer == CoverageRasterizer::masks;
            if (fast && options->precision != CoveragePrecision::fixed) {
                throw Error("--rasterizer runs and masks are exact: they work in fixed "
                            "point only (--precision fixed)");
            }
            if (output_option->count() > 0) {
                check_output(options->output, "coverage", // before reading the input
                             std::span(&standard_input, 1));
            }
            Viewport viewport{0, 0};
            const CoverageRasterizer kind = options->rasterizer;
            // A failed read of standard input ends std::cin as its end would: the error
            // flag of stdin (which std::cin reads through) tells the two apart, and a
            // failed read is an error, whatever the reader made of the input before it.
            const auto unread = [] {
                return Error("standard input: cannot read it to its end (a read failed)");
            };
            std::vector<int> counts;
            try {
                counts = count_input(kind, options->precision, viewport);
            } catch (const Error&) {
                if (std::ferror(stdin)) {
                    throw unread();
                }
                throw;
            }
            if (std::ferror(stdin)) {
                throw unread();
            }
            const std::string out = format_counts(counts, viewport);
            if (output_option->count() > 0) {
                write_file_atomically(options->output, "coverage", out,
                                      std::span(&standard_input, 1));
            } else {
                write_standard_output(out);
            }
        });
    });
}

} // namespace exactpixels::cli
