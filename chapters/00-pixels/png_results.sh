#!/bin/sh
# The committed, dated run of bench_ch00_png that the solution of chapter 0's exercise on
# the cost of write_png quotes (chapters/00-pixels/png_results.md).
# Usage (from the repository root):
#   cmake --build build --target bench-full-ch00_png
#   chapters/00-pixels/png_results.sh build ["note on the load"]
set -eu
build=${1:?usage: png_results.sh BUILD_DIR [NOTE]}
note=${2:-}
csv="$build/bench/bench_ch00_png.csv"
out=chapters/00-pixels/png_results.md
. bench/committed_run.sh
require_csv "$csv" "png_results.sh"
{
    echo "# Chapter 0: what writing a PNG costs, and where"
    echo
    measured_line "$csv" "bench/ch00_png.cpp says what each run does"
    echo "Regenerate with"
    echo
    echo '```{.sh}'
    echo "cmake --build build --target bench-full-ch00_png"
    echo "chapters/00-pixels/png_results.sh build"
    echo '```'
    echo
    [ -z "$note" ] || { echo "$note"; echo; }
    echo ': Scene "time": CPU ns per pixel, and over copying a 64 × 64 frame.'
    echo
    echo "| run | ns/px | × copy of 64 × 64 |"
    echo "|:--|--:|--:|"
    bench/median_rows.sh "$csv" ns_per_px copy/64 | sort -t_ -k1,1 -k2,2n
    echo
    echo ': Scene "bytes": bytes produced per pixel (the copy: 4), and over the copy.'
    echo
    echo "| run | bytes/px | × copy of 64 × 64 |"
    echo "|:--|--:|--:|"
    bench/median_rows.sh "$csv" bytes_per_px copy/64 | sort -t_ -k1,1 -k2,2n
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
