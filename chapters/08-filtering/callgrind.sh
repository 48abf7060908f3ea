#!/bin/sh
# Instructions per pixel of every filter on every scene of chapter 8, counted by
# valgrind's callgrind: noise-free, unlike the times of bench_ch08_filters.
# Usage (from the repository root, after building bench_ch08_filters in BUILD_DIR):
#   chapters/08-filtering/callgrind.sh BUILD_DIR [OUTPUT.md]
# For each run NAME listed by `bench_ch08_filters --list` it runs
#   valgrind --tool=callgrind --toggle-collect=ch08_filter_once \
#            bench_ch08_filters --once=NAME
# which counts the instructions (Ir) executed inside one pass of the filter over the
# scene, and
# divides by the pixels filtered. Writes a Markdown table (default:
# chapters/08-filtering/callgrind_results.md). Takes a few minutes.
set -eu
build=${1:?usage: callgrind.sh BUILD_DIR [OUTPUT.md]}
out=${2:-chapters/08-filtering/callgrind_results.md}
bench="$build/bin/bench_ch08_filters"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
{
    echo "# Chapter 8: instructions per pixel (callgrind)"
    echo
    echo "Measured $(date -u +%Y-%m-%d) with $(valgrind --version) on $(uname -m)," \
         "compiler $(c++ --version | head -n 1). Regenerate with"
    echo "\`chapters/08-filtering/callgrind.sh build\` (Release build)."
    echo
    echo "| run | instructions | pixels | instructions per pixel |"
    echo "|:--|--:|--:|--:|"
    "$bench" --list | while read -r name pixels; do
        valgrind --tool=callgrind --toggle-collect=ch08_filter_once \
            --callgrind-out-file="$scratch/callgrind.out" \
            "$bench" --once="$name" >/dev/null 2>"$scratch/log"
        ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$scratch/log")
        echo "| $name | $ir | $pixels | $(awk "BEGIN { printf \"%.1f\", $ir / $pixels }") |"
    done
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
