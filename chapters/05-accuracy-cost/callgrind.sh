#!/bin/sh
# Instructions per pixel of every mapper on every scene of chapter 5, counted by
# valgrind's callgrind: noise-free, unlike the times of bench_ch05_mappers.
# Usage (from the repository root, after building bench_ch05_mappers in BUILD_DIR):
#   chapters/05-accuracy-cost/callgrind.sh BUILD_DIR [OUTPUT.md]
# For each run NAME listed by `bench_ch05_mappers --list` it runs
#   valgrind --tool=callgrind --toggle-collect=ch05_render_once \
#            bench_ch05_mappers --once=NAME
# which counts the instructions (Ir) executed inside one drawing of the scene, and
# divides by the scene's pixel writes. Writes a Markdown table (default:
# chapters/05-accuracy-cost/callgrind_results.md). Takes about two minutes.
set -eu
build=${1:?usage: callgrind.sh BUILD_DIR [OUTPUT.md]}
out=${2:-chapters/05-accuracy-cost/callgrind_results.md}
bench="$build/bin/bench_ch05_mappers"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
{
    echo "# Chapter 5: instructions per pixel (callgrind)"
    echo
    echo "Measured $(date -u +%Y-%m-%d) with $(valgrind --version) on $(uname -m)," \
         "compiler $(c++ --version | head -n 1). Regenerate with"
    echo "\`chapters/05-accuracy-cost/callgrind.sh build\` (Release build)."
    echo
    echo "| run | instructions | pixel writes | instructions per pixel |"
    echo "|:--|--:|--:|--:|"
    "$bench" --list | while read -r name pixels; do
        valgrind --tool=callgrind --toggle-collect=ch05_render_once \
            --callgrind-out-file="$scratch/callgrind.out" \
            "$bench" --once="$name" >/dev/null 2>"$scratch/log"
        ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$scratch/log")
        echo "| $name | $ir | $pixels | $(awk "BEGIN { printf \"%.1f\", $ir / $pixels }") |"
    done
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
