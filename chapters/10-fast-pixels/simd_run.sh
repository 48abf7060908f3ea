#!/bin/sh
# Chapter 10's vector instruction sets (@sec:fast-simd): the textured runs forced to each
# set this CPU has, against llvmpipe, on the 1000 px textured set and the empty frame
# (bench_ch10_fast --simd), one core each, interleaved in one run; then callgrind's
# instructions per triangle of the sets valgrind can run (it has no AVX-512).
# Usage (from the repository root, after building bench_ch10_fast in BUILD_DIR, a
# Release build):
#   chapters/10-fast-pixels/simd_run.sh BUILD_DIR
# Writes chapters/10-fast-pixels/simd_results.md, whose table rows are the facts the
# chapter quotes. Takes about three minutes.
set -eu
build=${1:?usage: simd_run.sh BUILD_DIR}
out=chapters/10-fast-pixels/simd_results.md
bench="$build/bin/bench_ch10_fast"
[ -x "$bench" ] || { echo "simd_run.sh: no $bench: build bench_ch10_fast first" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
pin=""
command -v taskset >/dev/null && pin="taskset -c 1"
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
mesa=$(dpkg-query -W -f='${Version}' libgl1-mesa-dri 2>/dev/null || echo unknown)
start=$(date -u +'%Y-%m-%d %H:%M')
load_start=$(cut -d ' ' -f 1-3 /proc/loadavg)
LP_NUM_THREADS=1 $pin "$bench" --simd --benchmark_repetitions=5 \
    --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
    --benchmark_out="$scratch/run.csv" --benchmark_out_format=csv >"$scratch/log"
end=$(date -u +%H:%M)
load_end=$(cut -d ' ' -f 1-3 /proc/loadavg)
bench/repeated_csv.sh median "$scratch/run.csv" >"$scratch/median.csv"
# name -> ms per frame (process CPU time), from the medians
ms() {
    awk -F, -v want="\"textured/$1/1/process_time\"" '$1 == want { printf "%.3f", $4 / 1e6 }' "$scratch/median.csv"
}
count() {
    LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect=ch10_draw_once \
        --smc-check=all-non-file --callgrind-out-file="$scratch/callgrind.out" \
        "$bench" --once="textured/$1" >/dev/null 2>"$scratch/vg.log"
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$scratch/vg.log"
}
{
    echo "# Chapter 10: the textured runs in each vector instruction set against llvmpipe"
    echo
    echo "Measured $start-$end UTC on $(uname -m) ($cpu, $(nproc --all) cores; load average $load_start at the start, $load_end at the end), compiler $(c++ --version | head -n 1), Mesa $mesa, $(valgrind --version). Regenerate with \`chapters/10-fast-pixels/simd_run.sh build\` (Release build). The set: 1024 textured triangles of 1000 px (bench_ch10_fast's textured set, perspective-correct, nearest texel, a 256 x 256 texture that repeats), drawn in order into a 1024 x 1024 frame; llvmpipe with LP_NUM_THREADS=1 draws the same triangles (clip-space w = the depth), pinned to one core, 5 repetitions interleaved at random, the median."
    echo
    echo "Milliseconds of process CPU time per frame; \"net\" is the frame less the empty frame of the same side (its fixed cost), \"over llvmpipe\" llvmpipe's net time over the variant's:"
    echo
    echo "| run | ms |"
    echo "|:--|--:|"
    lp=$(ms llvmpipe/1000); lp0=$(ms llvmpipe/0)
    echo "| llvmpipe 1000 | $lp |"
    echo "| llvmpipe 0 | $lp0 |"
    sets=$(sed -n 's/^"textured\/runs_\([a-z0-9]*\)\/1000\/1\/process_time".*/\1/p' "$scratch/median.csv")
    for s in $sets; do
        echo "| $s 1000 | $(ms runs_$s/1000) |"
        echo "| $s 0 | $(ms runs_$s/0) |"
    done
    echo
    echo "| variant | over llvmpipe |"
    echo "|:--|--:|"
    for s in $sets; do
        awk -v a="$lp" -v a0="$lp0" -v b="$(ms runs_$s/1000)" -v b0="$(ms runs_$s/0)" -v s="$s" \
            'BEGIN { printf "| %s over llvmpipe | %.2f |\n", s, (a - a0) / (b - b0) }'
    done
    echo
    echo "Instructions per triangle (callgrind, one frame less the empty frame, over 1024 triangles; valgrind runs no AVX-512, so that set is not counted):"
    echo
    echo "| run | instructions per triangle |"
    echo "|:--|--:|"
    for run in runs_portable runs_sse2 runs_avx2 llvmpipe; do
        full=$(count "$run/1000"); empty=$(count "$run/0")
        [ -n "$full" ] || continue
        awk -v f="$full" -v e="$empty" -v r="$run" \
            'BEGIN { sub(/^runs_/, "", r); printf "| instructions %s | %.0f |\n", r, (f - e) / 1024 }'
    done
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
