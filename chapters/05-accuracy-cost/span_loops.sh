#!/bin/sh
# The committed, dated run of bench_ch05_span_loops that the solutions of chapter 5's
# exercise on the masked wrap and chapter 6's exercise on evaluating the affine line
# afresh quote (chapters/05-accuracy-cost/span_loops_results.md).
# Usage (from the repository root):
#   cmake --build build --target bench-full-ch05_span_loops
#   chapters/05-accuracy-cost/span_loops.sh build ["note on the load"]
set -eu
build=${1:?usage: span_loops.sh BUILD_DIR [NOTE]}
note=${2:-}
csv="$build/bench/bench_ch05_span_loops.csv"
out=chapters/05-accuracy-cost/span_loops_results.md
. bench/committed_run.sh
require_csv "$csv" "span_loops.sh"
{
    echo "# Chapters 5 and 6: the mapper's inner loop, wrapped by modulo or by mask"
    echo
    measured_line "$csv" "bench/ch05_span_loops.cpp says what each run does"
    echo "Regenerate with"
    echo
    echo '```{.sh}'
    echo "cmake --build build --target bench-full-ch05_span_loops"
    echo "chapters/05-accuracy-cost/span_loops.sh build"
    echo '```'
    echo
    [ -z "$note" ] || { echo "$note"; echo; }
    echo ': Scene "modulo": CPU ns per pixel, and over the stepped affine loop with the modulo.'
    echo
    echo "| run | ns/px | × affine stepped, modulo |"
    echo "|:--|--:|--:|"
    bench/median_rows.sh "$csv" ns_per_px affine_stepped/modulo | sort
    echo
    echo ': Scene "mask": the same, over the stepped affine loop with the mask.'
    echo
    echo "| run | ns/px | × affine stepped, mask |"
    echo "|:--|--:|--:|"
    bench/median_rows.sh "$csv" ns_per_px affine_stepped/mask | sort
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
