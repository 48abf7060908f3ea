#!/bin/sh
# Chapter 8's committed, dated full run: bench_ch08_filters pinned to one core, every
# benchmark three times in random order (a slow spell of a shared machine then falls on
# every filter alike), the fastest repetition of each kept (bench/repeated_csv.sh: for
# single-threaded work a busy neighbour only ever slows a repetition down), and
# fig_ch08_table's tables assembled into chapters/08-filtering/bench_results.md with the
# date, the machine, the load average at the start and the end of the run and the commit.
# The chapter's claims about time read that file. Times are CPU time of the benchmark's
# one thread.
# Usage (from the repository root, after building bench_ch08_filters and fig_ch08_table
# in BUILD_DIR, a Release build, on a machine as quiet as can be had):
#   chapters/08-filtering/full_run.sh BUILD_DIR [OUTPUT.md] ["note on the machine"]
# With RUN_CSV=FILE set, the benchmark is not run again: FILE is the --benchmark_out of a
# run made with the options below. Takes about three minutes.
set -eu
build=${1:?usage: full_run.sh BUILD_DIR [OUTPUT.md] [NOTE]}
out=${2:-chapters/08-filtering/bench_results.md}
note=${3:-}
type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
[ "$type" = Release ] || { echo "full_run.sh: $build is a '$type' build, not Release" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
pin=
if command -v taskset >/dev/null; then pin="taskset -c 1"; fi
options="--benchmark_repetitions=3 --benchmark_enable_random_interleaving=true"
load_start=$(cut -d ' ' -f 1-3 /proc/loadavg)
load_end=
if [ -z "${RUN_CSV:-}" ]; then
    RUN_CSV="$scratch/run.csv"
    # shellcheck disable=SC2086 # options and pin are word lists
    $pin "$build/bin/bench_ch08_filters" $options --benchmark_out="$RUN_CSV" \
        --benchmark_out_format=csv >/dev/null 2>&1
    load_end=$(cut -d ' ' -f 1-3 /proc/loadavg)
fi
bench/repeated_csv.sh fastest "$RUN_CSV" > "$scratch/bench_ch08_filters.csv"
"$build/bin/fig_ch08_table" "$scratch" >/dev/null
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
{
    echo "# Chapter 8: full benchmark run"
    echo
    echo "Measured $(date -u -r "$RUN_CSV" '+%Y-%m-%d %H:%M UTC') on $(uname -m), $(nproc) cores ($cpu), $(c++ --version | head -n 1), Release build, commit $(git rev-parse --short HEAD)."
    echo "Regenerate with \`chapters/08-filtering/full_run.sh build\`: ${pin:+pinned to one core, }every benchmark three times in random order, the fastest repetition of each (ns per pixel of CPU time; the error columns are deterministic, the same in every build)."
    echo "The time baseline, \`nearest\`, copies the 8-bit texel as stored; \`nearest linear-light\` picks the same texel through linear light and the encode, as every other filter does."
    echo
    if [ -n "$note" ]; then echo "$note"; echo; fi
    echo "## The machine during the run"
    echo
    if [ -n "$load_end" ]; then
        echo "| load average | 1 min | 5 min | 15 min |"
        echo "|:--|--:|--:|--:|"
        echo "$load_start" | awk '{ printf "| at start | %s | %s | %s |\n", $1, $2, $3 }'
        echo "$load_end" | awk '{ printf "| at end | %s | %s | %s |\n", $1, $2, $3 }'
    else
        echo "Made from a run given as RUN_CSV: its load is not known to this script."
    fi
    echo
    echo "## All runs"
    echo
    echo "Front: 1 when the filter is on the scene's Pareto front (no other filter at least as fast and as accurate on the minified pixels, and better in one), else 0."
    # fig_ch08_table's tables, the front column as 1 or 0 so that claims can read it
    sed 's/| yes |$/| 1 |/; s/|  |$/| 0 |/' "$scratch/ch08_table.md"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
