// build/bin/exactpixels: the book's command-line program. Chapters add subcommands.
//
// Exit codes: 0 success; 2 (exit_bad_input) for any bad input, usage mistake or failed
// write, with one line on standard error naming the file, line, option or value.
#include "commands.hpp"

#include "exactpixels/base/atomic_file.hpp"
#include "exactpixels/base/error.hpp"
#ifdef EXACTPIXELS_HAS_FAST // chapter 10's layer (an earlier chapter's kit has not got it)
#include "exactpixels/fast/simd.hpp"
#endif

#include <fmt/format.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <system_error>

int main(int argc, char** argv) {
    // A file size limit (ulimit -f) must fail a write with EFBIG, which the writers
    // report and clean up after, rather than kill the program half way through a file.
    std::signal(SIGXFSZ, SIG_IGN);
    // Killed while a file is being written (Ctrl-C, kill, a closed pipe): its temporary
    // file goes too.
    exactpixels::remove_temporaries_on_signals();

    // EXACTPIXELS_SIMD, when set, must name a vector instruction set this CPU has
    // (fast/simd.hpp): refused at once, before any command runs.
#ifdef EXACTPIXELS_HAS_FAST
    try {
        (void)exactpixels::chosen_simd();
    } catch (const exactpixels::Error& error) {
        exactpixels::cli::print_error("", error.what());
        return exactpixels::cli::exit_bad_input;
    }
#endif

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

    try {
        app.parse(argc, argv);
        if (app.get_subcommands().empty()) {
            std::fputs(app.help().c_str(), stdout);
        }
    } catch (const CLI::CallForHelp& request) { // --help, --version: exit code 0
        return app.exit(request);
    } catch (const CLI::CallForAllHelp& request) {
        return app.exit(request);
    } catch (const CLI::CallForVersion& request) {
        return app.exit(request);
    } catch (const CLI::ParseError& error) { // a usage mistake: like any bad input
        exactpixels::cli::print_error("", std::string(error.what()) +
                                              " (see exactpixels --help)");
        return exactpixels::cli::exit_bad_input;
    } catch (const std::system_error& error) { // fmt::print could not write its output
        exactpixels::cli::print_error("", error.what());
        return exactpixels::cli::exit_bad_input;
    }
    // Whatever was printed must have arrived: a full disk or a closed pipe is an error.
    // (A command that failed has said so already.)
    if (exit_code == 0 && (std::fflush(stdout) != 0 || std::ferror(stdout) != 0)) {
        exactpixels::cli::print_error(
            "", fmt::format("standard output: cannot write ({})",
                            errno != 0 ? std::strerror(errno) : "write failed"));
        return exactpixels::cli::exit_bad_input;
    }
    return exit_code;
}
