#include "support/process.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace exactpixels::testing {

namespace {
std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}
} // namespace

CommandResult run_command(const std::string& command, const std::string& input) {
    const auto folder = std::filesystem::temp_directory_path() /
                        ("exactpixels-run-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const auto in = folder / "in", out = folder / "out", err = folder / "err";
    std::ofstream(in, std::ios::binary) << input;
    const std::string full = command + " <'" + in.string() + "' >'" + out.string() +
                             "' 2>'" + err.string() + "'";
    const int status = std::system(full.c_str());
    CommandResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = slurp(out);
    result.err = slurp(err);
    std::filesystem::remove_all(folder);
    return result;
}

// A cross build's emulator (CMAKE_CROSSCOMPILING_EMULATOR, words separated by spaces);
// empty in a native build and in an assignment kit.
#ifndef EXACTPIXELS_EMULATOR
#define EXACTPIXELS_EMULATOR ""
#endif

std::string program_command(const std::string& path) {
    const std::string emulator = EXACTPIXELS_EMULATOR;
    return (emulator.empty() ? "" : emulator + " ") + "'" + path + "'";
}

std::string cli_path() {
    return program_command(EXACTPIXELS_CLI);
}

} // namespace exactpixels::testing
