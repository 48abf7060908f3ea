#!/bin/sh
# The committed, dated run that the solution of chapter 8's exercise on a wall at 60
# degrees quotes (chapters/08-filtering/oblique_results.md): every filter's time per
# pixel, its ratio to nearest, its error on the minified pixels, and whether it is on the
# Pareto front (no other filter at least as fast and as accurate, and better in one).
# Usage (from the repository root, after building bench_ch08_filters):
#   taskset -c 1 build/bin/bench_ch08_filters --oblique --benchmark_repetitions=5 \
#       --benchmark_enable_random_interleaving=true --benchmark_min_time=0.1 \
#       --benchmark_out=build/bench/bench_ch08_oblique.csv --benchmark_out_format=csv
#   chapters/08-filtering/oblique.sh build ["note on the load"]
set -eu
build=${1:?usage: oblique.sh BUILD_DIR [NOTE]}
note=${2:-}
csv="$build/bench/bench_ch08_oblique.csv"
out=chapters/08-filtering/oblique_results.md
. bench/committed_run.sh
require_csv "$csv" "oblique.sh"
{
    echo "# Chapter 8's exercise: the filters on a wall at 60 degrees"
    echo
    measured_line "$csv" "\`bench_ch08_filters --oblique\`; bench/ch08_filters.cpp says what a run does"
    echo "The errors are deterministic. Regenerate with the commands at the top of" \
         "chapters/08-filtering/oblique.sh."
    echo
    [ -z "$note" ] || { echo "$note"; echo; }
    awk -F, '
        /^name,/ {
            for (i = 1; i <= NF; ++i) { h = $i; gsub(/"/, "", h); col[h] = i }
            next
        }
        $1 ~ /_median"?$/ {
            name = $1; gsub(/"/, "", name); sub(/_median$/, "", name)
            scene = name; sub(/\/.*/, "", scene); sub(/^[^\/]*\//, "", name)
            names[++n] = name; ns[name] = $col["ns_per_px"]; err[name] = $col["error"]
            minified = $col["minified"]; pixels = $col["pixels"]
        }
        END {
            if (!("nearest" in ns)) { print "oblique.sh: no nearest run" > "/dev/stderr"; exit 2 }
            printf ": Scene \"%s\": %d pixels, %d of them minified. Error: RMS difference", scene, pixels, minified
            printf " from the reference in 8-bit sRGB codes on the minified pixels; front: 1 when on the Pareto front.\n\n"
            print "| filter | ns/px | × nearest | error | front |"
            print "|:--|--:|--:|--:|--:|"
            for (a = 1; a <= n; ++a) {
                A = names[a]; front = 1
                for (b = 1; b <= n; ++b) {
                    B = names[b]
                    if (ns[B] <= ns[A] && err[B] <= err[A] && (ns[B] < ns[A] || err[B] < err[A])) front = 0
                }
                printf "| %s | %.1f | %.2f | %.2f | %d |\n", A, ns[A], ns[A] / ns["nearest"], err[A], front
            }
        }
    ' "$csv" > "$out.rows"
    # rows in the configurations' order (filter_configs), as the chapter's tables list them
    head -n 4 "$out.rows"
    for f in nearest nearest_linear-light bilinear mip-nearest trilinear trilinear_per-span trilinear_per-triangle \
             anisotropic-4 anisotropic-16 ewa; do
        grep "^| $f |" "$out.rows" || true
    done
    rm -f "$out.rows"
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
