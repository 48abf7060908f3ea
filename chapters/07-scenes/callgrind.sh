#!/bin/sh
# Instructions per textured pixel of the horizon scene under `auto` with each error
# budget of chapter 7's Exercise 5, counted by valgrind's callgrind: noise-free, unlike
# a time measured on a busy machine.
# Usage (from the repository root, after building fig_ch07_budgets in BUILD_DIR):
#   chapters/07-scenes/callgrind.sh BUILD_DIR [OUTPUT.md]
# For each budget B it runs
#   valgrind --tool=callgrind --toggle-collect='exactpixels::render_scene*' \
#            fig_ch07_budgets --once B
# which counts the instructions (Ir) executed inside one render of the scene (loading
# the scene file is not counted), and divides by its textured pixels. Writes a Markdown
# table (default: chapters/07-scenes/callgrind_results.md). Takes about a minute.
set -eu
build=${1:?usage: callgrind.sh BUILD_DIR [OUTPUT.md]}
out=${2:-chapters/07-scenes/callgrind_results.md}
program="$build/bin/fig_ch07_budgets"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
"$program" "$scratch" # the divides and textured pixels of every budget
pixels=$(sed -n 's/^pixels \([0-9]*\)$/\1/p' "$scratch/ch07_budgets.txt")
{
    echo "# Chapter 7: instructions per textured pixel of the horizon by budget (callgrind)"
    echo
    echo "Measured $(date -u +%Y-%m-%d) with $(valgrind --version) on $(uname -m)," \
         "compiler $(c++ --version | head -n 1). Regenerate with"
    echo "\`chapters/07-scenes/callgrind.sh build\` (Release build)."
    echo
    echo "| run | instructions | divides | textured pixels | instructions per pixel |"
    echo "|:--|--:|--:|--:|--:|"
    for budget in 0.05 0.1 0.25 0.5 1 2 4; do
        valgrind --tool=callgrind --toggle-collect='exactpixels::render_scene*' \
            --callgrind-out-file="$scratch/callgrind.out" \
            "$program" --once "$budget" >/dev/null 2>"$scratch/log"
        ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$scratch/log")
        divides=$(sed -n "s/^divides_$budget \([0-9]*\)$/\1/p" "$scratch/ch07_budgets.txt")
        echo "| budget $budget | $ir | $divides | $pixels |" \
             "$(awk "BEGIN { printf \"%.1f\", $ir / $pixels }") |"
    done
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
