#!/bin/sh
# Chapter 10's textured run: perspective-correct nearest texturing, the teaching path and
# the textured runs against llvmpipe (bench_ch10_fast --textured), as its own committed,
# dated file, so that the default run (data/ch10_fast.csv) is regenerated independently.
# Usage (from the repository root, after building bench_ch10_fast in BUILD_DIR, a
# Release build, on a machine as quiet as can be had):
#   chapters/10-fast-pixels/textured_run.sh BUILD_DIR
# Writes data/ch10_textured.csv (every benchmark three times in random order, the median
# of each kept, as full_run.sh does; llvmpipe with LP_NUM_THREADS=1, rates per second of
# process CPU time) with a
# '#' header naming the date, machine, load, software and command, and
# data/ch10_textured_compare.csv (bench_ch10_fast --compare-textured=AREA for every area:
# pixels drawn, coverage and texel differences against llvmpipe, and the runs against the
# teaching path), and data/ch10_textured_instructions.csv (instructions per triangle of
# one frame, counted by callgrind as callgrind.sh counts the default run, less the count
# of a frame with nothing in it: the teaching path, the runs and llvmpipe at 3 and
# 1000 px). Takes about five minutes.
set -eu
build=${1:?usage: textured_run.sh BUILD_DIR}
data=chapters/10-fast-pixels/data
bench="$build/bin/bench_ch10_fast"
[ -x "$bench" ] || { echo "textured_run.sh: no $bench: build bench_ch10_fast first" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
mhz=$(sed -n 's/^cpu MHz[[:space:]]*: \([0-9]*\).*/\1/p' /proc/cpuinfo | head -n 1)
mesa=$(dpkg-query -W -f='${Version}' libgl1-mesa-dri 2>/dev/null || echo unknown)
type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
start=$(date -u +'%Y-%m-%d %H:%M')
load_start=$(cut -d ' ' -f 1-3 /proc/loadavg)
LP_NUM_THREADS=1 "$bench" --textured --benchmark_repetitions=3 \
    --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
    --benchmark_out="$scratch/run.csv" --benchmark_out_format=csv >"$scratch/log"
end=$(date -u +%H:%M)
load_end=$(cut -d ' ' -f 1-3 /proc/loadavg)
{
    echo "# bench_ch10_fast --textured full run, measured $start-$end UTC: every benchmark repeated"
    echo "# three times in random order, the median of each kept under the run's name (as full_run.sh),"
    echo "# with the spread of the three in time_cv (their times' coefficient of variation)"
    echo "# machine: $cpu, $(nproc --all) cores at $mhz MHz, load average (1, 5, 15 min) $load_start at the start, $load_end at the end"
    echo "# software: $(c++ --version | head -n 1), Mesa $mesa llvmpipe via OSMesa, ${type:-unknown} build, commit $commit"
    echo "# command: chapters/10-fast-pixels/textured_run.sh build (LP_NUM_THREADS=1 bench_ch10_fast --textured --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true)"
    echo "# rates are per second of process CPU time (all threads, llvmpipe's rasterizer thread too)"
    bench/repeated_csv.sh median "$scratch/run.csv"
} >"$data/ch10_textured.csv.tmp"
mv "$data/ch10_textured.csv.tmp" "$data/ch10_textured.csv"
{
    echo "# bench_ch10_fast --compare-textured=AREA for every area, $(date -u +%Y-%m-%d), Mesa $mesa: pixels the teaching path"
    echo "# draws (textured set, 1024 triangles in order), pixels whose coverage differs in llvmpipe's frame, pixels both draw"
    echo "# with another texel, how many of those are a neighbouring texel, pixels where the runs differ from the teaching path"
    echo "name,pixels_drawn,coverage_differ,texel_differ,neighbour_texel,runs_differ"
    for area in 3 15 80 1000 65536; do
        LP_NUM_THREADS=1 "$bench" --compare-textured="$area"
    done
} >"$data/ch10_textured_compare.csv.tmp"
mv "$data/ch10_textured_compare.csv.tmp" "$data/ch10_textured_compare.csv"
{
    echo "# Chapter 10, textured: instructions per triangle (callgrind), measured $(date -u +%Y-%m-%d)"
    echo "# with $(valgrind --version) on $(uname -m), compiler $(c++ --version | head -n 1),"
    echo "# Mesa $mesa. Regenerate with chapters/10-fast-pixels/textured_run.sh build (Release build)."
    echo "# instructions_per_triangle = (instructions - fixed_instructions) / triangles, where"
    echo "# fixed_instructions is the count of textured/VARIANT/0, a frame with nothing in it."
    echo "name,instructions,fixed_instructions,triangles,instructions_per_triangle"
    count() {
        LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect=ch10_draw_once \
            --smc-check=all-non-file --callgrind-out-file="$scratch/callgrind.out" \
            "$bench" --once="$1" >/dev/null 2>"$scratch/log"
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$scratch/log"
    }
    for variant in teaching runs llvmpipe; do
        fixed=$(count "textured/$variant/0")
        echo "textured/$variant/0,$fixed,$fixed,0,0"
        for area in 3 1000; do
            ir=$(count "textured/$variant/$area")
            echo "textured/$variant/$area,$ir,$fixed,1024,$(awk "BEGIN { printf \"%.1f\", ($ir - $fixed) / 1024 }")"
        done
    done
} >"$data/ch10_textured_instructions.csv.tmp"
mv "$data/ch10_textured_instructions.csv.tmp" "$data/ch10_textured_instructions.csv"
echo "wrote $data/ch10_textured.csv, ch10_textured_compare.csv, ch10_textured_instructions.csv"
