#!/bin/sh
# Instructions per triangle of chapter 10's variants and of llvmpipe, counted by
# valgrind's callgrind: noise-free, unlike the times of bench_ch10_fast on a busy machine.
# Usage (from the repository root, after building bench_ch10_fast in BUILD_DIR):
#   chapters/10-fast-pixels/callgrind.sh BUILD_DIR [OUTPUT.csv]
# For each run NAME (MODE/VARIANT/AREA: walk, runs, masks and llvmpipe at 3, 80 and
# 1000 px; 65536 px takes too long under valgrind) it runs
#   LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect=ch10_draw_once \
#       bench_ch10_fast --once=NAME
# which counts the instructions (Ir) of one frame of the run's 1024 triangles, after
# an uncounted first frame (llvmpipe compiles its code then; LP_NUM_THREADS=0 makes it
# rasterize in the counted thread). Area 0 is the same frame with nothing in it (the
# depth clear, llvmpipe's frame copy): its count is the fixed cost of the frame, written
# as its own row, and instructions_per_triangle is (instructions - fixed) / triangles,
# the fixed cost subtracted openly (chapter 10's measurement protocol). Writes a CSV
# (default: chapters/10-fast-pixels/data/ch10_instructions.csv). Takes a few minutes.
set -eu
build=${1:?usage: callgrind.sh BUILD_DIR [OUTPUT.csv]}
out=${2:-chapters/10-fast-pixels/data/ch10_instructions.csv}
bench="$build/bin/bench_ch10_fast"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
{
    echo "# Chapter 10: instructions per triangle (callgrind), measured $(date -u +%Y-%m-%d)"
    echo "# with $(valgrind --version) on $(uname -m), compiler $(c++ --version | head -n 1),"
    echo "# Mesa $(dpkg-query -W -f='${Version}' libgl1-mesa-dri 2>/dev/null || echo unknown)."
    echo "# Regenerate with chapters/10-fast-pixels/callgrind.sh build (Release build)."
    echo "# instructions_per_triangle = (instructions - fixed_instructions) / triangles, where"
    echo "# fixed_instructions is the count of MODE/VARIANT/0, a frame with nothing in it."
    echo "name,instructions,fixed_instructions,triangles,instructions_per_triangle"
    fixed=0
    "$bench" --list | while read -r name triangles; do
        case "$name" in */15 | */65536 | */blocks/* | */tiled/*) continue ;; esac
        LP_NUM_THREADS=0 valgrind --tool=callgrind --toggle-collect=ch10_draw_once \
            --smc-check=all-non-file --callgrind-out-file="$scratch/callgrind.out" \
            "$bench" --once="$name" >/dev/null 2>"$scratch/log"
        ir=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$scratch/log")
        case "$name" in
        */0) fixed=$ir; echo "$name,$ir,$ir,0,0" ;; # --list gives area 0 first
        *) echo "$name,$ir,$fixed,$triangles,$(awk "BEGIN { printf \"%.1f\", ($ir - $fixed) / $triangles }")" ;;
        esac
    done
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
