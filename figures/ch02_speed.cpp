// Figure data: chapter 2's speed table and sweep, from the benchmark's CSV.
//
// Reads FOLDER/bench_ch02_rasterizers.csv (written by bench_ch02_rasterizers with
// --benchmark_out=... --benchmark_out_format=csv, which the book build runs first) and
// writes FOLDER/ch02_speed_table.md (the source's table shape: float/fixed x 1x1/8x8 at
// 3, 15 and 80 px, with the naive rasterizer and the plain fill, and the ratios; then
// the large-triangle rates against the plain fill) and FOLDER/ch02_speed_sweep.dat
// (Mpix/s per variant against triangle area, for ch02_speed.gp). When a benchmark ran
// several times, the median of its runs is used. A missing or unreadable CSV is an
// error naming the file.
#include "exactpixels/base/error.hpp"
#include "support/figure_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using exactpixels::Error;

const char* const variants[] = {"float_1x1", "float_8x8", "fixed_1x1",
                                "fixed_8x8", "naive",     "plain_fill"};
const char* const labels[] = {"float 1x1", "float 8x8",        "fixed 1x1",
                              "fixed 8x8", "naive (tutorial)", "plain fill (ceiling)"};

/// Rates of one benchmark: triangles and pixels per second (medians over its runs).
struct Rates {
    std::vector<double> tri;
    std::vector<double> pix;
};

/// One comma-separated CSV line, with double quotes removed from quoted fields.
std::vector<std::string> fields_of(const std::string& line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (const char c : line) {
        if (c == '"') {
            quoted = !quoted;
        } else if (c == ',' && !quoted) {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    return fields;
}

double median(std::vector<double> v) {
    if (v.empty()) {
        return 0.0;
    }
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// name ("table/fixed_8x8/3") -> rates, read from Google Benchmark's CSV.
std::map<std::string, Rates> read_csv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) {
        throw Error(fmt::format("{}: cannot read the benchmark results (run "
                                "bench_ch02_rasterizers --benchmark_out={} "
                                "--benchmark_out_format=csv first)",
                                path.string(), path.string()));
    }
    std::string line;
    int number = 0;
    std::vector<std::string> header;
    std::map<std::string, Rates> rates;
    while (std::getline(in, line)) {
        ++number;
        if (header.empty()) {
            if (line.rfind("name,", 0) == 0) {
                header = fields_of(line);
            }
            continue;
        }
        const auto fields = fields_of(line);
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) {
            row[header[i]] = fields[i];
        }
        const std::string& name = row["name"];
        if (name.find("_mean") != std::string::npos ||
            name.find("_median") != std::string::npos ||
            name.find("_stddev") != std::string::npos ||
            name.find("_cv") != std::string::npos) {
            continue; // aggregates: the runs themselves are used
        }
        try {
            rates[name].tri.push_back(std::stod(row.at("tri_per_s")));
            rates[name].pix.push_back(std::stod(row.at("pix_per_s")));
        } catch (const std::exception&) {
            throw Error(fmt::format("{}:{}: no tri_per_s / pix_per_s values in '{}'",
                                    path.string(), number, line));
        }
    }
    if (header.empty() || rates.empty()) {
        throw Error(fmt::format("{}: no benchmark results in the file", path.string()));
    }
    return rates;
}

/// The median rate of benchmark `name` (tri or pix per second), or an error naming it.
double rate(const std::map<std::string, Rates>& rates, const std::string& name,
            bool pixels, const std::filesystem::path& path) {
    const auto it = rates.find(name);
    if (it == rates.end()) {
        throw Error(
            fmt::format("{}: the benchmark '{}' is missing", path.string(), name));
    }
    return median(pixels ? it->second.pix : it->second.tri);
}

void write_table(const std::map<std::string, Rates>& rates,
                 const std::filesystem::path& csv, std::ostream& out) {
    const int areas[] = {3, 15, 80};
    const auto mtri = [&](const std::string& v, int area) {
        return rate(rates, fmt::format("table/{}/{}", v, area), false, csv) / 1e6;
    };
    out << "| variant | 3 px | 15 px | 80 px | x naive 3 px | x naive 15 px | x naive 80 "
           "px |\n"
        << "|---|--:|--:|--:|--:|--:|--:|\n";
    for (int k = 0; k < 6; ++k) {
        out << "| " << labels[k] << " |";
        for (const int area : areas) {
            out << fmt::format(" {:.1f} |", mtri(variants[k], area));
        }
        for (const int area : areas) {
            out << fmt::format(" {:.2f} |",
                               mtri(variants[k], area) / mtri("naive", area));
        }
        out << '\n';
    }
    out << "\n: Measured here: millions of triangles per second on one core, triangles "
           "of 3, 15 and 80 px area, and each rate over the naive rasterizer's "
           "(bench_ch02_rasterizers). {#tbl:edge-speed}\n\n";

    const int big[] = {4096, 65536};
    out << "| variant | Mpix/s, 4096 px | % of plain fill | Mpix/s, 65536 px | "
           "% of plain fill |\n|---|--:|--:|--:|--:|\n";
    for (int k = 0; k < 6; ++k) {
        out << "| " << labels[k] << " |";
        for (const int area : big) {
            const double p =
                rate(rates, fmt::format("sweep/{}/{}", variants[k], area), true, csv);
            const double fill =
                rate(rates, fmt::format("sweep/plain_fill/{}", area), true, csv);
            out << fmt::format(" {:.0f} | {:.0f} |", p / 1e6, 100.0 * p / fill);
        }
        out << '\n';
    }
    out << "\n: Measured here: millions of pixels per second on one core for large "
           "triangles, and the share of the plain fill's rate. {#tbl:edge-speed-large}\n";
}

void write_sweep(const std::map<std::string, Rates>& rates,
                 const std::filesystem::path& csv, std::ostream& out) {
    out << "# area_px";
    for (const char* v : variants) {
        out << ' ' << v << "_Mpix_s";
    }
    out << '\n';
    for (int area = 2; area <= 65536; area *= 2) {
        out << area;
        for (const char* v : variants) {
            out << fmt::format(
                " {:.2f}",
                rate(rates, fmt::format("sweep/{}/{}", v, area), true, csv) / 1e6);
        }
        out << '\n';
    }
}

} // namespace

int main(int argc, char** argv) {
    const std::filesystem::path folder = argc > 1 ? argv[1] : ".";
    const auto csv = folder / "bench_ch02_rasterizers.csv";
    try {
        const auto rates = read_csv(csv);
        std::ostringstream table, sweep;
        write_table(rates, csv, table);
        write_sweep(rates, csv, sweep);
        for (const auto& [name, text] :
             {std::pair{"ch02_speed_table.md", table.str()},
              std::pair{"ch02_speed_sweep.dat", sweep.str()}}) {
            exactpixels::write_figure_file(folder / name, text);
        }
    } catch (const Error& error) {
        std::fprintf(stderr, "fig_ch02_speed: %s\n", error.what());
        return 1;
    }
    std::printf("wrote ch02_speed_table.md and ch02_speed_sweep.dat in %s\n",
                folder.c_str());
}
