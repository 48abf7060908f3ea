#include "support/printing.hpp"
// Chapter 10 tests (kept with chapter 7's suite, whose scene they draw): the comparisons
// @sec:scene-speed states about the big torus against llvmpipe, checked against the
// committed, dated run (chapters/07-scenes/big_scene_results.md, written by big_scene.sh
// beside it). A new run that changes a comparison makes the matching test fail, and the
// sentence must change with it. The instruction counts of the fast paths (FastPaths) are
// checked the same way.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

/// The facts of the committed run: every Markdown table row "| name | ... | value |",
/// named as the book's claims name it (its first cell, spaces as _), with its last cell.
const std::map<std::string, double>& facts() {
    static const std::map<std::string, double> table = [] {
        std::map<std::string, double> out;
        std::ifstream in(std::filesystem::path(EXACTPIXELS_SOURCE_DIR) /
                         "chapters/07-scenes/big_scene_results.md");
        REQUIRE(in);
        std::string line;
        while (std::getline(in, line)) {
            if (line.rfind("| ", 0) != 0) {
                continue;
            }
            std::vector<std::string> cells;
            std::stringstream row(line.substr(1));
            std::string cell;
            while (std::getline(row, cell, '|')) {
                const auto first = cell.find_first_not_of(' ');
                const auto last = cell.find_last_not_of(' ');
                cells.push_back(first == std::string::npos
                                    ? ""
                                    : cell.substr(first, last - first + 1));
            }
            if (cells.size() < 2) {
                continue;
            }
            std::string name = cells.front();
            for (char& c : name) {
                c = c == ' ' ? '_' : c;
            }
            try {
                out[name] = std::stod(cells.back());
            } catch (const std::exception&) { // a header row or a text cell
            }
        }
        return out;
    }();
    return table;
}

double fact(const std::string& name) {
    INFO(name);
    REQUIRE(facts().count(name) == 1);
    return facts().at(name);
}

} // namespace

TEST_CASE("claim: on the big torus ours is the shorter frame, on one core and on two, "
          "and executes fewer instructions") {
    // Shorter: the medians more than 3 % apart, about the spread of either side's
    // repetitions (@sec:scene-speed; closer is a tie, as ch10_speed.cpp's verdicts say).
    CHECK(fact("time_ratio_full") < 0.97);
    CHECK(fact("time_ratio_full_two_threads") < 0.97);
    CHECK(fact("instruction_ratio_full") < 1.0);
    CHECK(fact("instructions_ours_full") < fact("instructions_llvmpipe_full"));
    // Not yet the goal of twice llvmpipe's rate (@sec:fast-scene).
    CHECK(fact("time_ratio_full") > 0.5);
}

TEST_CASE("claim: the big torus without depth and texture costs less time and work") {
    CHECK(fact("ours_flat") < fact("ours_full"));
    CHECK(fact("instructions_ours_flat") < fact("instructions_ours_full"));
}

TEST_CASE(
    "claim: on the big torus each fast path saves instructions, and all save more") {
    const double plain = fact("instructions_ours_full_plain");
    for (const char* path : {"masked_fetch", "lean_spans", "lean_geometry"}) {
        INFO(path);
        const double alone = fact(std::string("instructions_ours_full_") + path);
        CHECK(alone < plain);
        CHECK(fact("instructions_ours_full") < alone);
    }
}

TEST_CASE("claim: the big torus's geometry and rasterizer take most of its frame") {
    // The report kept is the median render's, so its stages add up to its total.
    const double geometry = fact("stage_ms_full_geometry");
    const double raster = fact("stage_ms_full_raster");
    const double pixels = fact("stage_ms_full_depth") + fact("stage_ms_full_texture");
    const double total = fact("stage_ms_full_total");
    CHECK(geometry + raster > 0.6 * total); // "more than three fifths" (@sec:scene-speed)
    CHECK(pixels < geometry + raster);
    CHECK(geometry + raster + pixels <= total);
}
