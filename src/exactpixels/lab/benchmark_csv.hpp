// benchmark_csv.hpp: the results of a Google Benchmark run, read from its CSV output
// (--benchmark_out=FILE --benchmark_out_format=csv), for the figures and for the tests
// that check the book's sentences against committed measurements.
//
// Usage:
//   const BenchmarkRuns runs = read_benchmark_csv("data/ch10_fast.csv");
//   double r = runs.value("flat/runs/1000/1/process_time", "tri_per_s");  // per second
//   double n = runs.net_rate("flat/runs/1000/1/process_time",
//                            "flat/runs/0/1/process_time", // the empty frame's run
//                            "tri_per_s", "cpu_time");  // less the empty frame's time
//
// Lines before the header row (Google Benchmark writes none; committed files may carry
// '#' comments naming the machine and date) are skipped. Values are as written: times in
// the run's time_unit, counters per second. Missing runs or columns throw Error naming
// the file, the run and the column.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace exactpixels {

/// Every run of one CSV file: run name -> column name -> number.
struct BenchmarkRuns {
    std::string file;                                          ///< where it was read
    std::map<std::string, std::map<std::string, double>> runs; ///< the numeric cells
    /// The number in column `column` of run `name`; Error naming both when absent.
    double value(const std::string& name, const std::string& column) const;
    /// The rate in counter `counter` of run `name` net of a fixed per-frame cost: run
    /// `empty` times the same frame with nothing in it, and the rate is scaled by
    /// t / (t - t_empty), t from column `time` (cpu_time, or real_time for wall-clock
    /// runs) of each run. Error when a run or column is absent, or t_empty >= t.
    double net_rate(const std::string& name, const std::string& empty,
                    const std::string& counter, const std::string& time) const;
    /// True when a run called `name` exists.
    bool has(const std::string& name) const { return runs.count(name) != 0; }
};

/// Reads a Google Benchmark CSV file. Throws Error naming the file (and line) when it
/// cannot be read, has no header row, or a row has the wrong number of cells.
BenchmarkRuns read_benchmark_csv(const std::filesystem::path& path);

} // namespace exactpixels
