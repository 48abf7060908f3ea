#include "exactpixels/lab/benchmark_csv.hpp"

#include "exactpixels/base/decimal_from_chars.hpp"
#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <fstream>
#include <vector>

namespace exactpixels {

namespace {

/// The cells of one CSV line; double quotes group a cell and are removed.
std::vector<std::string> cells_of(const std::string& line) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (const char c : line) {
        if (c == '"') {
            quoted = !quoted;
        } else if (c == ',' && !quoted) {
            cells.emplace_back();
        } else if (c != '\r') {
            cells.back() += c;
        }
    }
    return cells;
}

} // namespace

double BenchmarkRuns::value(const std::string& name, const std::string& column) const {
    const auto run = runs.find(name);
    if (run == runs.end()) {
        throw Error(fmt::format("{}: no run named '{}'", file, name));
    }
    const auto cell = run->second.find(column);
    if (cell == run->second.end()) {
        throw Error(
            fmt::format("{}: run '{}' has no number in column '{}'", file, name, column));
    }
    return cell->second;
}

double BenchmarkRuns::net_rate(const std::string& name, const std::string& empty,
                               const std::string& counter,
                               const std::string& time) const {
    const double t = value(name, time), t_empty = value(empty, time);
    if (!(t_empty < t)) {
        throw Error(fmt::format("{}: run '{}' takes no longer than its empty frame '{}'",
                                file, name, empty));
    }
    return value(name, counter) * t / (t - t_empty);
}

BenchmarkRuns read_benchmark_csv(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) {
        throw Error(fmt::format("{}: cannot be read", path.string()));
    }
    BenchmarkRuns result{path.string(), {}};
    std::vector<std::string> header;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        if (header.empty()) {
            if (line.rfind("name,", 0) == 0) {
                header = cells_of(line);
            }
            continue; // comments and anything before the header row
        }
        if (line.empty()) {
            continue;
        }
        const std::vector<std::string> cells = cells_of(line);
        if (cells.size() != header.size()) {
            throw Error(fmt::format("{}:{}: {} cells, the header has {}", path.string(),
                                    number, cells.size(), header.size()));
        }
        auto& run = result.runs[cells[0]];
        for (std::size_t k = 1; k < cells.size(); ++k) {
            double v = 0;
            const char* end = cells[k].data() + cells[k].size();
            const auto [ptr, status] = decimal_from_chars(cells[k].data(), end, v);
            if (status == std::errc() && ptr == end && !cells[k].empty()) {
                run[header[k]] = v; // text cells (time_unit, label) are left out
            }
        }
    }
    if (header.empty()) {
        throw Error(fmt::format("{}: no header row 'name,...'", path.string()));
    }
    return result;
}

} // namespace exactpixels
