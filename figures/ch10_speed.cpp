// Chapter 10 figures and tables from the committed, dated benchmark run
// (chapters/10-fast-pixels/data/ch10_fast.csv, bench_ch10_fast's CSV with a '#' header
// naming machine and date): ch10_speed_flat.dat and ch10_speed_depth.dat (millions of
// pixels per second against area, one column per variant, for ch10_speed.gp),
// ch10_speed_textured.dat (the same for the textured run: teaching path, runs, llvmpipe),
// ch10_table.md (the same numbers and the ratio to llvmpipe), ch10_fixed.md (the fixed
// cost of an empty frame on each side, subtracted from every rate: chapter 10's
// measurement protocol), ch10_speed_facts.txt (the main run's ratios for the
// chapter's sentences), ch10_targets.md (each
// target of the chapter, met or not, with the numbers that decide it) and
// ch10_instructions.md (instructions per triangle from data/ch10_instructions.csv),
// ch10_textured.md (the textured run, data/ch10_textured.csv: the teaching path, the
// textured runs and llvmpipe, with the ratios), ch10_textured.txt (the textured
// section's facts, with data/ch10_textured_compare.csv's pixel counts), and
// ch10_threads.txt (facts for Exercise 4's solution: the one-core ratio of the tiled
// renderer to llvmpipe, and what two threads gave on the machine of the committed run)
// and ch10_threads.md (the wall-clock table of one and two threads, ours and llvmpipe's),
// and ch10_issue_targets.md (issue 34's targets against llvmpipe, met or short by how
// much, from this run, chapter 7's big_scene_results.md and simd_results.md).
// Usage: fig_ch10_speed FIGURE_DIR
#include "exactpixels/base/error.hpp"
#include "exactpixels/lab/benchmark_csv.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace exactpixels;

namespace {

const int areas[] = {3, 15, 80, 1000, 65536};
const char* const project_variants[] = {"walk", "blocks", "runs", "masks", "tiled"};

/// `counter` of MODE/VARIANT/AREA (one core, process CPU time) net of the fixed cost of
/// its frame: the same run at area 0, a frame with nothing in it (chapter 10's protocol).
double net(const BenchmarkRuns& r, const std::string& mode, const std::string& variant,
           int area, const std::string& counter) {
    return r.net_rate(fmt::format("{}/{}/{}/1/process_time", mode, variant, area),
                      fmt::format("{}/{}/0/1/process_time", mode, variant), counter,
                      "cpu_time");
}

/// Triangles per second of MODE/VARIANT/AREA, the frame's fixed cost subtracted.
double rate(const BenchmarkRuns& r, const std::string& mode, const std::string& variant,
            int area) {
    return net(r, mode, variant, area, "tri_per_s");
}

/// The fastest project variant at `area` and its rate.
std::pair<std::string, double> best(const BenchmarkRuns& r, const std::string& mode,
                                    int area) {
    std::pair<std::string, double> b{"", 0.0};
    for (const char* v : project_variants) {
        const double x = rate(r, mode, v, area);
        if (x > b.second) {
            b = {v, x};
        }
    }
    return b;
}

/// Triangles per second of wall/VARIANT/AREA/THREADS (wall clock).
double wall_rate(const BenchmarkRuns& r, const std::string& variant, int area,
                 int threads) {
    return r.net_rate(fmt::format("wall/{}/{}/{}/real_time", variant, area, threads),
                      fmt::format("wall/{}/0/{}/real_time", variant, threads),
                      "tri_per_s", "real_time");
}

/// Pixels per second of MODE/VARIANT/AREA (one core).
double pixel_rate(const BenchmarkRuns& r, const std::string& mode,
                  const std::string& variant, int area) {
    return net(r, mode, variant, area, "pix_per_s");
}

void write_dat(const BenchmarkRuns& r, const std::string& mode,
               const std::filesystem::path& path) {
    std::ostringstream out;
    out << "# area walk blocks runs masks tiled llvmpipe plain (Mpix/s, one core)\n";
    for (const int area : areas) {
        out << area;
        for (const char* v : project_variants) {
            out << ' ' << pixel_rate(r, mode, v, area) / 1e6;
        }
        out << ' ' << pixel_rate(r, mode, "llvmpipe", area) / 1e6;
        out << ' ' << (mode == "flat" ? pixel_rate(r, mode, "plain", area) / 1e6 : 0.0)
            << '\n';
    }
    write_figure_file(path, out.str());
}

std::string table(const BenchmarkRuns& r) {
    std::string md;
    for (const std::string mode : {"flat", "depth"}) {
        md += "| area (px) | walk | blocks | runs | masks | tiled | llvmpipe | best / "
              "llvmpipe |\n|--:|--:|--:|--:|--:|--:|--:|--:|\n";
        for (const int area : areas) {
            md += fmt::format("| {} |", area);
            for (const char* v : project_variants) {
                md += fmt::format(" {:.3g} |", rate(r, mode, v, area) / 1e6);
            }
            const auto [name, b] = best(r, mode, area);
            const double peer = rate(r, mode, "llvmpipe", area);
            md += fmt::format(" {:.3g} | {:.2f} ({}) |\n", peer / 1e6, b / peer, name);
        }
        md += fmt::format(
            "\n: Millions of triangles per second on one core, {}, from the committed "
            "run, and the fastest variant's rate over llvmpipe's. {{#tbl:ch10-{}}}\n\n",
            mode == "flat" ? "flat colour" : "flat colour with a 32-bit depth test",
            mode);
    }
    return md;
}

/// ch10_speed_textured.dat: Mpix/s of the teaching path, the textured runs and llvmpipe
/// against area in the textured run (one core).
void write_textured_dat(const BenchmarkRuns& t, const std::filesystem::path& path) {
    std::ostringstream out;
    out << "# area teaching runs llvmpipe (Mpix/s, one core, perspective-correct nearest "
           "texturing)\n";
    for (const int area : areas) {
        out << area;
        for (const char* v : {"teaching", "runs", "llvmpipe"}) {
            out << ' ' << net(t, "textured", v, area, "pix_per_s") / 1e6;
        }
        out << '\n';
    }
    write_figure_file(path, out.str());
}

/// Triangles per second of textured/VARIANT/AREA in the textured run (one core).
double textured_rate(const BenchmarkRuns& t, const std::string& variant, int area) {
    return net(t, "textured", variant, area, "tri_per_s");
}

/// The textured run's table: Mtri/s and Mpix/s of each side, runs over llvmpipe and
/// over the teaching path.
std::string textured_table(const BenchmarkRuns& t) {
    std::string md =
        "| area (px) | teaching | runs | llvmpipe | runs (Mpix/s) | llvmpipe "
        "(Mpix/s) | runs / llvmpipe | runs / teaching |\n"
        "|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const int area : areas) {
        const double teaching = textured_rate(t, "teaching", area);
        const double runs = textured_rate(t, "runs", area);
        const double peer = textured_rate(t, "llvmpipe", area);
        const auto pixels = [&](const char* v) {
            return net(t, "textured", v, area, "pix_per_s") / 1e6;
        };
        md += fmt::format("| {} | {:.3g} | {:.3g} | {:.3g} | {:.0f} | {:.0f} | {:.2f} | "
                          "{:.2f} |\n",
                          area, teaching / 1e6, runs / 1e6, peer / 1e6, pixels("runs"),
                          pixels("llvmpipe"), runs / peer, runs / teaching);
    }
    md +=
        "\n: Perspective-correct nearest texturing on one core: millions of triangles "
        "per second (and of pixels for the runs and llvmpipe) in the committed textured "
        "run (data/ch10_textured.csv), and the runs' rate over llvmpipe's and over the "
        "teaching path's. {#tbl:ch10-textured}\n";
    return md;
}

/// The textured section's facts, one "NAME VALUE" per line: the runs' rate over
/// llvmpipe's and over the teaching path's at each area (textured run), and, summed over
/// the areas of data/ch10_textured_compare.csv, the pixels drawn, those whose coverage
/// differs in llvmpipe's frame, those drawn with another texel and how many of those
/// are a neighbouring texel, and the pixels where the runs differ from the teaching path;
/// and the instructions per triangle of data/ch10_textured_instructions.csv.
std::string textured_facts(const BenchmarkRuns& t, const BenchmarkRuns& compare,
                           const BenchmarkRuns& instructions) {
    std::string facts = "# chapter 10, textured runs: the committed textured run\n";
    for (const int area : areas) {
        const double runs = textured_rate(t, "runs", area);
        facts += fmt::format("runs_over_llvmpipe_{} {:.4f}\n", area,
                             runs / textured_rate(t, "llvmpipe", area));
        facts += fmt::format("runs_over_teaching_{} {:.4f}\n", area,
                             runs / textured_rate(t, "teaching", area));
    }
    for (const char* column : {"pixels_drawn", "coverage_differ", "texel_differ",
                               "neighbour_texel", "runs_differ"}) {
        double sum = 0;
        for (const int area : areas) {
            sum += compare.value(fmt::format("textured/{}", area), column);
        }
        facts += fmt::format("{} {:.0f}\n", column, sum);
    }
    for (const char* v : {"teaching", "runs", "llvmpipe"}) {
        for (const int area : {3, 1000}) {
            facts +=
                fmt::format("{}_instructions_{} {:.1f}\n", v, area,
                            instructions.value(fmt::format("textured/{}/{}", v, area),
                                               "instructions_per_triangle"));
        }
    }
    return facts;
}

std::string targets(const BenchmarkRuns& r, const BenchmarkRuns& t) {
    const auto met = [](bool ok) { return ok ? "**met**" : "**not met**"; };
    std::string md;
    // Blocks (8x8 masks) beat the pixel walk at every size from 15 px up.
    bool masks_win = true;
    std::string detail;
    for (const int area : areas) {
        if (area < 15) {
            continue;
        }
        const double q = rate(r, "flat", "masks", area) / rate(r, "flat", "walk", area);
        masks_win = masks_win && q > 1.0;
        detail += fmt::format("{}{} px: {:.2f}x", detail.empty() ? "" : ", ", area, q);
    }
    md += fmt::format("- 8x8 masks faster than the pixel walk from 15 px up: {} ({}).\n",
                      met(masks_win), detail);
    const auto [big_name, big] = best(r, "flat", 65536);
    const double plain = rate(r, "flat", "plain", 65536);
    md += fmt::format("- At least 50 % of a plain fill on 65536-px triangles: {} ({}: "
                      "{:.0f} %).\n",
                      met(big >= 0.5 * plain), big_name, 100.0 * big / plain);
    const auto [small_name, small] = best(r, "flat", 3);
    md += fmt::format("- At least 60 Mtri/s on 3-px triangles: {} ({}: {:.1f} Mtri/s).\n",
                      met(small >= 60e6), small_name, small / 1e6);
    for (const std::string mode : {"flat", "depth"}) {
        bool five = true;
        std::string d;
        for (const int area : areas) {
            const double q = best(r, mode, area).second / rate(r, mode, "llvmpipe", area);
            five = five && q >= 5.0;
            d += fmt::format("{}{} px: {:.1f}x", d.empty() ? "" : ", ", area, q);
        }
        md += fmt::format("- At least 5x llvmpipe, {}, one thread each: {} ({}).\n", mode,
                          met(five), d);
    }
    bool three = true;
    std::string textured_detail;
    for (const int area : areas) {
        const double q =
            textured_rate(t, "runs", area) / textured_rate(t, "llvmpipe", area);
        three = three && q >= 3.0;
        textured_detail +=
            fmt::format("{}{} px: {:.1f}x", textured_detail.empty() ? "" : ", ", area, q);
    }
    md += fmt::format(
        "- At least 3x llvmpipe with perspective-correct nearest texturing, "
        "one thread each: {} (textured runs, {}; the separate textured run).\n",
        met(three), textured_detail);
    const double one = wall_rate(r, "tiled", 1000, 1);
    const double two = wall_rate(r, "tiled", 1000, 2);
    md += fmt::format("- Two threads at least 1.8x one thread at 1000 px: {} ({:.2f}x, "
                      "wall clock).\n",
                      met(two >= 1.8 * one), two / one);
    return md;
}

/// The rows of a committed Markdown results file as the book's claims read them: a row
/// "| name words | ... | value |" is NAME_WORDS with its cells after the name, numbers
/// where they parse (chapters/07-scenes/big_scene_results.md, simd_results.md).
std::map<std::string, std::vector<double>> markdown_rows(const std::string& relative) {
    std::ifstream in(std::filesystem::path(EXACTPIXELS_SOURCE_DIR) / relative);
    if (!in) {
        throw Error(relative + ": cannot read");
    }
    std::map<std::string, std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.size() < 2 || line[0] != '|' || line[1] != ' ') {
            continue;
        }
        std::vector<std::string> cells;
        std::istringstream row(line.substr(1));
        for (std::string cell; std::getline(row, cell, '|');) {
            cell.erase(0, std::min(cell.find_first_not_of(' '), cell.size()));
            cell.erase(cell.find_last_not_of(' ') + 1);
            cells.push_back(cell);
        }
        std::string name = cells.front();
        std::replace(name.begin(), name.end(), ' ', '_');
        std::vector<double> values;
        for (std::size_t k = 1; k < cells.size(); ++k) {
            char* end = nullptr;
            const double x = std::strtod(cells[k].c_str(), &end);
            if (end == cells[k].c_str() || *end != '\0') {
                break; // a header row or a text cell
            }
            values.push_back(x);
        }
        if (!values.empty() && values.size() + 1 == cells.size()) {
            rows[name] = values;
        }
    }
    return rows;
}

/// The last value of row `name` of `rows` (Error naming the file when it is missing).
double row_value(const std::map<std::string, std::vector<double>>& rows,
                 const std::string& file, const std::string& name) {
    const auto it = rows.find(name);
    if (it == rows.end()) {
        throw Error(file + ": no row " + name);
    }
    return it->second.back();
}

/// How far above a target a rate must be to meet it: 3 %, about the spread of one
/// side's repetitions in the committed runs (the big torus's smallest and largest
/// repetitions, big_scene_results.md). Closer than that, the two are a tie.
constexpr double tie_margin = 0.03;

/// The verdict on a rate `q` times llvmpipe's against a target of `must` (goal `goal`)
/// times: computed from the data, never typed. Short means the rate must grow by
/// must / q (or goal / q) to meet it.
std::string verdict(double q, double must, double goal) {
    if (q >= goal) {
        return "**met**, goal met";
    }
    if (q >= must && q < must * (1.0 + tie_margin)) {
        return fmt::format("**not met**: a tie, within {:.0f} % of it", 100 * tie_margin);
    }
    if (q >= must) {
        return fmt::format("**met**; goal short by {:.2f}x", goal / q);
    }
    return fmt::format("**not met**: short by {:.2f}x", must / q);
}

/// The targets of issue 34 (exact and faster than llvmpipe), each row's measured cell
/// and verdict from a committed run: the big torus on one core and on two (chapter 7's
/// big_scene_results.md: llvmpipe's time over ours), the textured 1000-px set
/// (simd_results.md: the fastest instruction set), flat and depth-tested 80 and 1000 px
/// (the main run: the fastest variant), and the cheaper scene (the big torus without
/// depth and texture, ours: its slowest repetition against the full scene's fastest).
std::string issue_targets(const BenchmarkRuns& r) {
    const std::string big_file = "chapters/07-scenes/big_scene_results.md";
    const std::string simd_file = "chapters/10-fast-pixels/simd_results.md";
    const auto big = markdown_rows(big_file);
    const auto simd = markdown_rows(simd_file);
    std::string md = "| target | must | goal | measured | verdict |\n"
                     "|:--|:--|:--|:--|:--|\n";
    const double torus = 1.0 / row_value(big, big_file, "time_ratio_full");
    md += fmt::format("| big textured, depth-tested torus, 1280 × 720, one core | faster "
                      "than llvmpipe | 2x llvmpipe | {:.2f}x llvmpipe | {} |\n",
                      torus, verdict(torus, 1.0, 2.0));
    const double torus_two =
        1.0 / row_value(big, big_file, "time_ratio_full_two_threads");
    md +=
        fmt::format("| the same, two threads each (wall clock) | faster than llvmpipe on "
                    "two threads | 2x | {:.2f}x llvmpipe | {} |\n",
                    torus_two, verdict(torus_two, 1.0, 2.0));
    std::pair<std::string, double> lanes{"", 0.0};
    for (const char* set : {"portable", "sse2", "avx2", "avx512", "neon"}) {
        const auto it = simd.find(fmt::format("{}_over_llvmpipe", set));
        if (it != simd.end() && it->second.back() > lanes.second) {
            lanes = {set, it->second.back()};
        }
    }
    if (lanes.first.empty()) {
        throw Error(simd_file + ": no row SET_over_llvmpipe");
    }
    md +=
        fmt::format("| textured triangles of 1000 px (exact mapper) | 2x llvmpipe | 3x | "
                    "{:.2f}x ({}) | {} |\n",
                    lanes.second, lanes.first, verdict(lanes.second, 2.0, 3.0));
    for (const std::string mode : {"flat", "depth"}) {
        for (const int area : {80, 1000}) {
            const auto [name, b] = best(r, mode, area);
            const double q = b / rate(r, mode, "llvmpipe", area);
            md +=
                fmt::format("| {} triangles of {} px | 3x llvmpipe | 5x | {:.2f}x ({}) | "
                            "{} |\n",
                            mode == "flat" ? "flat" : "depth-tested", area, q, name,
                            verdict(q, 3.0, 5.0));
        }
    }
    const auto& full = big.at("ours_full");
    const auto& flat = big.at("ours_flat");
    const bool cheaper = flat.at(1) < full.at(0); // slowest flat below the fastest full
    md += fmt::format("| a scene calling for fewer effects (the torus without depth and "
                      "texture, ours) | measurably cheaper | | {:.2f} of the full "
                      "scene's time | {} |\n",
                      flat.back() / full.back(),
                      cheaper ? "**met**" : "**not met**: the spreads overlap");
    md += "\n: Issue 34's targets, judged by the build from the committed runs (rates "
          "over llvmpipe's, one core each, fixed costs apart; in brackets the fastest "
          "variant or instruction set; a rate within 3 % of its target is a tie). "
          "{#tbl:ch10-issue-targets}\n";
    return md;
}

/// Instructions per triangle (callgrind) of walk, runs, masks and llvmpipe.
std::string instruction_table(const BenchmarkRuns& r) {
    std::string md = "| mode | area (px) | walk | runs | masks | llvmpipe |\n"
                     "|---|--:|--:|--:|--:|--:|\n";
    for (const std::string mode : {"flat", "depth"}) {
        for (const int area : {3, 80, 1000}) {
            md += fmt::format("| {} | {} |", mode, area);
            for (const char* v : {"walk", "runs", "masks", "llvmpipe"}) {
                md += fmt::format(" {:.0f} |",
                                  r.value(fmt::format("{}/{}/{}", mode, v, area),
                                          "instructions_per_triangle"));
            }
            md += '\n';
        }
    }
    md += "\n: Instructions per triangle, counted by callgrind over one drawing of the "
          "1024 triangles of each area (data/ch10_instructions.csv). "
          "{#tbl:ch10-instructions}\n";
    return md;
}

/// Exercise 4's facts, one "NAME VALUE" per line: at each area from 80 px up, the tiled
/// renderer's rate over llvmpipe's with one thread each (process CPU time), in both
/// modes; the tiled renderer's wall-clock rate with two threads over one; and the
/// instructions per triangle of runs, masks and llvmpipe at 1000 px (callgrind).
std::string thread_facts(const BenchmarkRuns& r, const BenchmarkRuns& instructions) {
    std::string facts = "# chapter 10, Exercise 4: what the committed runs can say\n";
    for (const std::string mode : {"flat", "depth"}) {
        for (const int area : {80, 1000, 65536}) {
            facts += fmt::format("{}_tiled_over_llvmpipe_{} {:.4f}\n", mode, area,
                                 rate(r, mode, "tiled", area) /
                                     rate(r, mode, "llvmpipe", area));
        }
        for (const char* v : {"runs", "masks", "llvmpipe"}) {
            facts += fmt::format("{}_{}_instructions_1000 {:.1f}\n", mode, v,
                                 instructions.value(fmt::format("{}/{}/1000", mode, v),
                                                    "instructions_per_triangle"));
        }
        for (const char* v : {"walk", "llvmpipe"}) {
            facts += fmt::format("{}_{}_instructions_3 {:.1f}\n", mode, v,
                                 instructions.value(fmt::format("{}/{}/3", mode, v),
                                                    "instructions_per_triangle"));
        }
    }
    for (const int area : {80, 1000, 65536}) {
        facts +=
            fmt::format("wall_two_over_one_{} {:.4f}\n", area,
                        wall_rate(r, "tiled", area, 2) / wall_rate(r, "tiled", area, 1));
        facts += fmt::format("wall_llvmpipe_two_over_one_{} {:.4f}\n", area,
                             wall_rate(r, "llvmpipe", area, 2) /
                                 wall_rate(r, "llvmpipe", area, 1));
        for (const int n : {1, 2}) {
            facts += fmt::format("wall_tiled_over_llvmpipe_{}_{} {:.4f}\n", area, n,
                                 wall_rate(r, "tiled", area, n) /
                                     wall_rate(r, "llvmpipe", area, n));
        }
    }
    return facts;
}

/// The threads table: wall-clock Mtri/s of the kept tiled renderer and of llvmpipe
/// (its own process per thread count) on one and two threads, and the ratios.
std::string thread_table(const BenchmarkRuns& r) {
    std::string md =
        "| area (px) | tiled, 1 thread | 2 threads | 2 / 1 | llvmpipe, 1 thread "
        "| 2 threads | 2 / 1 | tiled / llvmpipe, 2 threads |\n"
        "|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const int area : areas) {
        const double t1 = wall_rate(r, "tiled", area, 1),
                     t2 = wall_rate(r, "tiled", area, 2);
        const double p1 = wall_rate(r, "llvmpipe", area, 1),
                     p2 = wall_rate(r, "llvmpipe", area, 2);
        md += fmt::format("| {} | {:.3g} | {:.3g} | {:.2f} | {:.3g} | {:.3g} | {:.2f} | "
                          "{:.2f} |\n",
                          area, t1 / 1e6, t2 / 1e6, t2 / t1, p1 / 1e6, p2 / 1e6, p2 / p1,
                          t2 / p2);
    }
    md += "\n: Millions of triangles per second by the wall clock, flat colour, from the "
          "committed run: the kept tiled renderer and llvmpipe on one and two threads "
          "(llvmpipe's two-thread rows from a second process, as OSMesa reads "
          "LP_NUM_THREADS once). {#tbl:ch10-threads}\n";
    return md;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    write_figure_file(path, text);
}

/// The main run's facts, one "NAME VALUE" per line, for the chapter's sentences: the
/// best variant's rate over llvmpipe's (MODE_AREA), the walk's and the runs' over
/// llvmpipe's, the runs' share of a plain fill at 65536 px, the fixed cost's share of
/// each side's 3 px frame, and llvmpipe's default (AVX) rate over its rate held to
/// SSE4.1 at 80 and 1000 px. Every rate is net of the frame's fixed cost.
std::string speed_facts(const BenchmarkRuns& r) {
    std::string facts = "# chapter 10: the committed main run (net rates)\n";
    const auto frame_time = [&](const std::string& mode, const std::string& v, int area) {
        return r.value(fmt::format("{}/{}/{}/1/process_time", mode, v, area), "cpu_time");
    };
    for (const std::string mode : {"flat", "depth"}) {
        for (const int area : areas) {
            const double peer = rate(r, mode, "llvmpipe", area);
            facts += fmt::format("best_over_llvmpipe_{}_{} {:.4f}\n", mode, area,
                                 best(r, mode, area).second / peer);
            for (const char* v : project_variants) {
                facts += fmt::format("{}_over_llvmpipe_{}_{} {:.4f}\n", v, mode, area,
                                     rate(r, mode, v, area) / peer);
                facts +=
                    fmt::format("{}_over_walk_{}_{} {:.4f}\n", v, mode, area,
                                rate(r, mode, v, area) / rate(r, mode, "walk", area));
            }
        }
        for (const char* v : {"runs", "llvmpipe"}) {
            facts += fmt::format("fixed_share_{}_{}_3 {:.4f}\n", v, mode,
                                 frame_time(mode, v, 0) / frame_time(mode, v, 3));
            facts += fmt::format("fixed_us_{}_{} {:.2f}\n", v, mode,
                                 frame_time(mode, v, 0) / 1e3);
        }
        for (const int area : {80, 1000}) {
            facts += fmt::format("llvmpipe_avx_over_sse41_{}_{} {:.4f}\n", mode, area,
                                 rate(r, mode, "llvmpipe", area) /
                                     rate(r, mode, "llvmpipe_sse4.1", area));
        }
    }
    facts +=
        fmt::format("runs_over_plain_65536 {:.4f}\n",
                    rate(r, "flat", "runs", 65536) / rate(r, "flat", "plain", 65536));
    facts +=
        fmt::format("blocks_over_plain_65536 {:.4f}\n",
                    rate(r, "flat", "blocks", 65536) / rate(r, "flat", "plain", 65536));
    facts += fmt::format("best_flat_3_mtri {:.2f}\n", best(r, "flat", 3).second / 1e6);
    return facts;
}

/// The fixed costs table: microseconds of a frame with nothing in it (area 0) for each
/// side and mode, and its share of the 3 px set's frame, which every rate of the
/// chapter has subtracted.
std::string fixed_table(const BenchmarkRuns& r, const BenchmarkRuns& t) {
    std::string md =
        "| frame | ours, runs (us) | share at 3 px | llvmpipe (us) | share at "
        "3 px |\n|:--|--:|--:|--:|--:|\n";
    const auto row = [&](const BenchmarkRuns& runs, const std::string& mode) {
        std::string cells = fmt::format("| {} |", mode);
        for (const char* v : {"runs", "llvmpipe"}) {
            const auto time = [&](int area) {
                return runs.value(fmt::format("{}/{}/{}/1/process_time", mode, v, area),
                                  "cpu_time");
            };
            cells += fmt::format(" {:.1f} | {:.0f} % |", time(0) / 1e3,
                                 100.0 * time(0) / time(3));
        }
        return cells + "\n";
    };
    md += row(r, "flat") + row(r, "depth") + row(t, "textured");
    md += "\n: The fixed cost of a frame in the committed runs: the CPU time of a frame "
          "with nothing in it (ours: the depth clear; llvmpipe: the depth clear and the "
          "copy of its frame into the caller's at glFinish), and its share of the frame "
          "of 1024 triangles of 3 px. Every rate in this chapter has it subtracted. "
          "{#tbl:ch10-fixed}\n";
    return md;
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    try {
        const BenchmarkRuns r =
            read_benchmark_csv(std::filesystem::path(EXACTPIXELS_SOURCE_DIR) /
                               "chapters/10-fast-pixels/data/ch10_fast.csv");
        write_dat(r, "flat", folder / "ch10_speed_flat.dat");
        write_dat(r, "depth", folder / "ch10_speed_depth.dat");
        write_text(folder / "ch10_table.md", table(r));
        const BenchmarkRuns textured =
            read_benchmark_csv(std::filesystem::path(EXACTPIXELS_SOURCE_DIR) /
                               "chapters/10-fast-pixels/data/ch10_textured.csv");
        write_text(folder / "ch10_targets.md", targets(r, textured));
        write_text(folder / "ch10_issue_targets.md", issue_targets(r));
        write_text(folder / "ch10_fixed.md", fixed_table(r, textured));
        write_text(folder / "ch10_speed_facts.txt", speed_facts(r));
        write_text(folder / "ch10_textured.md", textured_table(textured));
        write_textured_dat(textured, folder / "ch10_speed_textured.dat");
        const BenchmarkRuns compare =
            read_benchmark_csv(std::filesystem::path(EXACTPIXELS_SOURCE_DIR) /
                               "chapters/10-fast-pixels/data/ch10_textured_compare.csv");
        const BenchmarkRuns textured_instructions = read_benchmark_csv(
            std::filesystem::path(EXACTPIXELS_SOURCE_DIR) /
            "chapters/10-fast-pixels/data/ch10_textured_instructions.csv");
        write_text(folder / "ch10_textured.txt",
                   textured_facts(textured, compare, textured_instructions));
        const BenchmarkRuns instructions =
            read_benchmark_csv(std::filesystem::path(EXACTPIXELS_SOURCE_DIR) /
                               "chapters/10-fast-pixels/data/ch10_instructions.csv");
        write_text(folder / "ch10_instructions.md", instruction_table(instructions));
        write_text(folder / "ch10_threads.txt", thread_facts(r, instructions));
        write_text(folder / "ch10_threads.md", thread_table(r));
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch10_speed: %s\n", error.what());
        return 2;
    }
    return 0;
}
