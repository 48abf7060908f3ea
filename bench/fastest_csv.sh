#!/bin/sh
# A repeated Google Benchmark run as if it were one run: the CSV header row and, for each
# benchmark, its fastest repetition under the benchmark's own name, for readers that take
# one row per run (read_benchmark_csv, fig_ch05_table, fig_ch09_speed). On a shared
# machine a slow spell only ever slows a repetition down, so the fastest one is the least
# disturbed; the median of three is not enough when a spell covers two of them.
# Fastest: the least cpu_time, or the least real_time for a run named .../real_time.
# Usage: bench/fastest_csv.sh RUN.csv > FASTEST.csv
#   RUN.csv   --benchmark_out of a run with --benchmark_repetitions=N (N >= 2), without
#             --benchmark_report_aggregates_only (aggregate rows are dropped)
# Exits 2 when RUN.csv holds no benchmark repeated at least twice.
set -eu
csv=${1:?usage: fastest_csv.sh RUN.csv}
[ -s "$csv" ] || { echo "fastest_csv.sh: no $csv" >&2; exit 2; }
awk -F, 'BEGIN { OFS = "," }
    /^name,/ { header = $0; next }
    !header || $1 ~ /_(mean|median|stddev|cv)"?$/ { next }
    {
        time = ($1 ~ /real_time"?$/) ? $3 : $4
        if (!($1 in best) || time + 0 < best[$1]) { best[$1] = time + 0; row[$1] = $0 }
        if (++seen[$1] == 1) order[++n] = $1
    }
    END {
        repeated = 0
        for (k = 1; k <= n; ++k) repeated += seen[order[k]] >= 2
        if (!repeated) { print "fastest_csv.sh: no benchmark repeated in the run" > "/dev/stderr"; exit 2 }
        print header
        for (k = 1; k <= n; ++k) print row[order[k]]
    }' "$csv"
