// build/bin/exactpixels: the book's command-line program. Chapters add subcommands.
#include "commands.hpp"

#include <fmt/format.h>

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"Exact Pixels: the book's rasterizers and texture mappers from the "
                 "command line"};
    app.set_version_flag("--version", fmt::format("exactpixels {}", EXACTPIXELS_VERSION));
    app.require_subcommand(0, 1);

    int exit_code = 0;
    // Each subcommand is there when the library layer it needs is (an assignment kit
    // carries only its chapter's layers; see src/CMakeLists.txt).
    exactpixels::cli::add_pattern_command(app, exit_code);
#ifdef EXACTPIXELS_HAS_RASTER
    exactpixels::cli::add_coverage_command(app, exit_code);
#endif
#ifdef EXACTPIXELS_HAS_SCENE
    exactpixels::cli::add_render_command(app, exit_code);
#endif

    CLI11_PARSE(app, argc, argv);
    if (app.get_subcommands().empty()) {
        std::fputs(app.help().c_str(), stdout);
    }
    return exit_code;
}
