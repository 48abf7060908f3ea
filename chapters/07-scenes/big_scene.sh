#!/bin/sh
# The 102,400-triangle torus at 1280 x 720 against Mesa's llvmpipe, one core each:
# CPU time per frame from one full run of bench_ch07_big_scene (pinned to one core,
# five interleaved repetitions, medians), instructions of one frame counted by
# valgrind's callgrind for both sides, and the renderer's per-stage report.
# Usage (from the repository root, after building bench_ch07_big_scene in BUILD_DIR):
#   chapters/07-scenes/big_scene.sh BUILD_DIR [OUTPUT.md]
# Instruction counts: for each run NAME it runs
#   LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect=ch07_frame_once \
#       bench_ch07_big_scene --once=NAME
# (and for our full scene also with --fast=none, and --fast=NAME for each fast path,
# screen_accept, masked_fetch, unlit_geometry and lean_spans, before --once: the plain
# path and each fast path alone)
# which counts one frame after an uncounted first one (llvmpipe compiles its code then;
# LP_NUM_THREADS=0 makes it rasterize in the counted thread). Writes Markdown tables whose
# rows are facts for the chapter's claims (default:
# chapters/07-scenes/big_scene_results.md). Takes ten minutes or more.
set -eu
build=${1:?usage: big_scene.sh BUILD_DIR [OUTPUT.md]}
out=${2:-chapters/07-scenes/big_scene_results.md}
bench="$build/bin/bench_ch07_big_scene"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
pin=
if command -v taskset >/dev/null; then pin="taskset -c 1"; fi
$pin "$bench" --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true \
    --benchmark_out="$scratch/times.csv" --benchmark_out_format=csv >/dev/null 2>&1
# The median CPU time (ms) of run NAME.
ms() {
    awk -F, -v n="\"$1/process_time_median\"" '$1 == n { printf "%.2f", $4 }' \
        "$scratch/times.csv"
}
ratio() { awk "BEGIN { printf \"%.2f\", $1 / $2 }"; }
# Instructions of one frame of run $1, with only the fast paths $2 when given.
instructions() {
    LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect=ch07_frame_once \
        --smc-check=all-non-file --callgrind-out-file="$scratch/callgrind.out" \
        "$bench" ${2:+--fast="$2"} --once="$1" >/dev/null 2>"$scratch/log"
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$scratch/log"
}
{
    echo "# Chapter 7: the big torus against llvmpipe, one core each"
    echo
    echo "Measured $(date -u +%Y-%m-%d) on $(uname -m) ($(nproc) cores, shared with other" \
         "work: load average $(cut -d' ' -f1-3 /proc/loadavg) at the start), compiler" \
         "$(c++ --version | head -n 1), Mesa" \
         "$(dpkg-query -W -f='${Version}' libgl1-mesa-dri 2>/dev/null || echo unknown)," \
         "$(valgrind --version). Regenerate with \`chapters/07-scenes/big_scene.sh build\`" \
         "(Release build). The scene: 102,400 triangles at 1280 x 720, textured (auto" \
         "mapper), depth on, back faces culled; llvmpipe draws the triangles our geometry" \
         "stage keeps (after culling), with LP_NUM_THREADS=1 (bench/ch07_big_scene.cpp)."
    echo
    echo "CPU time of the process per frame, median of five interleaved repetitions," \
         "pinned to one core:"
    echo
    echo "| run | ms per frame |"
    echo "|:--|--:|"
    for effects in full no_depth no_texture flat; do
        echo "| ours $effects | $(ms ours/$effects) |"
        echo "| llvmpipe $effects | $(ms llvmpipe/$effects) |"
    done
    echo
    echo "Ours over llvmpipe (time per frame; below 1 means ours is faster):"
    echo
    echo "| run | ratio |"
    echo "|:--|--:|"
    for effects in full no_depth no_texture flat; do
        echo "| time ratio $effects | $(ratio "$(ms ours/$effects)" "$(ms llvmpipe/$effects)") |"
    done
    echo "| ours full over ours flat | $(ratio "$(ms ours/full)" "$(ms ours/flat)") |"
    echo
    echo "Instructions of one frame (callgrind; llvmpipe with LP_NUM_THREADS=0):"
    echo
    ours_full=$(instructions ours/full)
    lp_full=$(instructions llvmpipe/full)
    ours_flat=$(instructions ours/flat)
    ours_plain=$(instructions ours/full none)
    ours_accept=$(instructions ours/full screen_accept)
    ours_masked=$(instructions ours/full masked_fetch)
    ours_unlit=$(instructions ours/full unlit_geometry)
    ours_lean=$(instructions ours/full lean_spans)
    echo "| run | instructions |"
    echo "|:--|--:|"
    echo "| instructions ours full | $ours_full |"
    echo "| instructions llvmpipe full | $lp_full |"
    echo "| instructions ours flat | $ours_flat |"
    echo "| instruction ratio full | $(ratio "$ours_full" "$lp_full") |"
    echo
    echo "Ours on the full scene with only some fast paths (FastPaths): none (the plain" \
         "path), each one alone; all of them is \"ours full\" above:"
    echo
    echo "| run | instructions |"
    echo "|:--|--:|"
    echo "| instructions ours full plain | $ours_plain |"
    echo "| instructions ours full screen_accept | $ours_accept |"
    echo "| instructions ours full masked_fetch | $ours_masked |"
    echo "| instructions ours full unlit_geometry | $ours_unlit |"
    echo "| instructions ours full lean_spans | $ours_lean |"
    echo
    echo "The same in millions:"
    echo
    echo "| run | millions of instructions |"
    echo "|:--|--:|"
    echo "| instructions ours full millions | $(ratio "$ours_full" 1000000) |"
    echo "| instructions llvmpipe full millions | $(ratio "$lp_full" 1000000) |"
    echo "| instructions ours flat millions | $(ratio "$ours_flat" 1000000) |"
    echo "| instructions ours full plain millions | $(ratio "$ours_plain" 1000000) |"
    echo "| instructions ours full screen_accept millions |" \
         "$(ratio "$ours_accept" 1000000) |"
    echo "| instructions ours full masked_fetch millions |" \
         "$(ratio "$ours_masked" 1000000) |"
    echo "| instructions ours full unlit_geometry millions |" \
         "$(ratio "$ours_unlit" 1000000) |"
    echo "| instructions ours full lean_spans millions |" \
         "$(ratio "$ours_lean" 1000000) |"
    "$bench" --report >"$scratch/report.txt"
    # The full scene's raster line: stage, triangles, spans, pixels, divides, ms.
    drawn=$(awk '/^## full/ { f = 1 } f && $1 == "raster" { print $2; exit }' \
        "$scratch/report.txt")
    pixels=$(awk '/^## full/ { f = 1 } f && $1 == "raster" { print $4; exit }' \
        "$scratch/report.txt")
    echo
    echo "What the full scene draws (the renderer's counts, exact):"
    echo
    echo "| count | value |"
    echo "|:--|--:|"
    echo "| triangles drawn full | $drawn |"
    echo "| pixels drawn full | $pixels |"
    echo "| pixels per drawn triangle full | $(ratio "$pixels" "$drawn") |"
    echo
    echo "Where the time of one frame goes, stage by stage, in milliseconds: the reports" \
         "below, the render whose total is the median of seven (depth has no row where" \
         "its stage is off):"
    echo
    echo "| stage | ms |"
    echo "|:--|--:|"
    awk '/^## / { set = $2 }
         set != "" && $2 ~ /^[0-9]+$/ &&
             ($1 == "geometry" || $1 == "depth" || $1 == "raster" || $1 == "texture") {
             printf "| stage ms %s %s | %s |\n", set, $1, $NF }
         /^total:/ { printf "| stage ms %s total | %s |\n", set, $(NF - 1) }' \
        "$scratch/report.txt"
    echo
    echo "Our renderer's report of each: of seven renders after a first, the one whose" \
         "total time is the median (times: wall clock, on the machine as the header says):"
    echo
    echo '```text'
    cat "$scratch/report.txt"
    echo '```'
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
