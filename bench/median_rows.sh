#!/bin/sh
# The medians of a repeated Google Benchmark run as Markdown table rows, for the committed
# result files the chapters' claims read (book/AUTHORING.md, "Claims the build checks").
# Usage: bench/median_rows.sh RUN.csv COUNTER BASELINE
#   RUN.csv   --benchmark_out of a run with --benchmark_repetitions (its _median rows)
#   COUNTER   the user counter to report, e.g. ns_per_px
#   BASELINE  a run name; each row also gives its value over the baseline's
# Prints "| name | value | x baseline |" rows, one per run in the CSV's order, with every
# '/' of a run's name written '_' (a claim names a row as SCENE/ROW).
set -eu
csv=${1:?usage: median_rows.sh RUN.csv COUNTER BASELINE}
counter=${2:?counter}
baseline=${3:?baseline}
[ -s "$csv" ] || { echo "median_rows.sh: no $csv" >&2; exit 2; }
awk -F, -v counter="$counter" -v baseline="$(echo "$baseline" | tr / _)" '
    /^name,/ {
        for (i = 1; i <= NF; ++i) { h = $i; gsub(/"/, "", h); if (h == counter) col = i }
        if (!col) { print "median_rows.sh: no column " counter > "/dev/stderr"; exit 2 }
        next
    }
    col && $1 ~ /_median"?$/ {
        name = $1; gsub(/"/, "", name); sub(/_median$/, "", name); gsub(/\//, "_", name)
        names[++n] = name; value[name] = $col
    }
    END {
        if (!(baseline in value)) { print "median_rows.sh: no run " baseline > "/dev/stderr"; exit 2 }
        for (k = 1; k <= n; ++k) {
            name = names[k]
            printf "| %s | %.3f | %.3f |\n", name, value[name], value[name] / value[baseline]
        }
    }
' "$csv"
