// Chapter 0 tests: the framebuffer's conventions, the "F" pattern, PNG round trips and
// the all-or-nothing PNG writer.
#include "exactpixels/base/error.hpp"
#include "exactpixels/base/png.hpp"
#include "exactpixels/base/test_pattern.hpp"
#include "support/printing.hpp"
#include "support/process.hpp"

#include <doctest/doctest.h>

#include <bit>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

using namespace exactpixels;
namespace fs = std::filesystem;

namespace {
fs::path scratch_folder(const std::string& name) {
    auto folder = fs::temp_directory_path() /
                  ("exactpixels-ch00-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}
} // namespace

TEST_CASE("pixel centres sit at half-integer coordinates") {
    CHECK(pixel_centre(0, 0) == Point2{0.5, 0.5});
    CHECK(pixel_centre(7, 3) == Point2{7.5, 3.5});
}

TEST_CASE("an integer edge meets a centre exactly when dx and dy have equal largest "
          "powers of two") {
    // dx = 2^a m and dy = 2^b n with m, n odd: the edge meets a centre exactly when both
    // are non-zero and a == b, so (4, 2) does not, though 2 divides both; (4, 12) does.
    // Every edge between integer points of [-6, 6]^2, against every pixel centre near it,
    // in doubled coordinates so that the centre (i + 1/2, j + 1/2) is the odd integer
    // point (2i + 1, 2j + 1) and every test is exact.
    const auto twos = [](int d) { return std::countr_zero(static_cast<unsigned>(d)); };
    int edges = 0, through_centre = 0;
    for (int x0 = -6; x0 <= 6; ++x0) {
        for (int y0 = -6; y0 <= 6; ++y0) {
            for (int x1 = -6; x1 <= 6; ++x1) {
                for (int y1 = -6; y1 <= 6; ++y1) {
                    const int dx = x1 - x0, dy = y1 - y0;
                    if (dx == 0 && dy == 0) {
                        continue;
                    }
                    bool meets = false;
                    for (int cx = -11; cx <= 11 && !meets; cx += 2) {
                        for (int cy = -11; cy <= 11 && !meets; cy += 2) {
                            const int ax = cx - 2 * x0, ay = cy - 2 * y0;
                            const int along = ax * dx + ay * dy; // in [0, 2|d|^2]
                            meets = ax * dy - ay * dx == 0 && along >= 0 &&
                                    along <= 2 * (dx * dx + dy * dy);
                        }
                    }
                    const bool predicted = dx != 0 && dy != 0 && twos(dx) == twos(dy);
                    CAPTURE(x0);
                    CAPTURE(y0);
                    CAPTURE(x1);
                    CAPTURE(y1);
                    REQUIRE(meets == predicted);
                    ++edges;
                    through_centre += meets ? 1 : 0;
                }
            }
        }
    }
    // (0, 0)-(2, 2) passes through the centre (1/2, 1/2) of pixel (0, 0); no row or
    // column.
    CHECK(pixel_centre(0, 0) == Point2{0.5, 0.5});
    CHECK(through_centre > 0);
    CHECK(through_centre < edges);
}

TEST_CASE("the framebuffer is row-major with the origin at the top left") {
    Framebuffer frame(3, 2, rgba(0, 0, 0));
    frame.at(2, 0) = rgba(1, 2, 3); // top row, rightmost column
    frame.at(0, 1) = rgba(4, 5, 6); // bottom row, leftmost column
    // Element y * width + x: (2, 0) is element 2, (0, 1) is element 3.
    CHECK(frame.pixels()[2] == rgba(1, 2, 3));
    CHECK(frame.pixels()[3] == rgba(4, 5, 6));
    CHECK(frame.contains(2, 1));
    CHECK_FALSE(frame.contains(3, 0));
    CHECK_FALSE(frame.contains(0, -1));
}

TEST_CASE("the F pattern has the expected pixels, red on blue") {
    const Framebuffer f = draw_f_pattern(2); // 10 x 14 pixels
    REQUIRE(f.width() == 10);
    REQUIRE(f.height() == 14);
    // Each glyph row, one character per pixel column ('R' red, '.' blue).
    const char* expected[] = {
        "RRRRRRRRRR", "RRRRRRRRRR", "RR........", "RR........", "RR........",
        "RR........", "RRRRRRRR..", "RRRRRRRR..", "RR........", "RR........",
        "RR........", "RR........", "RR........", "RR........",
    };
    int red = 0;
    for (int y = 0; y < f.height(); ++y) {
        for (int x = 0; x < f.width(); ++x) {
            const bool want_red = expected[y][x] == 'R';
            INFO("pixel (" << x << ", " << y << ")");
            CHECK(f.at(x, y) == (want_red ? pattern_red : pattern_blue));
            red += want_red;
        }
    }
    CHECK(red == 4 * (5 + 6 + 3)); // 14 glyph cells of 2 x 2 pixels
    // The F has no symmetry: its mirror images differ from it.
    bool mirror_x_differs = false, mirror_y_differs = false;
    for (int y = 0; y < f.height(); ++y) {
        for (int x = 0; x < f.width(); ++x) {
            mirror_x_differs |= f.at(x, y) != f.at(f.width() - 1 - x, y);
            mirror_y_differs |= f.at(x, y) != f.at(x, f.height() - 1 - y);
        }
    }
    CHECK(mirror_x_differs);
    CHECK(mirror_y_differs);
}

TEST_CASE("to_rgba8 rounds to nearest and clamps") {
    CHECK(to_rgba8({0.0, 0.5, 1.0}) == rgba(0, 128, 255));
    CHECK(to_rgba8({-1.0, 2.0, 0.2}) == rgba(0, 255, 51));
}

TEST_CASE("a PNG written and read back has the same pixels") {
    const auto folder = scratch_folder("roundtrip");
    Framebuffer f = draw_f_pattern(3);
    f.at(1, 1) = rgba(10, 20, 30, 40); // a translucent pixel survives too
    write_png(folder / "f.png", f);
    CHECK(read_png(folder / "f.png") == f);
    CHECK_FALSE(fs::exists(folder / "f.png.partial"));
    fs::remove_all(folder);
}

TEST_CASE("writing to an unwritable path fails, names the path and leaves no file") {
    const auto folder = scratch_folder("unwritable");
    const fs::path target = folder / "no-such-folder" / "f.png";
    try {
        write_png(target, draw_f_pattern(1));
        FAIL("write_png did not throw");
    } catch (const Error& error) {
        CHECK(std::string(error.what()).find(target.string()) != std::string::npos);
    }
    CHECK_FALSE(fs::exists(target));
    CHECK(fs::is_empty(folder));
    fs::remove_all(folder);
}

TEST_CASE("reading a missing or corrupt file fails with the path in the message") {
    const auto folder = scratch_folder("corrupt");
    CHECK_THROWS_WITH_AS(read_png(folder / "missing.png"),
                         doctest::Contains((folder / "missing.png").string().c_str()),
                         Error);
    std::ofstream(folder / "bad.png") << "not a png";
    CHECK_THROWS_AS(read_png(folder / "bad.png"), Error);
    fs::remove_all(folder);
}

TEST_CASE("exactpixels pattern: --help, --version, and an unwritable output") {
    using testing::run_command;
    CHECK(run_command(testing::cli_path() + " --version").out.find("exactpixels 0.") ==
          0);
    CHECK(run_command(testing::cli_path() + " --help").exit_code == 0);

    const auto folder = scratch_folder("cli");
    const auto ok = run_command(testing::cli_path() + " pattern -o '" +
                                (folder / "f.png").string() + "' --cell 2");
    CHECK(ok.exit_code == 0);
    CHECK(read_png(folder / "f.png") == draw_f_pattern(2));

    const fs::path bad = folder / "missing" / "f.png";
    const auto failed =
        run_command(testing::cli_path() + " pattern -o '" + bad.string() + "'");
    CHECK(failed.exit_code != 0);
    CHECK(failed.err.find(bad.string()) != std::string::npos);
    CHECK_FALSE(fs::exists(bad));
    fs::remove_all(folder);
}
