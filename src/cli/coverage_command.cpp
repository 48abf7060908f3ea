// exactpixels coverage: how many triangles cover each pixel centre (chapter 2).
//
// Standard input: a first line "W H" (the frame's size in pixels), then one triangle per
// line, "x0 y0 x1 y1 x2 y2" (pixels, origin top-left, y down, decimal numbers). Blank
// lines are skipped. Output: H lines of W space-separated counts, on standard output or,
// with -o FILE, written all or nothing to FILE. Malformed input or a failed write: a
// message naming the line and the value (or the file) on stderr, exit code 2.
#include "commands.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/coverage_reader.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <iostream>
#include <map>
#include <string>

namespace exactpixels::cli {

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
            const std::vector<int> counts = count_coverage(std::cin, options->rasterizer,
                                                           options->precision, viewport);
            const std::string out = format_counts(counts, viewport);
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
