#!/bin/sh
# A repeated Google Benchmark run as if it were one run: the CSV header row and one row
# per benchmark under the benchmark's own name, for readers that take one row per run
# (read_benchmark_csv, fig_ch10_speed; fig_ch05_table reads the repetitions itself).
# Which row:
#   fastest  the repetition with the least cpu_time (least real_time for a run named
#            .../real_time). For single-threaded work on a shared machine a slow spell
#            only ever slows a repetition down, so the fastest is the least disturbed.
#   median   Google Benchmark's _median row (needs --benchmark_repetitions >= 2). For
#            runs whose time a busy neighbour can also shorten (llvmpipe's waiting
#            thread, two threads on two cores), where the fastest is not the truest.
#            A last column, time_cv, gives the spread: the coefficient of variation of
#            the repetitions' time (the _cv row; 0.02 is 2 %).
# Usage: bench/repeated_csv.sh fastest|median RUN.csv > ONE_ROW_EACH.csv
# Exits 2 when RUN.csv holds no benchmark repeated at least twice (no _median row).
set -eu
mode=${1:?usage: repeated_csv.sh fastest|median RUN.csv}
csv=${2:?usage: repeated_csv.sh fastest|median RUN.csv}
[ -s "$csv" ] || { echo "repeated_csv.sh: no $csv" >&2; exit 2; }
case "$mode" in
fastest | median) ;;
*) echo "repeated_csv.sh: mode $mode is neither fastest nor median" >&2; exit 2 ;;
esac
awk -F, -v mode="$mode" 'BEGIN { OFS = "," }
    /^name,/ { header = $0; next }
    !header { next }
    mode == "median" && $1 ~ /_cv"?$/ {
        sub(/_cv/, "", $1)
        # Google Benchmark writes the ratio in the time columns scaled like a time
        unit = ($5 == "ns") ? 1e9 : ($5 == "us") ? 1e6 : ($5 == "ms") ? 1e3 : 1
        cv[$1] = (($1 ~ /real_time"?$/) ? $3 : $4) / unit; next
    }
    mode == "median" && $1 ~ /_median"?$/ {
        sub(/_median/, "", $1)
        if (!($1 in row)) order[++n] = $1
        row[$1] = $0; seen[$1] = 2; next
    }
    mode == "median" || $1 ~ /_(mean|median|stddev|cv)"?$/ { next }
    {
        time = ($1 ~ /real_time"?$/) ? $3 : $4
        if (!($1 in row)) order[++n] = $1
        if (!($1 in best) || time + 0 < best[$1]) { best[$1] = time + 0; row[$1] = $0 }
        ++seen[$1]
    }
    END {
        repeated = 0
        for (k = 1; k <= n; ++k) repeated += seen[order[k]] >= 2
        if (!repeated) { print "repeated_csv.sh: no benchmark repeated in the run" > "/dev/stderr"; exit 2 }
        if (mode == "median") {
            print header ",time_cv"
            for (k = 1; k <= n; ++k) print row[order[k]] "," (order[k] in cv ? cv[order[k]] : 0)
        } else {
            print header
            for (k = 1; k <= n; ++k) print row[order[k]]
        }
    }' "$csv"
