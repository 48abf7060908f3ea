#!/bin/sh
# Chapter 5's committed, dated full run: bench_ch05_mappers pinned to one core, every
# benchmark three times in random order (a slow spell of a shared machine then falls on
# every mapper alike), and fig_ch05_table's tables (the fastest repetition of each, the
# run's noise from the spread of the repetitions, the Pareto fronts within that noise)
# assembled into chapters/05-accuracy-cost/bench_results.md with the date, the machine,
# the load average when the run began and ended, and a "met" column for the speed
# targets. The chapter's claims read that file.
# Usage (from the repository root, after building bench_ch05_mappers and fig_ch05_table):
#   chapters/05-accuracy-cost/full_run.sh BUILD_DIR [OUTPUT.md] ["note on the machine"]
# With RUN_CSV=FILE set, the benchmark is not run again: FILE is the --benchmark_out of a
# run made with the options below. Takes a few minutes (three on a 2.6 GHz EPYC).
set -eu
build=${1:?usage: full_run.sh BUILD_DIR [OUTPUT.md] [NOTE]}
out=${2:-chapters/05-accuracy-cost/bench_results.md}
note=${3:-}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
pin=
if command -v taskset >/dev/null; then pin="taskset -c 1"; fi
options="--benchmark_repetitions=3 --benchmark_enable_random_interleaving=true "
if [ -z "${RUN_CSV:-}" ]; then
    began=$(cut -d' ' -f1-3 /proc/loadavg)
    RUN_CSV="$scratch/run.csv"
    # shellcheck disable=SC2086 # options and pin are word lists
    $pin "$build/bin/bench_ch05_mappers" $options --benchmark_out="$RUN_CSV" \
        --benchmark_out_format=csv >/dev/null 2>&1
    load="load average (1, 5, 15 minutes) $began when the run began and $(cut -d' ' -f1-3 /proc/loadavg) when it ended (the run itself adds about 1)"
else
    load="run made earlier ($RUN_CSV), its load not recorded here"
fi
cp "$RUN_CSV" "$scratch/bench_ch05_mappers.csv"
"$build/bin/fig_ch05_table" "$scratch" >/dev/null
{
    echo "# Chapter 5: full benchmark run"
    echo
    echo "Measured $(date -u -r "$RUN_CSV" '+%Y-%m-%d %H:%M UTC') on $(uname -m), $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')), $(c++ --version | head -n 1), Release build, commit $(git rev-parse --short HEAD); $load."
    echo "Regenerate with \`chapters/05-accuracy-cost/full_run.sh build\`: ${pin:+pinned to one core, }every benchmark three times in random order, the fastest repetition of each (ns per pixel; the error columns are the same on every repetition). Two times are tied when the slower is within the run's noise of the faster (the median, over the run's benchmarks, of slowest over fastest repetition minus 1); the front is computed with ties (\`beaten by\` 0: on the front)."
    echo
    if [ -n "$note" ]; then echo "$note"; echo; fi
    echo "## Speed targets"
    echo
    # fig_ch05_table's target rows, with a "met" column: the ratio against "at most N".
    awk -F'|' 'NR == 1 { print "| target | mapper | × affine | met |"; next }
        NR == 2 { print "|:--|:--|--:|:-:|"; next }
        /^\|/ { split($2, a, "at most "); met = ($4 + 0 <= a[2] + 0) ? "yes" : "no"
                printf "|%s|%s|%s| %s |\n", $2, $3, $4, met; next }
        { print }' "$scratch/ch05_table_targets.md"
    echo
    echo "## Time noise"
    echo
    cat "$scratch/ch05_table_noise.md"
    echo
    echo "## Cheapest mapper under half a texel, by span depth ratio (floor)"
    echo
    cat "$scratch/ch05_table_picks.md"
    echo
    echo "## All runs"
    echo
    cat "$scratch/ch05_table.md"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
