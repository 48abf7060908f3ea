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
[ -s "$csv" ] || { echo "span_loops.sh: no $csv: run the full benchmark first" >&2; exit 2; }
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
{
    echo "# Chapters 5 and 6: the mapper's inner loop, wrapped by modulo or by mask"
    echo
    echo "Measured $(date -u -r "$csv" +%Y-%m-%d) on $(uname -m), $(nproc) cores ($cpu)," \
         "$(c++ --version | head -n 1), Release build, pinned to one core, each benchmark" \
         "repeated five times in random order and the median taken (bench/ch05_span_loops.cpp" \
         "says what each run does). Regenerate with"
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
