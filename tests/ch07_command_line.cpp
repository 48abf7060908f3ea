// Chapter 0's rule for the command line, tested on all three commands (so in chapter 7's
// suite, whose kit has every layer): every usage mistake on the command line is bad
// input like any other:
// exit code 2 and one line on standard error that names the option, with long words cut.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/printable.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

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
    CHECK(result.err.find(std::string(4096, 'x') + "...") != std::string::npos);
    CHECK(result.err.find(std::string(4097, 'x')) == std::string::npos);

    // A huge word in the input (here a scene's value) is cut the same way.
    const auto folder = std::filesystem::temp_directory_path() /
                        ("exactpixels-huge-word-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "scene.toml")
        << "[[mesh]]\nprimitive = \"" << token.substr(0, 10000) << "\"\n";
    const auto input = run_command(cli_path() + " render '" +
                                   (folder / "scene.toml").string() + "' -o '" +
                                   (folder / "out.png").string() + "'");
    std::filesystem::remove_all(folder);
    CHECK(input.exit_code == 2);
    CHECK(lines_in(input.err) == 1);
    // The word is the value in its quotes: a quote and 4095 letters, then the ellipsis.
    std::string cut = "'"; // built by appending: GCC 12's -Wrestrict misfires on "'" + s
    cut.append(4095, 'x').append("...");
    CHECK(input.err.find(cut) != std::string::npos);
    CHECK(input.err.find(std::string(4096, 'x')) == std::string::npos);
}

TEST_CASE("a long path is named whole in the message") {
    // A temporary folder can be deep (macOS's is /var/folders/../T/, a grader's is inside
    // its own scratch folder): the message names the file whole all the same, as long as
    // the system accepts the path at all (here 600 characters, beyond any short cut).
    std::string path = "/nonexistent";
    while (path.size() < 600) {
        path += "/a-folder-whose-name-is-long-enough-to-matter";
    }
    path += "/scene.toml";
    const auto result = run_command(cli_path() + " render '" + path + "' -o /dev/null");
    CHECK(result.exit_code == 2);
    CHECK(lines_in(result.err) == 1);
    CHECK(result.err.find(path) != std::string::npos);
}

TEST_CASE("a message escapes every control character and keeps UTF-8 letters") {
    using exactpixels::printable;
    const std::string every_c0 = [] {
        std::string text;
        for (int c = 0; c < 0x20; ++c) {
            text += static_cast<char>(c);
        }
        return text + '\x7f';
    }();
    const std::string escaped = printable(every_c0);
    CHECK(escaped == "\\0\\x01\\x02\\x03\\x04\\x05\\x06\\x07\\x08\\t\\n\\x0b\\x0c\\r"
                     "\\x0e\\x0f\\x10\\x11\\x12\\x13\\x14\\x15\\x16\\x17\\x18\\x19"
                     "\\x1a\\x1b\\x1c\\x1d\\x1e\\x1f\\x7f");
    // UTF-8 letters stay; the C1 controls (U+0080 to U+009F, 0x9b begins an escape
    // sequence) and bytes that are not UTF-8 are written out.
    CHECK(printable("caf\xc3\xa9 \xe2\x82\xac") == "caf\xc3\xa9 \xe2\x82\xac");
    CHECK(printable("a\xc2\x9b"
                    "31m") == "a\\u009b31m");
    CHECK(printable("\xff\xc3(\xe2\x82") == "\\xff\\xc3(\\xe2\\x82");
    // Applied twice it changes nothing, so a message wrapped in another stays as it was.
    CHECK(printable(escaped) == escaped);
    // Every Error escapes its message, and keeps what follows a NUL.
    CHECK(std::string(exactpixels::Error(std::string("a\0b\x1b", 4)).what()) ==
          "a\\0b\\x1b");
}

TEST_CASE("a control character on the command line is escaped in the message") {
    // CLI11 quotes the argument raw; the message must still be one visible line.
    const auto result = run_command(cli_path() + " coverage --rasterizer \"$(printf "
                                                 "'a\\033[31mb\\007')\"");
    CHECK(result.exit_code == 2);
    CHECK(lines_in(result.err) == 1);
    CHECK(result.err.find("a\\x1b[31mb\\x07") != std::string::npos);
}
