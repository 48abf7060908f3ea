// Figure data: the gradient stability study of chapter 1. Writes ch01_stability.md (the
// table the chapter pulls in) and ch01_stability.dat (for ch01_stability.gp) into the
// folder argv[1].
#include "exactpixels/base/error.hpp"
#include "exactpixels/raster/gradient_stability.hpp"
#include "support/figure_file.hpp"

#include <cstdio>
#include <filesystem>
#include <sstream>

int main(int argc, char** argv) {
    using namespace exactpixels;
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const auto rows = gradient_stability_study(20000, 1); // 20000 triangles per row
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
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch01_stability: %s\n", error.what());
        return 1;
    }
}
