#!/bin/sh
# Chapter 2's committed, dated full run: the speed tables of bench_ch02_rasterizers, from
# the full run's CSV, with the machine and the date, into a Markdown file whose table rows
# the chapter's .claim spans check (book/AUTHORING.md, "Claims the build checks").
# Usage (from the repository root, after the full run):
#   cmake --build build --target bench-full-ch02_rasterizers   # or the `bench` workflow
#   chapters/02-edge-functions/bench_results.sh build [OUTPUT.md] ["note on the load"]
# The full run is pinned to one core (taskset -c 1) and repeats every benchmark five
# times, interleaved at random; fig_ch02_speed takes the median of the repetitions. The
# tables are named for the claims by a caption before each: Scene "small" (3, 15, 80 px),
# "large" (4096 and 65536 px) and "sweep" (Mpix/s against area), so a row is a fact such
# as small/fixed_8x8#5 (its rate over the naive rasterizer's at 3 px).
set -eu
build=${1:?usage: bench_results.sh BUILD_DIR [OUTPUT.md] [NOTE]}
out=${2:-chapters/02-edge-functions/bench_results.md}
note=${3:-}
csv="$build/bench/bench_ch02_rasterizers.csv"
[ -s "$csv" ] || { echo "bench_results.sh: no $csv: run the full benchmark first" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp "$csv" "$scratch/"
"$build/bin/fig_ch02_speed" "$scratch" >/dev/null
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
{
    echo "# Chapter 2: full benchmark run"
    echo
    echo "Measured $(date -u -r "$csv" +%Y-%m-%d) on $(uname -m), $(nproc) cores ($cpu)," \
         "$(c++ --version | head -n 1), Release build, pinned to one core, each benchmark" \
         "repeated five times in random order and the median taken. Regenerate with"
    echo
    echo '```{.sh}'
    echo "cmake --build build --target bench-full-ch02_rasterizers"
    echo "chapters/02-edge-functions/bench_results.sh build"
    echo '```'
    echo
    [ -z "$note" ] || { echo "$note"; echo; }
    # The generated fragment's two tables, each with its caption moved before it and
    # named as a scene; the book's own labels dropped (this file is not in the book).
    awk '
        /^\|/ { rows = rows $0 "\n"; next }
        /^: / {
            caption = $0
            sub(/ *\{#tbl:[^}]*\}/, "", caption)
            sub(/^: (Measured here: )?/, "", caption)
            scene = (++n == 1) ? "small" : "large"
            printf ": Scene \"%s\": %s\n\n%s\n", scene, caption, rows
            rows = ""
            next
        }
    ' "$scratch/ch02_speed_table.md"
    echo ": Scene \"sweep\": millions of pixels per second on one core against triangle" \
         "area (px)."
    echo
    echo "| area | float 1x1 | float 8x8 | fixed 1x1 | fixed 8x8 | naive | plain fill |"
    echo "|--:|--:|--:|--:|--:|--:|--:|"
    grep -v '^#' "$scratch/ch02_speed_sweep.dat" | awk '{
        printf "|"; for (i = 1; i <= NF; ++i) printf " %s |", $i; printf "\n" }'
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
