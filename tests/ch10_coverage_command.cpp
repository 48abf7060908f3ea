// Chapter 10 tests: `exactpixels coverage --rasterizer runs|masks` count the same pixels
// as chapter 2's rasterizers, refuse float precision, and report bad input like them.
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <string>

using exactpixels::testing::cli_path;
using exactpixels::testing::run_command;

namespace {

// Three triangles in an 8 x 6 frame (one partly outside), plus a fan of four slivers
// around (3.5, 2.5) whose shared edges pass through pixel centres.
const std::string input = "8 6\n"
                          "0.5 0.5 5.5 0.5 5.5 5.5\n"
                          "0.5 5.5 0.5 0.5 5.5 5.5\n"
                          "3 -2 12 3 3 7.2\n"
                          "3.5 2.5 7.5 2.5 7.5 3\n"
                          "3.5 2.5 7.5 3 7.5 5.5\n";

/// The counts chapter 2's pixel walk prints for `input` (its own tests check it).
std::string reference() {
    const auto result = run_command(cli_path() + " coverage --rasterizer edge", input);
    REQUIRE(result.exit_code == 0);
    return result.out;
}

} // namespace

TEST_CASE("coverage: --rasterizer runs prints the pixel walk's counts") {
    const auto result = run_command(cli_path() + " coverage --rasterizer runs", input);
    CHECK(result.exit_code == 0);
    CHECK(result.err.empty());
    CHECK(result.out == reference());
    CHECK(result.out.find('2') != std::string::npos); // overlaps are counted
}

TEST_CASE("coverage: --rasterizer masks prints the pixel walk's counts") {
    const auto result = run_command(cli_path() + " coverage --rasterizer masks", input);
    CHECK(result.exit_code == 0);
    CHECK(result.err.empty());
    CHECK(result.out == reference());
}

TEST_CASE("coverage: runs and masks refuse float precision with exit code 2") {
    for (const char* kind : {"runs", "masks"}) {
        const auto result = run_command(
            cli_path() + " coverage --precision float --rasterizer " + kind, input);
        INFO(kind);
        CHECK(result.exit_code == 2);
        CHECK(result.out.empty());
        CHECK(result.err.find("fixed point only") != std::string::npos);
    }
}

TEST_CASE("coverage: runs and masks name the line and vertex of a bad coordinate") {
    for (const char* kind : {"runs", "masks"}) {
        const auto result = run_command(cli_path() + " coverage --rasterizer " + kind,
                                        "4 4\n0 0 3 0 3 3\n0 0 3 0 3 2000000\n");
        INFO(kind);
        CHECK(result.exit_code == 2);
        CHECK(result.out.empty());
        CHECK(result.err.find("line 3: vertex 2: coordinate 2000000 px is outside") !=
              std::string::npos);
    }
}
