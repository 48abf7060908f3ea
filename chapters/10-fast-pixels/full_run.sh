#!/bin/sh
# Chapter 10's committed, dated full run: every benchmark of bench_ch10_fast repeated
# five times in random order (so that a slow spell of a shared machine falls on every
# variant alike, not on whichever ran during it), and the median of each kept under the
# run's own name, so that chapters/10-fast-pixels/data/ch10_fast.csv reads like a single
# run for fig_ch10_speed and tests/ch10_claims.cpp. The median, not the fastest
# (bench/repeated_csv.sh says why): llvmpipe's process time and the two-thread wall clock
# depend on what the other core does, so their fastest repetition is not their truest.
# Usage (from the repository root, after building bench_ch10_fast in BUILD_DIR):
#   chapters/10-fast-pixels/full_run.sh BUILD_DIR [OUTPUT.csv] ["note on the machine"]
# FULL_RUN_REPETITIONS (default 5) sets the repetitions: three let llvmpipe's median on
# small triangles move by half between two runs on the same idle machine (2026-11-27:
# depth-tested 80 px, 1.68 ms then 0.92 ms), so the committed run takes five; fewer only
# to try the script. Takes about eight minutes.
set -eu
build=${1:?usage: full_run.sh BUILD_DIR [OUTPUT.csv] [NOTE]}
out=${2:-chapters/10-fast-pixels/data/ch10_fast.csv}
note=${3:-}
repetitions=${FULL_RUN_REPETITIONS:-5}
bench="$build/bin/bench_ch10_fast"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
started=$(date -u '+%Y-%m-%d %H:%M')
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
LP_NUM_THREADS=1 "$bench" --benchmark_repetitions="$repetitions" \
    --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
    --benchmark_out="$scratch/run.csv" --benchmark_out_format=csv >/dev/null 2>&1
# llvmpipe on two threads: OSMesa reads LP_NUM_THREADS once per process (at its first
# context), so the two-thread wall clock of llvmpipe is a second process, its rows added
# to the first run's (wall/llvmpipe/AREA/2 beside wall/llvmpipe/AREA/1).
LP_NUM_THREADS=2 "$bench" --benchmark_filter='^wall/llvmpipe/' --benchmark_repetitions="$repetitions" \
    --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
    --benchmark_out="$scratch/two.csv" --benchmark_out_format=csv >/dev/null 2>&1
cat "$scratch/two.csv" >> "$scratch/run.csv"
# llvmpipe held to SSE4.1 (128-bit vectors, four floats) where by default it generates
# AVX code (256-bit vectors, eight floats): Mesa reads GALLIUM_OVERRIDE_CPU_CAPS once per
# process, so these rows (MODE/llvmpipe_sse4.1/AREA/1) come from a third process.
LP_NUM_THREADS=1 GALLIUM_OVERRIDE_CPU_CAPS=sse4.1 "$bench" \
    --benchmark_filter='^(flat|depth)/llvmpipe_sse4.1/(0|80|1000)/' --benchmark_repetitions="$repetitions" \
    --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
    --benchmark_out="$scratch/narrow.csv" --benchmark_out_format=csv >/dev/null 2>&1
cat "$scratch/narrow.csv" >> "$scratch/run.csv"
{
    echo "# bench_ch10_fast full run, measured $started to $(date -u '+%H:%M') UTC: every benchmark"
    echo "# repeated $repetitions times in random order, the median of each kept under the run's name,"
    echo "# with the spread of the $repetitions in time_cv (their times' coefficient of variation)"
    echo "# machine: $(nproc) CPUs ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')), load average $load_start at the start, $(cut -d' ' -f1-3 /proc/loadavg) at the end${note:+; $note}"
    echo "# software: $(c++ --version | head -n 1), $(dpkg-query -W -f 'Mesa ${Version}' libosmesa6 2>/dev/null || echo 'Mesa') llvmpipe via OSMesa, Release build, commit $(git rev-parse --short HEAD)"
    echo "# command: chapters/10-fast-pixels/full_run.sh build"
    echo "# rates are per second of process CPU time (all threads) except wall/* (wall clock)"
    bench/repeated_csv.sh median "$scratch/run.csv"
} > "$out.tmp"
grep -q '^"flat/walk/3/1/process_time"' "$out.tmp" || {
    echo "full_run.sh: the run wrote no repeated benchmark (see $bench --help)" >&2
    rm -f "$out.tmp"
    exit 2
}
mv "$out.tmp" "$out"
echo "wrote $out"
