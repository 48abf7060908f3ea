#!/bin/sh
# A repeated Google Benchmark run as if it were one run: the CSV header row and each
# benchmark's _median row under the benchmark's own name, for readers that take one row
# per run (read_benchmark_csv, fig_ch05_table, fig_ch09_speed).
# Usage: bench/median_csv.sh RUN.csv > MEDIANS.csv
#   RUN.csv   --benchmark_out of a run with --benchmark_repetitions=N (N >= 2) and
#             --benchmark_report_aggregates_only=true (or without it: other rows are dropped)
# Exits 2, printing nothing, when RUN.csv holds no median row.
set -eu
csv=${1:?usage: median_csv.sh RUN.csv}
[ -s "$csv" ] || { echo "median_csv.sh: no $csv" >&2; exit 2; }
grep -q '_median"\{0,1\},' "$csv" || { echo "median_csv.sh: no _median rows in $csv" >&2; exit 2; }
awk -F, 'BEGIN { OFS = "," }
    /^name,/ { print; next }
    $1 ~ /_median"?$/ { sub(/_median/, "", $1); print }' "$csv"
