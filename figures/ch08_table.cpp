// Chapter 8's tables and plot data: time per pixel of every filter (from the benchmark
// run of bench_ch08_filters) beside its error against the reference image.
// Usage: fig_ch08_table FIGURE_DIR
// Reads FIGURE_DIR/bench_ch08_filters.csv (the book build's quick run, or a full run)
// and writes into FIGURE_DIR:
//   ch08_table.md         one table per scene: time per pixel, ratio to nearest, error
//                         on the minified pixels and on all pixels, Pareto front
//   ch08_levels.md        per scene: minified pixels, the level errors of the per-span
//                         and per-triangle derivatives (worst, mean, pixels whose
//                         mip level changes) and the largest per-span bound
//   ch08_facts.txt        the same as facts (SCENE_span_worst 0.01 ...), every
//                         filter's error (SCENE_error_FILTER, minified pixels) for
//                         claims, and, on scenes with minified pixels, how far the book's
//                         first reference (a regular 32 x 32 grid of samples) is from the
//                         exact one there: its worst pixel (SCENE_grid_worst_pixel,
//                         codes) and the largest change of a filter's error
//                         (SCENE_grid_shift)
//   ch08_table_SCENE.dat  ratio, error, front flag, name (for gnuplot)
//   ch08_table_SCENE_front.dat  ratio and error of the front's filters, by ratio
// The reference images are computed here, once per build (filter_measure.hpp); every
// error is deterministic, only the times move from run to run.
#include "exactpixels/base/error.hpp"
#include "exactpixels/lab/filter_measure.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace exactpixels;
namespace fs = std::filesystem;

namespace {

struct Row {
    std::string filter;
    double ns_per_px = 0, ratio = 0;
    double error = 0;     // on the minified pixels (all pixels where none is minified)
    double error_all = 0; // on all pixels
    bool front = false;
};

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ',')) {
        field.erase(std::remove(field.begin(), field.end(), '"'), field.end());
        fields.push_back(field);
    }
    return fields;
}

/// run name -> ns_per_px, from Google Benchmark's CSV.
std::map<std::string, double> read_times(const fs::path& path) {
    std::ifstream in(path);
    if (!in) {
        throw Error(fmt::format("{}: cannot read the benchmark results (run the "
                                "bench-quick target first)",
                                path.string()));
    }
    std::map<std::string, double> times;
    std::vector<std::string> header;
    std::string line;
    int line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (line.rfind("name,", 0) == 0) {
            header = split(line);
            continue;
        }
        if (header.empty()) {
            continue;
        }
        const std::vector<std::string> f = split(line);
        const auto column = std::find(header.begin(), header.end(), "ns_per_px");
        const std::size_t k = static_cast<std::size_t>(column - header.begin());
        if (column == header.end() || k >= f.size()) {
            throw Error(
                fmt::format("{}:{}: no ns_per_px column", path.string(), line_number));
        }
        try {
            times[f[0]] = std::stod(f[k]);
        } catch (const std::exception&) {
            throw Error(fmt::format("{}:{}: ns_per_px '{}' is not a number",
                                    path.string(), line_number, f[k]));
        }
    }
    if (times.empty()) {
        throw Error(fmt::format("{}: no benchmark rows", path.string()));
    }
    return times;
}

/// On the front when no other row is at least as fast and as accurate, and better in one.
void mark_front(std::vector<Row>& rows) {
    for (Row& a : rows) {
        a.front = std::none_of(rows.begin(), rows.end(), [&](const Row& b) {
            return b.ratio <= a.ratio && b.error <= a.error &&
                   (b.ratio < a.ratio || b.error < a.error);
        });
    }
}

void write(const fs::path& path, const std::string& text) {
    write_figure_file(path, text);
}

} // namespace

int main(int argc, char** argv) try {
    const fs::path folder = argc > 1 ? argv[1] : ".";
    const std::map<std::string, double> times =
        read_times(folder / "bench_ch08_filters.csv");
    std::string table, facts,
        levels = "| scene | pixels | minified | span worst | span mean | span moved "
                 "| span bound | tri. worst | tri. mean | tri. moved "
                 "|\n|:--|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
    for (const AccuracyScene& scene : filter_scenes()) {
        const FilterScene fs = prepare_filter_scene(scene);
        const std::vector<LinearTexel> reference = reference_image(fs);
        const std::vector<bool> minified = minified_pixels(fs);
        const auto n_minified = std::count(minified.begin(), minified.end(), true);
        std::vector<Row> rows;
        std::vector<std::vector<LinearTexel>> images;
        for (const FilterConfig& c : filter_configs()) {
            std::string name = scene.name + "/" + c.name;
            std::replace(name.begin(), name.end(), ' ', '_');
            const auto at = times.find(name);
            if (at == times.end()) {
                throw Error(fmt::format("bench_ch08_filters.csv: no run named {}", name));
            }
            const std::vector<LinearTexel>& image =
                images.emplace_back(filter_image(fs, c));
            const double all = rms_code_error(image, reference);
            rows.push_back(
                {c.name, at->second, 0,
                 n_minified > 0 ? rms_code_error(image, reference, minified) : all, all,
                 false});
        }
        for (Row& r : rows) {
            r.ratio = r.ns_per_px / rows.front().ns_per_px; // nearest, same run
        }
        if (n_minified > 0) { // the first edition's reference against the exact one
            const std::vector<LinearTexel> grid =
                sampled_reference_image(fs, 32, SamplePattern::grid, minified);
            int worst = 0;
            for (std::size_t k = 0; k < grid.size(); ++k) {
                const Rgba8 a = encode_linear(grid[k]), b = encode_linear(reference[k]);
                if (minified[k]) {
                    worst = std::max({worst, std::abs(a.r - b.r), std::abs(a.g - b.g),
                                      std::abs(a.b - b.b)});
                }
            }
            double shift = 0.0;
            std::vector<double> on_grid;
            for (std::size_t c = 0; c < rows.size(); ++c) {
                on_grid.push_back(rms_code_error(images[c], grid, minified));
                shift = std::max(shift, std::abs(on_grid.back() - rows[c].error));
            }
            int reversed = 0; // pairs of filters in another order against the grid
            for (std::size_t a = 0; a < rows.size(); ++a) {
                for (std::size_t b = 0; b < rows.size(); ++b) {
                    reversed +=
                        rows[a].error < rows[b].error && !(on_grid[a] < on_grid[b]);
                }
            }
            facts += fmt::format("{0}_grid_worst_pixel {1}\n{0}_grid_shift {2:.6g}\n"
                                 "{0}_grid_reversed {3}\n",
                                 scene.name, worst, shift, reversed);
        }
        mark_front(rows);
        table +=
            fmt::format("\n: Scene \"{}\": {} pixels, {} of them minified. Error: "
                        "RMS difference from the reference in 8-bit sRGB codes, on "
                        "the minified pixels{} and on all.\n\n",
                        scene.name, fs.pixels.size(), n_minified,
                        n_minified > 0 ? "" : " (none here: the column repeats all)");
        table += "| filter | ns/px | × nearest | error, minified | error, all | front "
                 "|\n|:--|--:|--:|--:|--:|:-:|\n";
        std::string dat = "# ratio error front name\n";
        for (const Row& r : rows) {
            table += fmt::format("| {} | {:.1f} | {:.2f} | {:.2f} | {:.2f} | {} |\n",
                                 r.filter, r.ns_per_px, r.ratio, r.error, r.error_all,
                                 r.front ? "yes" : "");
            std::string key = r.filter;
            std::replace(key.begin(), key.end(), ' ', '_');
            facts += fmt::format("{}_error_{} {:.6g}\n", scene.name, key, r.error);
            dat += fmt::format("{:.4f} {:.4f} {} \"{}\"\n", r.ratio, r.error,
                               int(r.front), r.filter);
        }
        write(folder / ("ch08_table_" + scene.name + ".dat"), dat);
        std::vector<Row> front;
        std::copy_if(rows.begin(), rows.end(), std::back_inserter(front),
                     [](const Row& r) { return r.front; });
        std::sort(front.begin(), front.end(),
                  [](const Row& a, const Row& b) { return a.ratio < b.ratio; });
        std::string front_dat = "# ratio error (the Pareto front, by time)\n";
        for (const Row& r : front) {
            front_dat += fmt::format("{:.4f} {:.4f}\n", r.ratio, r.error);
        }
        write(folder / ("ch08_table_" + scene.name + "_front.dat"), front_dat);
        const LevelErrors span = level_errors(fs, Derivatives::per_span);
        const LevelErrors tri = level_errors(fs, Derivatives::per_triangle);
        levels += fmt::format(
            "| {} | {} | {} | {:.4f} | {:.5f} | {} | {:.4f} | {:.2f} | {:.3f} | {} |\n",
            scene.name, fs.pixels.size(), n_minified, span.worst, span.mean, span.changed,
            span.worst_bound, tri.worst, tri.mean, tri.changed);
        facts +=
            fmt::format("{0}_span_worst {1:.6g}\n{0}_span_mean {2:.6g}\n"
                        "{0}_span_changed {3}\n{0}_span_bound {4:.6g}\n"
                        "{0}_triangle_worst {5:.6g}\n{0}_triangle_mean {6:.6g}\n"
                        "{0}_triangle_changed {7}\n{0}_pixels {8}\n",
                        scene.name, span.worst, span.mean, span.changed, span.worst_bound,
                        tri.worst, tri.mean, tri.changed, fs.pixels.size());
    }
    write(folder / "ch08_table.md", table);
    write(folder / "ch08_levels.md",
          levels + "\n: The level of detail from per-span and per-triangle derivatives "
                   "against the exact per-pixel level: worst and mean |level error| over "
                   "all pixels (levels below 0 count as 0), pixels whose mip-nearest "
                   "level changes (moved), and the largest per-span bound of "
                   "@eq:level-bound; tri.: per triangle {#tbl:levels}\n");
    write(folder / "ch08_facts.txt",
          "# fig_ch08_table: level errors of the cheaper derivatives and the filters' "
          "errors (minified pixels), per scene\n" +
              facts);
    return 0;
} catch (const Error& e) {
    std::fprintf(stderr, "fig_ch08_table: %s\n", e.what());
    return 2;
}
