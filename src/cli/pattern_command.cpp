#include "commands.hpp"

#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <string>

namespace exactpixels::cli {

void add_pattern_command(CLI::App& app, int& exit_code) {
    struct Options {
        std::string output = "f.png";
        int cell = 8;
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand("pattern", "Write the red-on-blue \"F\" test "
                                                      "pattern of chapter 0 as a PNG");
    command->add_option("-o,--output", options->output, "PNG file to write")
        ->capture_default_str();
    command->add_option("--cell", options->cell, "Pixels per glyph cell")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    command->callback([options, &exit_code] {
        report_errors("pattern", exit_code,
                      [&] { write_png(options->output, draw_f_pattern(options->cell)); });
    });
}

} // namespace exactpixels::cli
