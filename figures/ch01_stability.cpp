// Figure data: the gradient stability study of chapter 1. Writes ch01_stability.md (the
// table the chapter pulls in), ch01_stability.dat (for ch01_stability.gp),
// ch01_stability_facts.txt (the summaries the chapter's prose quotes, one "NAME VALUE"
// per line) and ch01_stability_far.txt (the same study with every triangle moved by
// 3072 px in x and y, to about 4000 px; Exercise 5's solution quotes its facts) into
// the folder argv[1].
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/gradient_stability.hpp"
#include "support/figure_file.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

/// The range [lo, hi] of a value over the double rows with a non-zero y-delta.
struct Range {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -std::numeric_limits<double>::infinity();
    void add(double v) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
};

/// The facts the chapter states about the study, in `double`: ranges over the non-zero
/// y-deltas, pooled shares of wins, and the zero-delta row on its own.
std::string stability_facts(const std::vector<exactpixels::StabilityRow>& rows) {
    Range split_p99, split_median, closed_p99, closed_median, p99_ratio;
    double trials = 0, closed_wins = 0, split_wins = 0;
    std::ostringstream out;
    out << "# Chapter 1's stability study in double (fig_ch01_stability)\n";
    for (const exactpixels::StabilityRow& r : rows) {
        if (r.precision != "double") {
            continue;
        }
        const double share = 100.0 / r.triangles;
        if (r.y_delta == 0) {
            out << "zero_split_median " << r.split_median << "\nzero_closed_median "
                << r.closed_median << "\nzero_split_p99 " << r.split_p99
                << "\nzero_closed_p99 " << r.closed_p99 << "\nzero_split_wins_percent "
                << r.split_better * share << "\nzero_closed_wins_percent "
                << r.closed_better * share << '\n';
            continue;
        }
        split_p99.add(r.split_p99);
        split_median.add(r.split_median);
        closed_p99.add(r.closed_p99);
        closed_median.add(r.closed_median);
        p99_ratio.add(r.split_p99 / r.closed_p99);
        trials += r.triangles;
        closed_wins += r.closed_better;
        split_wins += r.split_better;
    }
    const auto range = [&](const char* name, const Range& v) {
        out << name << "_lo " << v.lo << '\n' << name << "_hi " << v.hi << '\n';
    };
    range("split_p99", split_p99);
    range("split_median", split_median);
    range("closed_p99", closed_p99);
    range("closed_median", closed_median);
    range("p99_ratio", p99_ratio);
    out << "closed_wins_percent " << 100.0 * closed_wins / trials
        << "\nsplit_wins_percent " << 100.0 * split_wins / trials << '\n';
    return out.str();
}

// One fact per line, "NAME VALUE": for each y-delta (named by its index, d0 = 1e-2 ..
// d5 = 0) and precision, the medians and 99th percentiles of both methods and how often
// each won, near the origin ("near") and moved to about 4000 px ("far").
std::string far_facts(const std::vector<exactpixels::StabilityRow>& near,
                      const std::vector<exactpixels::StabilityRow>& far) {
    std::ostringstream out;
    out << "# chapter 1, Exercise 5: the stability study at 100..1000 px (near) and "
           "moved\n"
           "# by 3072 px to 3082..4072 px (far); errors in machine epsilons\n";
    for (std::size_t i = 0; i < near.size(); ++i) {
        const std::string key = near[i].precision + "_d" + std::to_string(i / 2);
        for (const auto& [where, r] :
             {std::pair{"near", near[i]}, std::pair{"far", far[i]}}) {
            const double n = r.triangles / 100.0;
            out << key << "_split_median_" << where << ' ' << r.split_median << '\n'
                << key << "_split_p99_" << where << ' ' << r.split_p99 << '\n'
                << key << "_closed_median_" << where << ' ' << r.closed_median << '\n'
                << key << "_closed_p99_" << where << ' ' << r.closed_p99 << '\n'
                << key << "_closed_better_" << where << ' ' << r.closed_better / n << '\n'
                << key << "_split_better_" << where << ' ' << r.split_better / n << '\n';
        }
    }
    return out.str();
}

} // namespace

int main(int argc, char** argv) {
    using namespace exactpixels;
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const auto rows = gradient_stability_study(20000, 1); // 20000 triangles per row
    const auto far_rows = gradient_stability_study(20000, 1, 3072.0);
    std::ostringstream table;
    table << ": Error of the two gradient methods, in machine epsilons of the precision, "
             "over 20000 triangles per row {#tbl:stability}\n\n"
          << stability_table_markdown(rows);
    std::ostringstream data;
    data << "# y_delta precision split_median split_p99 split_max closed_median "
            "closed_p99 closed_max\n";
    for (const StabilityRow& r : rows) {
        if (r.y_delta > 0) { // the log axis has no place for 0
            data << r.y_delta << ' ' << r.precision << ' ' << r.split_median << ' '
                 << r.split_p99 << ' ' << r.split_max << ' ' << r.closed_median << ' '
                 << r.closed_p99 << ' ' << r.closed_max << '\n';
        }
    }
    try {
        write_figure_file(folder / "ch01_stability.md", table.str());
        write_figure_file(folder / "ch01_stability.dat", data.str());
        write_figure_file(folder / "ch01_stability_facts.txt", stability_facts(rows));
        write_figure_file(folder / "ch01_stability_far.txt", far_facts(rows, far_rows));
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch01_stability: %s\n", error.what());
        return 1;
    }
}
