// Chapter 2 tests: `exactpixels coverage`, every rasterizer/precision pair, and the
// messages and exit code for malformed input.
#include "support/printing.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <string>
#include <utility>

using exactpixels::testing::cli_path;
using exactpixels::testing::run_command;

namespace {

// The two triangles of the absolute convention (15 and 10 pixels) and a third one
// overlapping them, partly outside the 8 x 6 frame: its outside part is not drawn.
const std::string input = "8 6\n"
                          "0.5 0.5 5.5 0.5 5.5 5.5\n"
                          "\n"
                          "0.5 5.5 0.5 0.5 5.5 5.5\n"
                          "3 -2 12 3 3 7.2\n";

// Counted by hand (exact fractions): the square [0, 5) x [0, 5) once, plus the third
// triangle (7.2 snaps to 1843/256): the columns x = 3 .. 7 between its upper edge
// y = -2 + (x - 3) 5/9 and its lower edge. The centre (7.5, 0.5) lies exactly on the
// upper edge, a right edge, so it stays out.
const std::string expected = "1 1 1 2 2 1 1 0\n"
                             "1 1 1 2 2 1 1 1\n"
                             "1 1 1 2 2 1 1 1\n"
                             "1 1 1 2 2 1 1 1\n"
                             "1 1 1 2 2 1 1 1\n"
                             "0 0 0 1 1 1 1 0\n";

void check_pair(const std::string& options) {
    const auto result = run_command(cli_path() + " coverage " + options, input);
    INFO("options: " << options << "\nstderr: " << result.err);
    CHECK(result.exit_code == 0);
    CHECK(result.out == expected);
    CHECK(result.err.empty());
}

void check_malformed(const std::string& text, const std::string& message) {
    const auto result = run_command(cli_path() + " coverage", text);
    INFO("input: " << text);
    CHECK(result.exit_code == 2);
    CHECK(result.out.empty());
    CHECK(result.err.find(message) != std::string::npos);
}

} // namespace

TEST_CASE("coverage: default options (edge8x8, fixed)" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    check_pair("");
}

TEST_CASE("coverage: --rasterizer scanline --precision fixed") {
    check_pair("--rasterizer scanline --precision fixed");
}

TEST_CASE("coverage: --rasterizer scanline --precision float") {
    check_pair("--rasterizer scanline --precision float");
}

TEST_CASE("coverage: --rasterizer edge --precision fixed" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    check_pair("--rasterizer edge --precision fixed");
}

TEST_CASE("coverage: --rasterizer edge --precision float" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    check_pair("--rasterizer edge --precision float");
}

TEST_CASE("coverage: --rasterizer edge8x8 --precision fixed" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    check_pair("--rasterizer edge8x8 --precision fixed");
}

TEST_CASE("coverage: --rasterizer edge8x8 --precision float" *
          doctest::description("points: 1; exercise: ch02-edge-bias")) {
    check_pair("--rasterizer edge8x8 --precision float");
}

TEST_CASE("coverage: an unknown option value is refused") {
    const auto result = run_command(cli_path() + " coverage --rasterizer zbuffer", input);
    CHECK(result.exit_code != 0);
    CHECK(result.err.find("zbuffer") != std::string::npos);
}

TEST_CASE("coverage: malformed input names the line and exits with 2") {
    SUBCASE("missing numbers") {
        check_malformed("4 4\n0 0 3 0 3\n", "line 2: expected 6 numbers");
    }
    SUBCASE("too many numbers") {
        check_malformed("4 4\n0 0 3 0 3 3 1\n", "line 2: expected 6 numbers");
    }
    SUBCASE("text") {
        check_malformed("4 4\n0 0 3 0 3 3\n0 0 three 0 3 3\n",
                        "line 3: expected a number, "
                        "found 'three'");
    }
    SUBCASE("NaN") {
        check_malformed("4 4\n\n0 0 3 nan 3 3\n", "line 3: 'nan' is not a finite number");
    }
    SUBCASE("infinity") {
        check_malformed("4 4\n0 0 3 0 inf 3\n", "line 2: 'inf' is not a finite number");
    }
    SUBCASE("a short header") {
        check_malformed("4\n0 0 3 0 3 3\n", "line 1: expected the frame size 'W H'");
    }
    SUBCASE("a header that is not a size") {
        check_malformed("4 2.5\n", "line 1: frame size '2.5'");
        check_malformed("0 3\n", "line 1: frame size '0'");
    }
    SUBCASE("no input at all") {
        check_malformed("", "line 1: expected the frame size 'W H'");
    }
    SUBCASE("a coordinate beyond the exact range") {
        check_malformed("4 4\n0 0 3 0 3 2000000\n",
                        "line 2: vertex 2: coordinate 2000000 px is outside");
    }
}

TEST_CASE("coverage: a frame with no triangles prints zeros") {
    const auto result = run_command(cli_path() + " coverage", "3 2\n");
    CHECK(result.exit_code == 0);
    CHECK(result.out == "0 0 0\n0 0 0\n");
}

TEST_CASE("float coverage far from the origin is correct or rejected, never silently "
          "empty") {
    // A triangle that covers the whole 4 x 4 frame: corners (-s, -s), (-s, 3s), (3s, -s).
    const auto cover = [](double s, const std::string& rasterizer) {
        return run_command(
            cli_path() + " coverage --precision float --rasterizer " + rasterizer,
            fmt::format("4 4\n{} {} {} {} {} {}\n", -s, -s, -s, 3 * s, 3 * s, -s));
    };
    const std::string full = "1 1 1 1\n1 1 1 1\n1 1 1 1\n1 1 1 1\n";
    for (const char* rasterizer : {"edge", "edge8x8"}) {
        CAPTURE(rasterizer);
        CHECK(cover(1000, rasterizer).out == full);
        CHECK(cover(349525, rasterizer).out == full); // 3s = 1048575 px: still in range
        for (const double far : {349526.0, 1e19, 1e30}) { // 3s beyond 2^20 px
            CAPTURE(far);
            const auto result = cover(far, rasterizer);
            CHECK(result.exit_code == 2);
            CHECK(result.out.empty());
            CHECK(result.err.find("outside the exact range") !=
                  std::string::npos);
        }
    }
}

TEST_CASE("coverage refuses a frame of more than 2^24 pixels and an endless line") {
    const auto huge = run_command(cli_path() + " coverage", "16384 16384\n");
    CHECK(huge.exit_code == 2);
    CHECK(huge.err.find("16777216 pixels") != std::string::npos);
    // An endless line (/dev/zero has no line break) stops at max_line_bytes.
    const auto endless = run_command("sh -c \"" + cli_path() + " coverage </dev/zero\"");
    CHECK(endless.exit_code == 2);
    CHECK(endless.err.find("line 1: longer than the 1024 bytes allowed") !=
          std::string::npos);
    const auto largest = run_command(cli_path() + " coverage", "16384 1\n");
    CHECK(largest.exit_code == 0);
    CHECK(largest.out.size() == 2 * 16384);
}

TEST_CASE("coverage refuses an input over the fill-work limit before drawing it") {
    // Generated: thousands of lines. In a 4096 x 16 frame each triangle's bounding box
    // is the whole frame, 2^16 pixels, so 4096 triangles are exactly max_fill_work
    // (2^28 pixels) and a 4097th is over it.
    const auto input_of = [](int triangles) {
        std::string text = "4096 16\n";
        for (int k = 0; k < triangles; ++k) {
            text += "0 0 8192 0 0 32\n";
        }
        return text;
    };
    const auto over = run_command(cli_path() + " coverage", input_of(4097));
    CHECK(over.exit_code == 2);
    CHECK(over.out.empty());
    CHECK(over.err ==
          "exactpixels coverage: line 4098: the triangles up to this line ask "
          "for 268500992 pixels of drawing (their bounding boxes in the "
          "frame), more than the 268435456 allowed\n");
#if !defined(__SANITIZE_ADDRESS__) // drawing 2^28 pixels takes many seconds there
    // At the limit it is drawn: every pixel centre lies inside every triangle.
    const auto at = run_command(cli_path() + " coverage", input_of(4096));
    CHECK(at.exit_code == 0);
    std::string row = "4096";
    for (int x = 1; x < 4096; ++x) {
        row += " 4096";
    }
    std::string expected_counts;
    for (int y = 0; y < 16; ++y) {
        expected_counts += row + "\n";
    }
    CHECK(at.out == expected_counts);
#endif
}

namespace {

/// `exactpixels coverage OPTIONS` with tests/fixtures/coverage/NAME as its input.
exactpixels::testing::CommandResult cover_fixture(const std::string& name,
                                                  const std::string& options = "") {
    std::ifstream file(std::string(EXACTPIXELS_SOURCE_DIR) + "/tests/fixtures/coverage/" +
                           name,
                       std::ios::binary);
    REQUIRE(file);
    const std::string text{std::istreambuf_iterator<char>(file), {}};
    return run_command(cli_path() + " coverage " + options, text);
}

} // namespace

TEST_CASE("coverage: a number has at most one sign, in the documented form") {
    // "+-0.5" was read as -0.5: the sign '+' was dropped and from_chars took the '-'.
    for (const auto& fixture : {std::pair{"two_signs_plus_minus.txt", "+-0.5"},
                                std::pair{"two_signs_minus_plus.txt", "-+1"},
                                std::pair{"two_signs_plus_plus.txt", "++0"}}) {
        const char* name = fixture.first;
        const char* word = fixture.second;
        CAPTURE(name);
        const auto result = cover_fixture(name);
        CHECK(result.exit_code == 2);
        CHECK(result.out.empty());
        CHECK(result.err ==
              fmt::format("exactpixels coverage: line 2: expected a number, "
                          "found '{}'\n",
                          word));
    }
    // Every form the format allows, one sign at most, reads as the plain numbers do.
    const auto signed_forms = cover_fixture("signed_numbers.txt");
    const auto plain = run_command(cli_path() + " coverage", "4 4\n0 0 4 0 0 4\n");
    CHECK(signed_forms.exit_code == 0);
    CHECK(signed_forms.out == plain.out);
    CHECK(plain.out != "0 0 0 0\n0 0 0 0\n0 0 0 0\n0 0 0 0\n");
    check_malformed("4 4\n0 0 3 0 3 1e400\n",
                    "line 2: '1e400' is too large or too small for a double");
}

TEST_CASE("coverage: control characters in a line are escaped in its message") {
    // The line's last word is '1', NUL, ESC "[31m" (red text) and BEL. The message was
    // cut at the NUL; now every control character is written out and the line is whole.
    const auto result = cover_fixture("control_characters.txt");
    CHECK(result.exit_code == 2);
    CHECK(result.out.empty());
    CHECK(result.err == "exactpixels coverage: line 2: expected a number, found "
                        "'1\\0\\x1b[31m\\x07'\n");
}

TEST_CASE("coverage: a value beyond float's range is named as read, not as inf") {
    // 1e39 is more than float's largest value: converted first, it was named "inf".
    for (const char* rasterizer : {"edge", "edge8x8"}) {
        CAPTURE(rasterizer);
        const auto result =
            cover_fixture("beyond_float.txt",
                          std::string("--precision float --rasterizer ") + rasterizer);
        CHECK(result.exit_code == 2);
        CHECK(result.out.empty());
        CHECK(result.err ==
              "exactpixels coverage: line 2: vertex 2: coordinate 1e+39 px is "
              "outside the exact range [-1048576, 1048576]\n");
    }
}
