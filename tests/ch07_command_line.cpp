// Chapter 0's rule for the command line, tested on all three commands (so in chapter 7's
// suite, whose kit has every layer): every usage mistake on the command line is bad
// input like any other:
// exit code 2 and one line on standard error that names the option, with long words cut.
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <string>

using exactpixels::testing::cli_path;
using exactpixels::testing::run_command;

namespace {
/// How many lines `text` has.
long lines_in(const std::string& text) {
    return static_cast<long>(std::count(text.begin(), text.end(), '\n'));
}
} // namespace

TEST_CASE("every command-line usage error exits 2 with one line naming the option") {
    struct Mistake {
        std::string arguments; // after the program's name
        std::string named;     // what the message must name
    };
    const Mistake mistakes[] = {
        {"pattern --bogus", "--bogus"},
        {"pattern --cell", "--cell"},
        {"pattern --cell 0", "--cell"},
        {"pattern --cell many", "--cell"},
        {"coverage --rasterizer diagonal", "--rasterizer"},
        {"coverage --precision half", "--precision"},
        {"render a.toml b.toml", "b.toml"},
        {"render -o", "--output"},
        {"paint", "paint"},
    };
    for (const Mistake& mistake : mistakes) {
        CAPTURE(mistake.arguments);
        const auto result = run_command(cli_path() + " " + mistake.arguments);
        CHECK(result.exit_code == 2);
        CHECK(lines_in(result.err) == 1);
        CHECK(result.err.find(mistake.named) != std::string::npos);
        CHECK(result.out.empty());
    }
    // --help and --version are not mistakes.
    CHECK(run_command(cli_path() + " render --help").exit_code == 0);
    CHECK(run_command(cli_path() + " --version").exit_code == 0);
}

TEST_CASE("a huge token is cut with an ellipsis in the message") {
    const std::string token(100000, 'x'); // near the kernel's limit for one argument
    const auto result = run_command(cli_path() + " coverage --rasterizer " + token);
    CHECK(result.exit_code == 2);
    CHECK(lines_in(result.err) == 1);
    CHECK(result.err.find("--rasterizer") != std::string::npos);
    CHECK(result.err.find(std::string(80, 'x') + "...") != std::string::npos);
    CHECK(result.err.find(std::string(81, 'x')) == std::string::npos);

    // A huge word in the input is cut the same way.
    const auto input =
        run_command(cli_path() + " coverage", "2 " + token.substr(0, 1000) + "\n");
    CHECK(input.exit_code == 2);
    CHECK(input.err.size() < 300);
    CHECK(input.err.find("...") != std::string::npos);
}
