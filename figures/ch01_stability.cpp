// Figure data: the gradient stability study of chapter 1. Writes ch01_stability.md (the
// table the chapter pulls in) and ch01_stability.dat (for ch01_stability.gp) into the
// folder argv[1], and ch01_stability_far.txt: the same study with every triangle moved by
// 3072 px in x and y, to about 4000 px (Exercise 5's solution quotes its facts).
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/gradient_stability.hpp"
#include "support/figure_file.hpp"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

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
        write_figure_file(folder / "ch01_stability_far.txt", far_facts(rows, far_rows));
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch01_stability: %s\n", error.what());
        return 1;
    }
}
