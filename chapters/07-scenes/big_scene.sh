#!/bin/sh
# The 102,400-triangle torus at 1280 x 720 against Mesa's llvmpipe, one core each, under
# chapter 7's measurement protocol (bench/ch07_big_scene.cpp says what each side is
# given and does): CPU time per frame from one full run of bench_ch07_big_scene (pinned
# to one core, interleaved repetitions, each row's median with the smallest and largest
# repetition), the fixed cost of a frame with nothing in it on its own rows and the
# ratios both as measured and with it subtracted, the frame check of every llvmpipe run
# (its frame against ours, after timing), instructions of one frame counted by
# valgrind's callgrind for both sides, and the renderer's per-stage report. Then two
# threads each: the full and empty frames with `--threads=2` (ours with
# FastPaths::threads = 2, llvmpipe with LP_NUM_THREADS=2), pinned to two cores, in
# wall-clock time, the same repetitions.
# Usage (from the repository root, after building bench_ch07_big_scene in BUILD_DIR):
#   chapters/07-scenes/big_scene.sh BUILD_DIR [OUTPUT.md]
# BIG_SCENE_REPETITIONS (default 5) sets the repetitions; fewer only to try the script:
# the committed run uses the default.
# Instruction counts: for each run NAME it runs
#   LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect=ch07_frame_once \
#       bench_ch07_big_scene --once=NAME
# (and for our full scene also with --fast=none, and --fast=NAME for each fast path,
# masked_fetch, lean_spans and lean_geometry, before --once: the plain path, each fast
# path alone, and masked_fetch with lean_spans)
# which counts one frame after an uncounted first one (llvmpipe compiles its code then;
# LP_NUM_THREADS=0 makes it rasterize in the counted thread). Writes Markdown tables whose
# rows are facts for the chapter's claims (default:
# chapters/07-scenes/big_scene_results.md). Fails when a benchmark reports an error (a
# llvmpipe frame that does not match ours). Takes ten minutes or more.
set -eu
build=${1:?usage: big_scene.sh BUILD_DIR [OUTPUT.md]}
out=${2:-chapters/07-scenes/big_scene_results.md}
repetitions=${BIG_SCENE_REPETITIONS:-5}
bench="$build/bin/bench_ch07_big_scene"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
pin=
if command -v taskset >/dev/null; then pin="taskset -c 1"; fi
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
started=$(date -u '+%Y-%m-%d %H:%M UTC')
$pin "$bench" --benchmark_repetitions="$repetitions" \
    --benchmark_enable_random_interleaving=true \
    --benchmark_out="$scratch/times.csv" --benchmark_out_format=csv >/dev/null 2>&1 || {
    echo "big_scene.sh: bench_ch07_big_scene failed" >&2
    exit 1
}
pin2=
if command -v taskset >/dev/null && [ "$(nproc)" -ge 2 ]; then pin2="taskset -c 0,1"; fi
$pin2 "$bench" --threads=2 --benchmark_repetitions="$repetitions" \
    --benchmark_enable_random_interleaving=true \
    --benchmark_out="$scratch/times2.csv" --benchmark_out_format=csv >/dev/null 2>&1 || {
    echo "big_scene.sh: bench_ch07_big_scene --threads=2 failed" >&2
    exit 1
}
load_end=$(cut -d' ' -f1-3 /proc/loadavg)
# Column $2 (a header name: cpu_time, or a counter such as coverage_diff) of the row
# named $1 (such as "ours/full/process_time_median"), in the file $3 (default: the
# one-core run's).
column() {
    awk -F, -v n="\"$1\"" -v c="$2" '
        $1 == "name" { for (i = 1; i <= NF; i++) { h = $i; gsub(/"/, "", h); at[h] = i } }
        $1 == n { print $(at[c]); exit }' "${3:-$scratch/times.csv}"
}
errors=$(awk -F, '$9 == "true" { print $1 ": " $10 }' "$scratch/times.csv" \
    "$scratch/times2.csv")
if [ -n "$errors" ]; then
    echo "big_scene.sh: runs reported errors:" >&2
    echo "$errors" >&2
    exit 1
fi
# The median, smallest and largest CPU time (ms) of run NAME's repetitions.
ms() { column "$1/process_time_median" cpu_time | awk '{ printf "%.3f", $1 }'; }
ms_min() { column "$1/process_time_min" cpu_time | awk '{ printf "%.3f", $1 }'; }
ms_max() { column "$1/process_time_max" cpu_time | awk '{ printf "%.3f", $1 }'; }
# A frame-check counter of llvmpipe's run NAME.
check() { column "llvmpipe/$1/process_time_median" "$2" | awk '{ printf "%d", $1 }'; }
ratio() { awk "BEGIN { printf \"%.2f\", $1 / $2 }"; }
# The same of the two-thread run NAME, in wall-clock time.
ms2() {
    column "$1/real_time_$2" real_time "$scratch/times2.csv" | awk '{ printf "%.3f", $1 }'
}
# Ours over llvmpipe with each side's empty frame ($2) subtracted from run $1.
ratio_less() {
    ratio "($(ms ours/$1) - $(ms ours/$2))" "($(ms llvmpipe/$1) - $(ms llvmpipe/$2))"
}
# Rows "$1" and "$1 less empty": ours ($2) over llvmpipe ($3), as measured and with
# each side's empty frame (ours $4, llvmpipe $5) subtracted from its own.
ratio_rows() {
    echo "| $1 | $(ratio "$2" "$3") |"
    echo "| $1 less empty | $(ratio "($2 - $4)" "($3 - $5)") |"
}
percent() { awk "BEGIN { printf \"%.1f\", 100 * $1 / $2 }"; }
# The empty run whose fixed cost run $1 pays: with depth or without.
empty_of() {
    case $1 in no_depth | flat) echo empty_no_depth ;; *) echo empty ;; esac
}
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
    echo "Measured $started on $(uname -m)" \
         "($(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -n 1)," \
         "$(nproc) cores, shared with other work: load average $load_start at the start" \
         "of the timed runs and $load_end at their end), compiler" \
         "$(c++ --version | head -n 1), Mesa" \
         "$(dpkg-query -W -f='${Version}' libgl1-mesa-dri 2>/dev/null || echo unknown)," \
         "$(valgrind --version). Regenerate with \`chapters/07-scenes/big_scene.sh build\`" \
         "(Release build). The scene: 102,400 triangles at 1280 x 720, textured (auto" \
         "mapper), depth on, back faces culled. Both sides start from the model as" \
         "loaded: ours renders it with render_scene; llvmpipe (LP_NUM_THREADS=1) draws" \
         "it with one glDrawElements of its world-space positions and texture" \
         "coordinates (each distinct pair once) through the camera's matrices, culls" \
         "the back faces itself and clears the depth buffer every frame, as ours makes" \
         "a fresh one (bench/ch07_big_scene.cpp)."
    echo
    echo "CPU time of the process per frame in ms, pinned to one core, $repetitions" \
         "interleaved repetitions: the median, and the smallest and largest repetition." \
         "The empty runs draw nothing (ours: a frame and a depth buffer made and" \
         "cleared; llvmpipe: the clears and glFinish, which copies the frame into the" \
         "caller's buffer); \"no_depth\" has no depth buffer on either side. llvmpipe's" \
         "frame_copy is that copy alone (a frame with a triangle that covers no pixel" \
         "and no clear):"
    echo
    echo "| run | min | max | median |"
    echo "|:--|--:|--:|--:|"
    for effects in full no_depth no_texture flat empty empty_no_depth; do
        for side in ours llvmpipe; do
            echo "| $side $effects | $(ms_min $side/$effects) |" \
                 "$(ms_max $side/$effects) | $(ms $side/$effects) |"
        done
    done
    echo "| llvmpipe frame_copy | $(ms_min llvmpipe/frame_copy) |" \
         "$(ms_max llvmpipe/frame_copy) | $(ms llvmpipe/frame_copy) |"
    echo
    echo "The empty frame's share of each frame (percent of the median; no_depth and" \
         "flat against empty_no_depth):"
    echo
    echo "| run | percent |"
    echo "|:--|--:|"
    for effects in full no_depth no_texture flat; do
        for side in ours llvmpipe; do
            echo "| fixed cost percent $side $effects |" \
                 "$(percent "$(ms $side/$(empty_of $effects))" "$(ms $side/$effects)") |"
        done
    done
    echo
    echo "Ours over llvmpipe (time per frame; below 1 means ours is faster), as" \
         "measured, and with each side's empty frame subtracted from its own (\"less" \
         "empty\"):"
    echo
    echo "| run | ratio |"
    echo "|:--|--:|"
    for effects in full no_depth no_texture flat; do
        echo "| time ratio $effects | $(ratio "$(ms ours/$effects)" "$(ms llvmpipe/$effects)") |"
        echo "| time ratio $effects less empty | $(ratio_less $effects "$(empty_of $effects)") |"
    done
    echo "| ours full over ours flat | $(ratio "$(ms ours/full)" "$(ms ours/flat)") |"
    echo
    echo "Two threads each (ours: FastPaths::threads = 2, the triangles binned into" \
         "bands of 64 rows; llvmpipe: LP_NUM_THREADS=2), pinned to two cores, the full" \
         "scene and the empty frame: wall-clock ms per frame, $repetitions interleaved" \
         "repetitions (min, max, median), and ours over llvmpipe as measured and less" \
         "each side's empty frame:"
    echo
    echo "| run | min | max | median |"
    echo "|:--|--:|--:|--:|"
    for run in full empty; do
        for side in ours llvmpipe; do
            echo "| two threads $side $run | $(ms2 "$side/${run}_2_threads" min) |" \
                 "$(ms2 "$side/${run}_2_threads" max) |" \
                 "$(ms2 "$side/${run}_2_threads" median) |"
        done
    done
    full2_ours=$(ms2 ours/full_2_threads median)
    full2_lp=$(ms2 llvmpipe/full_2_threads median)
    empty2_ours=$(ms2 ours/empty_2_threads median)
    empty2_lp=$(ms2 llvmpipe/empty_2_threads median)
    echo
    echo "| run | ratio |"
    echo "|:--|--:|"
    ratio_rows "time ratio full two threads" "$full2_ours" "$full2_lp" "$empty2_ours" \
        "$empty2_lp"
    echo
    echo "The frame check of each llvmpipe run, after its timed loop: its last frame" \
         "against our render of the same scene, pixel by pixel; a pixel is covered when" \
         "it keeps its colour over a second background. Pixels our frame covers, pixels" \
         "covered in one frame and not the other (a run fails above one in ten" \
         "thousand of the covered), and pixels covered in both whose colour differs" \
         "(the two took a different texel or a different triangle there). The run" \
         "ids draws the full scene with every triangle in a colour of its own, its" \
         "24-bit id (a texture of ids, each triangle's corners at its own texel's" \
         "centre), so that its colour differences are pixels another triangle won:"
    echo
    echo "| frame check | pixels |"
    echo "|:--|--:|"
    for effects in full no_depth no_texture flat empty empty_no_depth ids; do
        echo "| pixels covered $effects | $(check $effects covered) |"
        echo "| coverage differences $effects | $(check $effects coverage_diff) |"
        echo "| colour differences $effects | $(check $effects colour_diff) |"
    done
    echo
    echo "Instructions of one frame (callgrind; llvmpipe with LP_NUM_THREADS=0):"
    echo
    ours_full=$(instructions ours/full)
    lp_full=$(instructions llvmpipe/full)
    ours_empty=$(instructions ours/empty)
    lp_empty=$(instructions llvmpipe/empty)
    ours_flat=$(instructions ours/flat)
    ours_plain=$(instructions ours/full none)
    ours_masked=$(instructions ours/full masked_fetch)
    ours_lean=$(instructions ours/full lean_spans)
    ours_geometry=$(instructions ours/full lean_geometry)
    ours_both=$(instructions ours/full masked_fetch,lean_spans)
    echo "| run | instructions |"
    echo "|:--|--:|"
    echo "| instructions ours full | $ours_full |"
    echo "| instructions llvmpipe full | $lp_full |"
    echo "| instructions ours flat | $ours_flat |"
    echo "| instructions ours empty | $ours_empty |"
    echo "| instructions llvmpipe empty | $lp_empty |"
    ratio_rows "instruction ratio full" "$ours_full" "$lp_full" "$ours_empty" "$lp_empty"
    echo
    echo "Ours on the full scene with only some fast paths (FastPaths): none (the teaching" \
         "path), each one alone (exact_lanes serves only the exact mapper), and" \
         "masked_fetch with lean_spans; all of them is" \
         "\"ours full\" above:"
    echo
    echo "| run | instructions |"
    echo "|:--|--:|"
    echo "| instructions ours full plain | $ours_plain |"
    echo "| instructions ours full masked_fetch | $ours_masked |"
    echo "| instructions ours full lean_spans | $ours_lean |"
    echo "| instructions ours full lean_geometry | $ours_geometry |"
    echo "| instructions ours full masked_fetch lean_spans | $ours_both |"
    echo
    echo "The same in millions:"
    echo
    echo "| run | millions of instructions |"
    echo "|:--|--:|"
    echo "| instructions ours full millions | $(ratio "$ours_full" 1000000) |"
    echo "| instructions llvmpipe full millions | $(ratio "$lp_full" 1000000) |"
    echo "| instructions ours flat millions | $(ratio "$ours_flat" 1000000) |"
    echo "| instructions ours empty millions | $(ratio "$ours_empty" 1000000) |"
    echo "| instructions llvmpipe empty millions | $(ratio "$lp_empty" 1000000) |"
    echo "| instructions ours full plain millions | $(ratio "$ours_plain" 1000000) |"
    echo "| instructions ours full masked_fetch millions |" \
         "$(ratio "$ours_masked" 1000000) |"
    echo "| instructions ours full lean_spans millions |" \
         "$(ratio "$ours_lean" 1000000) |"
    echo "| instructions ours full lean_geometry millions |" \
         "$(ratio "$ours_geometry" 1000000) |"
    echo "| instructions ours full masked_fetch lean_spans millions |" \
         "$(ratio "$ours_both" 1000000) |"
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
if grep -q '|  |' "$out.tmp"; then # a value the runs did not give
    echo "big_scene.sh: an empty cell in $out.tmp:" >&2
    grep '|  |' "$out.tmp" >&2
    exit 1
fi
mv "$out.tmp" "$out"
echo "wrote $out"
